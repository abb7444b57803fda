// Surfaces with known answers, for every integrator that handles them:
//  - a closed white-furnace sphere: inside a Lambertian sphere of albedo ρ whose surface emits
//    a uniform radiance Le, every ray sees L = Le Σ ρⁿ = Le/(1 − ρ) (volpath); the single-
//    scattering integrator stops at the first surface and must see exactly Le;
//  - a Lambertian floor lit by a distant light: L = ρ/π · E cos θ · S(λ) (all integrators);
//  - a caustic: a 45° mirror turns a horizontal parallel beam down onto a dark floor, which
//    then receives the beam's irradiance E; the photon integrator's caustic map must find
//    L = ρ/π · E · S(λ) there, while no shadow ray can (the direct beam grazes the floor).
#include <gtest/gtest.h>

#include <cmath>

#include "render/photon_integrator.h"
#include "spectrum/cie.h"
#include "test_support.h"

using namespace mirage;

namespace {

struct Stats {
    double mean = 0, se = 0;
};

template <typename F>
Stats meanOf(int n, F&& f) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        double v = f(i);
        sum += v;
        sum2 += v * v;
    }
    double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

RenderScene furnaceSphere(float albedo, float Le) {
    RenderScene scene;
    scene.geometry = std::make_unique<GeometryScene>();
    int m = scene.geometry->addMaterial(Material::diffuse("wall", Spectrum(albedo), Spectrum(Le)));
    scene.geometry->addSphere(Vec3(0.f), 1.f, m);
    scene.geometry->commit();
    return scene;
}

// Mean over wavelengths of L(λ) for one camera sample.
double radiance(const Integrator& integrator, const RenderScene& scene, const Ray& ray,
                uint64_t index, ThreadState& ts, Vec3* xyz = nullptr) {
    Sampler s(5, index, 0);
    SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
    ts.tracking.setWavelengths(w);
    RadianceSample r = integrator.Li(scene, ray, w, s, ts);
    if (xyz) *xyz = r.xyz;
    return r.L.average();
}

}  // namespace

TEST(SurfaceFurnace, VolPathFindsLeOverOneMinusAlbedo) {
    for (float albedo : {0.5f, 0.8f}) {
        RenderScene scene = furnaceSphere(albedo, 2.f);
        auto integrator = makeVolPathIntegrator();
        ThreadState ts(scene);
        Stats st = meanOf(40000, [&](int i) {
            Sampler s(1, uint64_t(i), 7);
            Vec3 d = sampleUniformSphere(s.get1D(), s.get1D());
            return radiance(*integrator, scene, Ray{Vec3(0.1f, -0.2f, 0.3f), d, kInfinity},
                            uint64_t(i), ts);
        });
        double expected = 2.0 / (1.0 - albedo);
        EXPECT_NEAR(st.mean, expected, 4 * st.se + 2e-3 * expected) << "albedo " << albedo;
    }
}

TEST(SurfaceFurnace, SingleScatteringSeesTheFirstSurfaceOnly) {
    RenderScene scene = furnaceSphere(0.8f, 2.f);
    auto integrator = makeSingleScatterIntegrator();
    ThreadState ts(scene);
    for (int i = 0; i < 100; ++i) {
        Sampler s(2, uint64_t(i), 0);
        Vec3 d = sampleUniformSphere(s.get1D(), s.get1D());
        EXPECT_NEAR(radiance(*integrator, scene, Ray{Vec3(0.f), d, kInfinity}, uint64_t(i), ts),
                    2.0, 1e-5);
    }
}

TEST(SurfaceDirectLight, LambertianFloorUnderADistantLight) {
    const float rho = 0.6f, E = 470.f, cosTheta = 0.8f;
    RenderScene scene;
    scene.geometry = std::make_unique<GeometryScene>();
    int m = scene.geometry->addMaterial(Material::diffuse("floor", Spectrum(rho)));
    scene.geometry->addQuad(Vec3(-5, 0, 5), Vec3(10, 0, 0), Vec3(0, 0, -10), m);
    scene.geometry->commit();
    scene.lights.push_back(
        makeDistantLight(Vec3(0.6f, -cosTheta, 0.f), E, Spectrum(1.f)));  // S(λ) = 1/470 nm⁻¹
    const double expected = rho / kPi * E * cosTheta / 470.0;
    PhotonIntegratorSettings ps;
    ps.photons = 20000;
    ps.progress = Progress::Mode::Quiet;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(scene);
    for (const char* name : {"single", "volpath"}) {
        auto integrator = makeIntegrator(name);
        ThreadState ts(scene);
        Stats st = meanOf(2000, [&](int i) {
            Ray r{Vec3(0.f, 2.f, 3.f), normalize(Vec3(0.f, -2.f, -3.f)), kInfinity};
            return radiance(*integrator, scene, r, uint64_t(i), ts);
        });
        EXPECT_NEAR(st.mean, expected, 1e-4 * expected) << name;  // one plane: no bounce back
    }
    ThreadState ts(scene);
    Vec3 xyz;
    double L = radiance(*photon, scene, Ray{Vec3(0.f, 2.f, 3.f), normalize(Vec3(0.f, -2.f, -3.f)),
                                            kInfinity},
                        0, ts, &xyz);
    EXPECT_NEAR(L, expected, 1e-4 * expected);
    EXPECT_EQ(xyz.y, 0.f);  // direct light is NEE's alone: no photon is stored for it
}

TEST(SurfaceCaustic, PhotonCausticMapFindsTheMirroredBeam) {
    const float rho = 0.1f, E = 470.f;
    RenderScene scene;
    scene.geometry = std::make_unique<GeometryScene>();
    GeometryScene& g = *scene.geometry;
    int floor = g.addMaterial(Material::diffuse("floor", Spectrum(rho)));
    int mirror = g.addMaterial(Material::mirror("mirror"));
    g.addQuad(Vec3(-3, 0, 3), Vec3(6, 0, 0), Vec3(0, 0, -6), floor);
    // A 45° mirror over x, z ∈ [−0.5, 0.5], y ∈ [0.5, 1.5]: light along +x leaves along −y.
    g.addQuad(Vec3(-0.5f, 1.5f, 0.5f), Vec3(1, -1, 0), Vec3(0, 0, -1), mirror);
    g.commit();
    scene.lights.push_back(makeDistantLight(Vec3(1, 0, 0), E, Spectrum(1.f)));
    PhotonIntegratorSettings ps;
    ps.photons = 2000000;
    ps.progress = Progress::Mode::Quiet;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(scene);
    ThreadState ts(scene);
    // Camera rays onto the floor's patch x, z ∈ [−0.3, 0.3] under the mirror.
    Stats st = meanOf(400, [&](int i) {
        Sampler s(4, uint64_t(i), 0);
        Vec3 target(-0.3f + 0.6f * s.get1D(), 0.f, -0.3f + 0.6f * s.get1D());
        Vec3 o(0.f, 0.4f, 3.f);
        Vec3 xyz;
        double L = radiance(*photon, scene, Ray{o, normalize(target - o), kInfinity}, uint64_t(i),
                            ts, &xyz);
        EXPECT_EQ(L, 0.0);  // the beam grazes the floor: no direct light
        return double(xyz.y);
    });
    // Y of a constant spectral radiance is that radiance (film normalisation).
    const double expected = rho / kPi * E / 470.0;
    EXPECT_NEAR(st.mean, expected, 0.06 * expected) << "± " << st.se;
}

// Indirect light from the global photon map. Inside a closed Lambertian sphere (radius R,
// albedo ρ) a point light of power Φ at the centre gives the wall the direct irradiance
// Φ/(4πR²); every diffuse bounce off a sphere's inside spreads uniformly over it, so the total
// is E = Φ/(4πR²(1 − ρ)) and the wall's radiance L = ρE/π everywhere. The photon integrator
// takes the first bounce by shadow rays and the rest, ρ/(1 − ρ) of it, from the global map.
TEST(SurfaceGlobal, PhotonGlobalMapFindsTheInterreflectionsOfAClosedSphere) {
    const float rho = 0.6f, power = 100.f, R = 1.f;
    RenderScene scene;
    scene.geometry = std::make_unique<GeometryScene>();
    int m = scene.geometry->addMaterial(Material::diffuse("wall", Spectrum(rho)));
    scene.geometry->addSphere(Vec3(0.f), R, m);
    scene.geometry->commit();
    scene.lights.push_back(makePointLight(Vec3(0.f), power, Spectrum(1.f)));  // S = 1/470 nm⁻¹
    const double direct = rho / kPi * power / (4 * kPi * R * R) / 470.0;
    const double expected = direct / (1.0 - rho);
    PhotonIntegratorSettings ps;
    ps.photons = 200000;
    ps.progress = Progress::Mode::Quiet;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(scene);
    auto single = makeIntegrator("single");
    ThreadState ts(scene);
    // The photon estimates arrive already reduced to XYZ (RadianceSample::xyz); for this flat
    // spectrum their Y is the radiance they add to the spectral part's mean (film
    // normalisation: a constant spectral radiance of 1 has Y = 1).
    auto viewOf = [&](const Integrator& integrator) {
        return meanOf(4000, [&](int i) {
            Sampler s(6, uint64_t(i), 0);
            Vec3 d = sampleUniformSphere(s.get1D(), s.get1D());
            Vec3 xyz;
            const double L = radiance(integrator, scene,
                                      Ray{Vec3(0.2f, 0.1f, -0.3f), d, kInfinity}, uint64_t(i),
                                      ts, &xyz);
            return L + double(xyz.y);
        });
    };
    // Shadow rays alone: the direct part, exactly (one wavelength sample's noise aside).
    Stats st = viewOf(*single);
    EXPECT_NEAR(st.mean, direct, 1e-3 * direct);
    // With the global map: within the density estimate's few per cent of the closed form, and
    // far from the direct part alone (the map holds 1.5× the direct light here).
    st = viewOf(*photon);
    EXPECT_NEAR(st.mean, expected, 0.04 * expected) << "± " << st.se;
}
