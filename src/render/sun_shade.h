// Where a sky map's sun is hidden from the media: the optical depth from points of the media
// towards the sun (Light::lobe: a dome image whose brightest 5° hold half its power), on a grid
// over the media's bounds, built with the frame. The path tracer's medium vertices that leave
// the lights at infinity to their escape draw those lights' own samples with a probability set
// by it (render/direct_light.h: SkyDraws).
//
// Why. Inside a dense cloud under such a sky most vertices lie optical depths deep on the sun's
// side: their shadow rays towards the sun, which the map's samples mostly are, find T ~ 0 and
// still cost a ratio-tracked ray each. The rule before (draw at half the rate after a drawn
// sample found no light) skipped half of those, and paid 1/rate on the vertices just coming out
// of the dark, where the sun is found again. A rate from where the vertex is — 1 where the sun's
// optical depth is small, down to kLeastRate deep inside — skips most of the deep draws and none
// of the shallow ones. The rate depends on the vertex's position alone, so its draws, counting
// 1/rate of themselves, and its escape, weighed with that rate in the power heuristic
// (skyAtEscape), stay one unbiased estimate, whatever the grid's accuracy; the grid sets only
// how well the rate follows the light.
//
// Measured on the sky-hdr regime (docs/regimes.md; 64 samples, seeds 11 and 12, relMSE against
// the reference and CPU seconds): the rule before 0.0515 and 13.3 s (7.3 M draws of the sky's
// samples); this, 0.0489 and 11.0 s (2.4 M draws): relMSE × CPU 1.27× lower. A 32³ grid, 1.18×;
// a rate of min(1, 10 e^−τ) ≥ 0.2, 1.14× (more draws: 3.8 M); of 2 e^−τ ≥ 0.05, 1.25×.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/math.h"
#include "render/render_scene.h"

namespace mirage {

class SunShade {
public:
    // The direction towards the scene's sun (its first dome with one) that forScene shades the
    // media from; none where no light has a sun, no medium has bounds or RenderScene::sunShade
    // is off.
    static std::optional<Vec3> sunOf(const RenderScene& scene);
    // The shade of that sun, or null where there is none.
    static std::unique_ptr<SunShade> forScene(const RenderScene& scene);

    // The shade of the direction `towardsSun` (unit) over the media of `scene`: res³ cells.
    SunShade(const RenderScene& scene, const Vec3& towardsSun, int res = kResolution);

    // The optical depth towards the sun from p (world), interpolated between the cells'
    // centres (trilinear, clamped at the grid's faces) and capped at kDepthCap.
    float opticalDepth(const Vec3& p) const;

    // The probability that a vertex at p draws the lights at infinity's own samples:
    // clamp(kRateScale e^−τ(p), kLeastRate, 1).
    float drawRate(const Vec3& p) const;

    static constexpr int kResolution = 64;
    static constexpr float kRateScale = 4.f, kLeastRate = 0.1f;
    // Past this optical depth the rate is kLeastRate (4 e^−3.7 = 0.1): the cells' rays stop there.
    static constexpr float kDepthCap = 5.f;

private:
    Bounds3 mBounds;
    int mRes;
    std::vector<float> mDepth;  // res³, x fastest
    float at(int x, int y, int z) const { return mDepth[(size_t(z) * mRes + y) * mRes + x]; }
};

}  // namespace mirage
