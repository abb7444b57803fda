// Emissive surfaces as a light (light/surface_light.h, scene/light_loader.h addSurfaceLight,
// render/direct_light.cpp): a 1 m² emissive quad over a floor and a box of fog gives the same
// radiance along camera rays as the `quad` light type of the same radiance — by volpath
// (next-event estimation with multiple importance sampling, the hits after a bounce left out)
// and by the photon integrator (photons from both sides of the surface, half lost upwards) —
// and its samples' pdf is the one a ray that hits it is weighed with.
#include "light/surface_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/photon_integrator.h"
#include "scene/light_loader.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr float kRadiance = 0.02f;  // W·m⁻²·sr⁻¹·nm⁻¹, flat over 360–830 nm
const Vec3 kCorner(0.f, 1.5f, 0.f), kEdgeU(1.f, 0.f, 0.f), kEdgeV(0.f, 0.f, 1.f);  // faces −y

// A grey floor at y = 0 and a box of fog over [0, 1]³; lit by a quad light, or by an emissive
// quad where the light was.
RenderScene floorAndFog(bool emissiveQuad) {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, 1.0 / 32, 0.2f, 1.f, 0.5f));
    scene.geometry = std::make_unique<GeometryScene>();
    const int grey = scene.geometry->addMaterial(Material::diffuse("floor", Spectrum(0.5f)));
    scene.geometry->addQuad(Vec3(-2.f, 0.f, -2.f), Vec3(4.f, 0.f, 0.f), Vec3(0.f, 0.f, 4.f), grey);
    if (emissiveQuad) {
        const int lamp = scene.geometry->addMaterial(
            Material::diffuse("lamp", Spectrum(0.f), Spectrum(kRadiance)));
        scene.geometry->addQuad(kCorner, kEdgeU, kEdgeV, lamp);
        // What readGeometry collects of a scene file's emissive quad.
        EmissiveTriangles tris;
        const Vec3 a = kCorner, b = kCorner + kEdgeU, c = b + kEdgeV, d = kCorner + kEdgeV;
        tris.vertices = {a, b, c, a, c, d};
        tris.emitter = {lamp, lamp};
        tris.radiance = {Spectrum(0.f), Spectrum(kRadiance)};
        tris.shapes = {false, true};
        addSurfaceLight(std::move(tris), &scene);
    } else {
        // L = Φ / (π A) × S(λ) / ∫ S dλ with S flat: Φ = π A L × 470 nm.
        const float power = kPi * 1.f * kRadiance * float(kLambdaMax - kLambdaMin);
        scene.lights.push_back(makeQuadLight(kCorner, kEdgeU, kEdgeV, power, Spectrum(1.f)));
    }
    scene.geometry->commit();
    return scene;
}

const Ray kRays[] = {
    {Vec3(0.5f, 0.5f, 3.f), normalize(Vec3(0.f, -0.3f, -2.5f)), kInfinity},  // fog, then floor
    {Vec3(2.5f, 1.f, 2.5f), normalize(Vec3(-1.f, -1.f, -1.f)), kInfinity},   // the floor beside
};

}  // namespace

TEST(SurfaceLight, SamplesAndHitsAgreeOnThePdf) {
    RenderScene scene = floorAndFog(true);
    ASSERT_EQ(scene.lights.size(), 1u);
    const SurfaceLight* found = surfaceLightOf(*scene.lights[0]);
    ASSERT_TRUE(found);
    const SurfaceLight& light = *found;
    EXPECT_TRUE(light.samples(1));
    EXPECT_FALSE(light.samples(0));
    EXPECT_EQ(scene.lightGroupSlot(0), 0);  // emission's slot
    // Two-sided: π L A on each side.
    EXPECT_NEAR(light.emittedPower(Bounds3{}), 2 * kPi * kRadiance * 470.0, 1e-3);
    const Vec3 p(0.3f, 0.2f, 0.6f);
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    Sampler s(3, 0, 0);
    test::SampleMean e;
    for (int i = 0; i < 20000; ++i) {
        LightSample ls;
        const float u1 = s.get1D(), u2 = s.get1D();
        ASSERT_TRUE(light.sampleLi(p, u1, u2, w, &ls));
        const Vec3 q = p + ls.wi * ls.distance;
        ASSERT_NEAR(q.y, 1.5f, 1e-5f);
        const float pdf = light.pdfAt(1, p, q, Vec3(0.f, -1.f, 0.f));
        ASSERT_NEAR(ls.pdf, pdf, 1e-4f * pdf);
        ASSERT_NEAR(ls.Li[0] * ls.pdf, kRadiance, 1e-6f);
        e.add(ls.Li[0] * ls.wi.y);  // irradiance on a surface facing up
    }
    // E = L × the quad's projected solid angle: the form factor of a unit square 1.3 m above p
    // by quadrature.
    double expected = 0.0;
    const int n = 400;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const Vec3 q = kCorner + kEdgeU * ((a + 0.5f) / n) + kEdgeV * ((b + 0.5f) / n);
            const Vec3 d = q - p;
            const double d2 = dot(d, d), c = d.y / std::sqrt(d2);
            expected += kRadiance * c * c / d2 / (double(n) * n);
        }
    EXPECT_NEAR(e.mean(), expected, 4 * e.standardError());
}

TEST(SurfaceLight, EmissiveQuadLightsLikeTheQuadLight) {
    const RenderScene quad = floorAndFog(false), emissive = floorAndFog(true);
    auto volpath = makeVolPathIntegrator();
    for (const Ray& ray : kRays) {
        const test::RayEstimate a = test::estimateAlongRay(*volpath, quad, ray, 40000);
        const test::RayEstimate b = test::estimateAlongRay(*volpath, emissive, ray, 40000);
        std::printf("volpath: quad light %.5g ± %.2g, emissive quad %.5g ± %.2g\n", a.mean, a.se,
                    b.mean, b.se);
        ASSERT_GT(a.mean, 0.0);
        EXPECT_NEAR(b.mean, a.mean, 4 * std::hypot(a.se, b.se));
    }
}

TEST(SurfaceLight, PhotonsFromAnEmissiveQuadMatchTheQuadLights) {
    // The same photon estimates, each within its noise: the emissive quad sends half its
    // photons up (lost), so it gets twice the photons.
    const RenderScene quad = floorAndFog(false), emissive = floorAndFog(true);
    auto estimate = [](const RenderScene& scene, uint64_t photons, const Ray& ray) {
        PhotonIntegratorSettings settings;
        settings.photons = photons;
        settings.progress = Progress::Mode::Quiet;
        auto integrator = makePhotonIntegrator(settings);
        integrator->preprocess(scene);
        return test::estimateAlongRay(*integrator, scene, ray, 4000);
    };
    for (const Ray& ray : kRays) {
        const test::RayEstimate a = estimate(quad, 200000, ray);
        const test::RayEstimate b = estimate(emissive, 400000, ray);
        std::printf("photon: quad light %.5g ± %.2g, emissive quad %.5g ± %.2g\n", a.mean, a.se,
                    b.mean, b.se);
        ASSERT_GT(a.mean, 0.0);
        EXPECT_NEAR(b.mean, a.mean, 4 * std::hypot(a.se, b.se) + 0.05 * a.mean);
    }
}
