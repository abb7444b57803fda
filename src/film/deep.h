// Deep output (docs/aovs.md, "Deep EXR"): per pixel, the stretches of volume and the surfaces
// along the camera ray, instead of their sum, so that a compositor can put the smoke behind a
// character it never saw.
//
// A camera sample records where along the ray its light comes from (DeepSample: radiance at a
// distance t, from the integrators' one place of adding, render/integrator.h) and where its
// coverage builds up (the camera ray's ratio-tracked walk, render/camera_ray_data.h, scaled to
// the sample's alpha). A pixel's events, over all its samples, are sorted by t and merged into
// deep samples while a sample's alpha stays within alphaTolerance and its colour within
// colorTolerance of the pixel's (3Delight's defaults, 0.02): dense smoke gives tens of samples,
// not thousands. Surfaces are point samples (Z = ZBack).
//
// Each merged sample k holds coverage A_k and colour C_k (the pixel's means). With the
// transmittance in front of it, T_k = 1 − Σ_{i<k} A_i, its deep alpha is α_k = A_k / T_k and
// its premultiplied colour c_k = C_k / T_k; then 1 − α_i = T_{i+1} / T_i telescopes, and
// over-compositing front to back, Σ_k c_k Π_{i<k} (1 − α_i) = Σ_k C_k, is the beauty, and
// 1 − Π (1 − α_k) its alpha: flattening gives the beauty to float rounding.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/matrix.h"
#include "core/spectral.h"

namespace mirage {

// Where along the camera ray a contribution belongs: distance t (m) and whether it is a
// surface's (a point sample). t = NaN: not placed; the pixel puts it where the sample's
// coverage reaches one half (a photon estimate gathered along the whole ray).
struct DeepAt {
    float t;
    bool surface = false;
};

// What one camera sample records.
struct DeepSample {
    struct Radiance {
        DeepAt at;
        SampledSpectrum L;  // spectral, at the sample's wavelengths
        Vec3 xyz;           // already XYZ (photon estimates)
    };
    struct Coverage {
        DeepAt at;
        float alpha;
    };
    std::vector<Radiance> radiance;
    std::vector<Coverage> coverage;

    void reset() {
        radiance.clear();
        coverage.clear();
    }
};

struct DeepSettings {
    std::string path;  // "" = no deep output
    float alphaTolerance = 0.02f;
    float colorTolerance = 0.02f;
};

// One deep sample: Z, ZBack (m along the camera ray), premultiplied colour and alpha. The
// colour is CIE XYZ as rendered, working-space RGB once DeepFilm::develop has run.
struct DeepPoint {
    float z, zBack;
    float rgba[4];
};

// The events of one pixel's samples, merged when the pixel is done.
class DeepPixel {
public:
    // Adds a sample whose coverage events sum to `alpha`'s share as the walk saw it: they are
    // scaled to sum to alpha (the beauty's own estimate), and its radiance reduced to XYZ.
    void addSample(const DeepSample& s, const SampledWavelengths& w, float alpha);
    // The merged deep samples (XYZ); `samples` is the pixel's count of valid samples, which
    // the sums are divided by.
    std::vector<DeepPoint> merge(const DeepSettings& settings, uint32_t samples) const;
    void clear() { mEvents.clear(); }

private:
    struct Event {
        float t;
        bool surface;
        float alpha;
        Vec3 xyz;
    };
    std::vector<Event> mEvents;
};

// A frame's deep samples, pixel by pixel.
class DeepFilm {
public:
    DeepFilm(int width, int height)
        : mWidth(width), mHeight(height), mPixels(size_t(width) * size_t(height)) {}
    void setPixel(int x, int y, std::vector<DeepPoint> points) {
        mPixels[size_t(y) * mWidth + x] = std::move(points);
    }
    const std::vector<DeepPoint>& pixel(int x, int y) const {
        return mPixels[size_t(y) * mWidth + x];
    }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    double meanSamples() const;
    size_t maxSamples() const;
    // XYZ → the working space (a linear map: premultiplied colours stay premultiplied).
    void develop(const Mat3& toWorking);

private:
    int mWidth, mHeight;
    std::vector<std::vector<DeepPoint>> mPixels;
};

// Writes an OpenEXR deep scanline image (Nuke's DeepRead takes scanline, not tiled): channels
// R G B A (half or float) and Z, ZBack (float), atomically; `metadata` as mirage:<key>. Throws
// MirageError naming the path.
void writeDeepExr(const std::string& path, const DeepFilm& film, bool halfFloat,
                  const std::string& colorSpace,
                  const std::map<std::string, std::string>& metadata);

// Reads one back (tests): per pixel, its samples.
DeepFilm readDeepExr(const std::string& path);

}  // namespace mirage
