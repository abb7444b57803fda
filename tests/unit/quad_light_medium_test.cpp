// A quad light inside a forward-scattering medium: next-event estimation samples the quad in
// solid angle and by the phase function, combined by multiple importance sampling
// (render/direct_light.cpp). The single-scattered radiance along a camera ray that passes
// 5 cm under the light must match an independent quadrature of the single-scattering integral
// over the ray and the quad's area, for an isotropic and a strongly forward lobe (HG g = 0.9),
// and the forward lobe's estimate must stay tame there (the speckles it made before).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "medium/phase.h"
#include "render/renderer.h"
#include "test_support.h"
#include "volume/grid_lookup.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;
constexpr float kSigmaA = 0.2f, kSigmaS = 1.f, kPower = 50.f;
const Vec3 kCorner(0.3f, 0.6f, 0.3f), kEdgeU(0.3f, 0.f, 0.f), kEdgeV(0.f, 0.f, 0.3f);

RenderScene lightInFog(float g) {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, kSigmaA, kSigmaS, g));
    // Edge_u × edge_v = −y: the quad emits downwards.
    scene.lights.push_back(makeQuadLight(kCorner, kEdgeU, kEdgeV, kPower, Spectrum(1.f)));
    return scene;
}

// Optical depth between two points by the midpoint rule on the grid's own trilinear field.
double opticalDepth(const FloatGrid& grid, const Vec3& a, const Vec3& b) {
    auto acc = grid.accessor();
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += grid.sample(acc, a + (b - a) * ((i + 0.5f) / n));
    return (kSigmaA + kSigmaS) * sum * length(b - a) / n;
}

}  // namespace

TEST(QuadLightInMedium, SingleScatteringMatchesQuadratureForwardLobeIncluded) {
    // The camera ray along +x at y = 0.55, z = 0.45: under the quad (y = 0.6) by 5 cm.
    const Ray ray{Vec3(-0.2f, 0.55f, 0.45f), Vec3(1, 0, 0), kInfinity};
    const Vec3 n(0, -1, 0);
    const double L = kPower / (kPi * 0.09) / double(kLambdaMax - kLambdaMin);
    for (float g : {0.f, 0.9f}) {
        SCOPED_TRACE("g = " + std::to_string(g));
        RenderScene scene = lightInFog(g);
        const FloatGrid& grid = scene.media[0]->binding().grids()[0];
        auto acc = grid.accessor();
        const HGPhase hg(g);
        // ∫ dt T_cam σs ρ ∫_A L p(cosθ) T_light cosθ_l / d² dA, on 240 × 40² points.
        double expected = 0.0, tauCam = 0.0;
        const int nt = 240, na = 40;
        const double t0 = 0.0, t1 = 1.4, dt = (t1 - t0) / nt;
        for (int i = 0; i < nt; ++i) {
            const Vec3 p = ray.at(float(t0 + (i + 0.5) * dt));
            const double density = grid.sample(acc, p);
            if (density > 0) {
                double in = 0.0;
                for (int a = 0; a < na; ++a)
                    for (int b = 0; b < na; ++b) {
                        const Vec3 q =
                            kCorner + kEdgeU * ((a + 0.5f) / na) + kEdgeV * ((b + 0.5f) / na);
                        const Vec3 d = q - p;
                        const double d2 = dot(d, d), dist = std::sqrt(d2);
                        const double cosL = -dot(d, n) / dist;
                        if (cosL <= 0) continue;
                        // Light travels along −d into p and on to the camera along −x.
                        const double cosT = dot(-d / float(dist), -ray.d);
                        in += L * hg.eval(float(cosT)) * std::exp(-opticalDepth(grid, p, q)) *
                              cosL / d2;
                    }
                in *= 0.09 / (na * na);
                expected += std::exp(-tauCam) * kSigmaS * density * in * dt;
            }
            tauCam += (kSigmaA + kSigmaS) * density * dt;
        }
        const test::RayEstimate e =
            test::estimateAlongRay(*makeSingleScatterIntegrator(), scene, ray, 40000);
        const double mean = e.mean, se = e.se, largest = e.largest;
        EXPECT_NEAR(mean, expected, 4 * se + 0.01 * expected) << "± " << se;
        std::printf("g %.1f: mean %.5g (quadrature %.5g), largest sample %.1f × the mean\n", g,
                    mean, expected, largest / mean);
        // Tame: no sample above 60 times the mean (the light's area samples alone have no
        // bound here, L A cosθ_l / d², and the forward lobe multiplies them by up to 15/sr).
        EXPECT_LT(largest, 60 * mean) << "largest sample " << largest << ", mean " << mean;
    }
}
