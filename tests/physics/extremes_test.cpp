// The extremes matrix: every knob pushed to its end must leave the image finite,
// the energy within what a furnace allows, the time bounded (caps counted), and the answer on
// the closed form where one exists.
//
// Closed forms used:
//   albedo 0, a parallel ray through a slab of optical depth τ: coverage α = 1 − e^{−τ},
//     radiance 0 (Beer–Lambert; nothing scatters or emits).
//   furnace (furnace_test.cpp): inside a deep, uniform, emitting medium L = Le for any albedo
//     below 1 and any phase function (Kirchhoff); L ≤ Le always; L = 0 for albedo 1 (σa = 0).
// The slab limits (thin → single scattering, thick → adding-doubling, albedo 0 → Beer–Lambert)
// are in extremes_slab_test.cpp. Everything here runs through the library API.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

#include "core/error.h"
#include "film/color.h"
#include "film/image_io.h"
#include "photon/photon_pass.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "spectrum/spectrum.h"
#include "test_grids.h"
#include "test_support.h"
#include "volume/vdb_file.h"

using namespace mirage;

namespace {

// Not-a-number guard for every developed pixel (RGB and alpha) and alpha in [0, 1].
void expectFiniteImage(const Image& image, const std::string& what) {
    int bad = 0;
    for (size_t i = 0; i < image.rgba.size(); ++i) {
        float v = image.rgba[i];
        if (!std::isfinite(v) || (i % 4 == 3 && (v < 0.f || v > 1.f + 1e-6f))) ++bad;
    }
    EXPECT_EQ(bad, 0) << what << ": " << bad << " non-finite or out-of-range values";
}

const ColorPipeline& colour() {
    static ColorPipeline c;
    return c;
}

struct Rendered {
    Image image;
    RenderStats stats;
    uint64_t capped = 0, nonFinitePhotons = 0;
};

// Renders `scene` with `name` ("single", "volpath", "photon") framed on its bounds.
Rendered renderWith(RenderScene& scene, const std::string& name, int w = 8, int h = 8,
                    int spp = 2, PhotonIntegratorSettings photon = {}) {
    if (scene.lights.empty())
        scene.lights.push_back(makeDistantLight(Vec3(0.3f, -1.f, -0.2f), 1000.f, Spectrum(1.f)));
    scene.camera = frameBounds(scene.bounds(), 40.f, float(w) / float(h));
    photon.progress = Progress::Mode::Quiet;
    photon.maxBounces = 1000;
    auto integrator = makeIntegrator(name, 1000, photon);
    integrator->preprocess(scene);
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.spp = spp;
    s.tileSize = 4;
    s.progress = Progress::Mode::Quiet;
    Rendered r;
    Film film = render(scene, *integrator, s, &r.stats);
    r.image = film.develop(colour());
    const IntegratorStats is = integrator->stats();
    r.capped = is.cappedPaths + r.stats.cappedFlights + is.cappedPhotonPaths;
    r.nonFinitePhotons = is.nonFinitePhotons;
    return r;
}

void expectFiniteWithEveryIntegrator(RenderScene& scene, const std::string& what) {
    for (const char* name : {"single", "volpath", "photon"}) {
        PhotonIntegratorSettings p;
        p.photons = 2000;
        Rendered r = renderWith(scene, name, 8, 8, 2, p);
        expectFiniteImage(r.image, what + " / " + name);
        EXPECT_EQ(r.stats.nonFiniteSamples, 0u) << what << " / " << name;
        EXPECT_EQ(r.nonFinitePhotons, 0u) << what << " / " << name;
    }
}

// A cube of uniform density 1 on [0, n·h]³ (voxel centres), grey σa, σs.
std::unique_ptr<Medium> cube(float sigmaA, float sigmaS, float g = 0.f, double h = 1.0 / 16,
                             int n = 16, const Transform& xf = Transform()) {
    return test::gridMedium([](int, int, int) { return 1.f; }, 0, n - 1, h, sigmaA, sigmaS, g,
                            xf);
}

// Mean coverage α and radiance of rays parallel to +x through the middle of a medium whose
// object bounds are `box` (world = object unless a transform is given), by `integrator`.
std::pair<double, double> parallelRays(const Integrator& integrator, const RenderScene& scene,
                                       const Bounds3& box, int n) {
    ThreadState ts(scene);
    double alpha = 0, L = 0;
    Vec3 c = box.center(), e = box.hi - box.lo;
    for (int i = 0; i < n; ++i) {
        Sampler s(5, uint64_t(i), 0);
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        // Within the middle half of the face, away from the dilated edge voxels.
        Vec3 o(box.lo.x - 1.f, c.y + (s.get1D() - 0.5f) * 0.5f * e.y,
               c.z + (s.get1D() - 0.5f) * 0.5f * e.z);
        RadianceSample r = integrator.Li(scene, Ray{o, Vec3(1, 0, 0), kInfinity}, w, s, ts);
        alpha += r.alpha;
        L += r.L.average();
    }
    return {alpha / n, L / n};
}

// Optical depth along x of cube(): the grid's trilinear density is 1 from the first voxel
// centre to the last ((n − 1)·h) and ramps linearly to 0 over one voxel at each end, adding
// half a voxel each side: n·h in all.
double cubeDepth(float sigmaT, double h = 1.0 / 16, int n = 16) { return sigmaT * n * h; }

}  // namespace

// ---- Media: σt, albedo, g ---------------------------------------------------------------

TEST(Extremes, SigmaTZeroIsTransparentAndBlack) {
    RenderScene scene;
    scene.media.push_back(cube(0.f, 0.f));
    for (const char* name : {"single", "volpath", "photon"}) {
        Rendered r = renderWith(scene, name);
        expectFiniteImage(r.image, name);
        for (float v : r.image.rgba) EXPECT_EQ(v, 0.f) << name;
    }
}

TEST(Extremes, ThinAndHugeSigmaTInOneScene) {
    RenderScene scene;
    scene.media.push_back(cube(0.5e-6f, 0.5e-6f));
    scene.media.push_back(cube(0.1e6f, 0.9e6f, 0.f, 1.0 / 16, 16,
                               Transform::translate(Vec3d(1.5, 0.0, 0.0))));
    expectFiniteWithEveryIntegrator(scene, "σt 1e-6 and 1e6");
    auto volpath = makeVolPathIntegrator();
    // The huge cube is opaque (τ = 1e6), the thin one transparent (α = 1 − e^{−1e-6}).
    auto [aHuge, lHuge] = parallelRays(*volpath, scene, scene.media[1]->worldBounds(), 200);
    EXPECT_EQ(aHuge, 1.0);
    EXPECT_TRUE(std::isfinite(lHuge));
    RenderScene thin;
    thin.media.push_back(cube(0.5e-6f, 0.5e-6f));
    auto [aThin, lThin] = parallelRays(*volpath, thin, thin.media[0]->worldBounds(), 2000);
    EXPECT_LT(aThin, 1e-3);  // 2000 rays: any absorption event would show as ≥ 5e-4
    EXPECT_EQ(lThin, 0.0);   // no light in this scene
}

TEST(Extremes, AlbedoZeroIsPureAbsorption) {
    for (float sigmaT : {0.5f, 2.f, 8.f}) {
        RenderScene scene;
        scene.media.push_back(cube(sigmaT, 0.f));
        scene.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 1000.f, Spectrum(1.f)));
        const double expected = 1.0 - std::exp(-cubeDepth(sigmaT));
        for (const char* name : {"single", "volpath"}) {
            auto integrator = makeIntegrator(name);
            const int n = 20000;
            auto [alpha, L] = parallelRays(*integrator, scene, scene.media[0]->worldBounds(), n);
            double se = std::sqrt(expected * (1 - expected) / n);
            EXPECT_NEAR(alpha, expected, 4 * se) << name << " σt " << sigmaT;
            EXPECT_EQ(L, 0.0) << name << " σt " << sigmaT;  // nothing scatters, nothing emits
        }
        // The photon pass stores nothing: every photon is absorbed at its first collision.
        PhotonPassSettings ps;
        ps.photons = 5000;
        ps.progress = Progress::Mode::Quiet;
        PhotonPassStats stats;
        PhotonList photons = tracePhotons({scene.lights[0].get()}, scene.mediaPointers(), ps,
                                          &stats);
        EXPECT_EQ(photons.size(), 0u);
        EXPECT_EQ(stats.cappedPaths, 0u);
    }
}

TEST(Extremes, AlbedoOnePhotonPathsStillEnd) {
    // No absorption at all: every photon must still leave the finite medium (σt = 20/m, 1 m:
    // ~400 scattering events each) well below the cap.
    RenderScene scene;
    scene.media.push_back(cube(0.f, 20.f, 0.f));
    scene.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 1000.f, Spectrum(1.f)));
    PhotonPassSettings ps;
    ps.photons = 4000;
    ps.storeFirstInteraction = true;
    ps.progress = Progress::Mode::Quiet;
    PhotonPassStats stats;
    PhotonList photons =
        tracePhotons({scene.lights[0].get()}, scene.mediaPointers(), ps, &stats);
    EXPECT_EQ(stats.cappedPaths, 0u);
    EXPECT_EQ(stats.nonFinite, 0u);
    // Every photon that reaches the cube scatters at least once (nothing absorbs).
    std::printf("albedo 1: %zu photons stored from %llu emitted\n", photons.size(),
                (unsigned long long)ps.photons);
    EXPECT_GT(photons.size(), ps.photons);
    expectFiniteWithEveryIntegrator(scene, "albedo 1");
}

// Emission at 1 K, 300 K, 1500 K and 1e5 K, albedo 0, 0.5 and 1, g = −0.999, 0, 0.999 inside a
// deep furnace: L/Le → 1 (albedo < 1), L = 0 where the model has no emission (albedo 1: σa = 0;
// below EmissionSpec::minTemperature, 500 K, where B is < 1e-9 of its 1500 K value in the
// visible), never non-finite.
TEST(Extremes, FurnaceMatrixTemperatureAlbedoAndAnisotropy) {
    const float sigmaT = 20.f;
    for (float T : {1.f, 300.f, 1500.f, 1e5f})
        for (float albedo : {0.f, 0.5f, 1.f})
            for (float g : {-0.999f, 0.f, 0.999f}) {
                RenderScene scene;
                ShaderDesc s = test::greyShader(sigmaT * (1 - albedo), sigmaT * albedo, g);
                EmissionSpec e;
                e.temperatureGrid = "temperature";
                s.emission = e;
                Vec3d origin(-1.0);
                auto one = [](int, int, int) { return 1.f; };
                auto hot = [T](int, int, int) { return T; };
                std::vector<FloatGrid> grids{
                    test::makeGrid(one, 0, 31, 1.0 / 16, origin, "density"),
                    test::makeGrid(hot, 0, 31, 1.0 / 16, origin, "temperature")};
                scene.media.push_back(
                    std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 8));
                auto integrator = makeVolPathIntegrator(100000);
                ThreadState ts(scene);
                const int n = 600;
                double sum = 0, sum2 = 0;
                bool finite = true, zero = true;
                for (int i = 0; i < n; ++i) {
                    Sampler smp(11, uint64_t(i), 0);
                    SampledWavelengths w = SampledWavelengths::sampleVisible(smp.get1D());
                    ts.tracking.setWavelengths(w);
                    Vec3 d = sampleUniformSphere(smp.get1D(), smp.get1D());
                    RadianceSample r =
                        integrator->Li(scene, Ray{Vec3(0.01f, 0.02f, 0.03f), d, kInfinity}, w,
                                       smp, ts);
                    finite &= r.L.isFinite();
                    double ratio = 0;
                    for (int k = 0; k < kSpectrumSamples; ++k) {
                        zero &= r.L[k] == 0.f;
                        double le = planck(w.lambda[k], T) * 1e-9;
                        if (le > 0) ratio += r.L[k] / le / kSpectrumSamples;
                    }
                    sum += ratio;
                    sum2 += ratio * ratio;
                }
                const std::string cell = "T " + std::to_string(T) + " albedo " +
                                         std::to_string(albedo) + " g " + std::to_string(g);
                EXPECT_TRUE(finite) << cell;
                EXPECT_EQ(integrator->stats().cappedPaths, 0u) << cell;
                if (T <= EmissionSpec().minTemperature || albedo == 1.f) {
                    EXPECT_TRUE(zero) << cell;
                    continue;
                }
                double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                // Leakage through the walls: below 1e-3 for these depths (furnace_test.cpp).
                EXPECT_NEAR(mean, 1.0, 4 * se + 2e-3) << cell << " ± " << se;
            }
}

// Fluorescence at Γ = 0 and Γ = 1 (every absorbed photon re-emitted): images finite through
// every integrator, photon paths end, and no photon ever carries more than the Φ/N it left the
// light with (re-emission scales power by λi/λo ≤ 1: energy is never created).
TEST(Extremes, FluorescenceAtGammaZeroAndOne) {
    size_t stored[2] = {0, 0};
    for (float gamma : {0.f, 1.f}) {
        ShaderDesc s = test::greyShader(0.f, 1.f, 0.3f);
        MediumComponent pigment;
        pigment.name = "pigment";
        pigment.grid = "density";
        pigment.sigmaA = Spectrum(3.f);
        pigment.quantumEfficiency = gamma;
        s.components.push_back(pigment);
        RenderScene scene;
        scene.media.push_back(std::make_unique<Medium>(
            s, std::vector<FloatGrid>{test::makeGrid([](int, int, int) { return 1.f; }, 0, 15,
                                                     1.0 / 16)},
            Transform(), 1.f, 8));
        const float irradiance = 1000.f;
        scene.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), irradiance, Spectrum(1.f)));
        expectFiniteWithEveryIntegrator(scene, "Γ " + std::to_string(gamma));

        PhotonPassSettings ps;
        ps.photons = 20000;
        ps.storeFirstInteraction = true;
        ps.maxBounces = 1000;
        ps.progress = Progress::Mode::Quiet;
        PhotonPassStats stats;
        PhotonList photons =
            tracePhotons({scene.lights[0].get()}, scene.mediaPointers(), ps, &stats);
        const Bounds3 b = scene.media[0]->worldBounds();
        const double phiPerPhoton =
            double(scene.lights[0]->emittedPower(b)) / double(ps.photons);
        double maxPower = 0;
        for (const Photon& ph : photons) maxPower = std::max(maxPower, double(ph.power));
        EXPECT_GT(photons.size(), 0u);
        EXPECT_LE(maxPower, phiPerPhoton * (1 + 1e-5)) << "Γ " << gamma;
        EXPECT_EQ(stats.cappedPaths, 0u) << "Γ " << gamma;
        EXPECT_EQ(stats.nonFinite, 0u) << "Γ " << gamma;
        stored[gamma > 0.f] = photons.size();
    }
    // At Γ = 1 an absorption no longer ends a photon: its walk goes on and stores more.
    EXPECT_GT(stored[1], stored[0]);
}

// ---- Grids: bad voxels, empty, one voxel, voxel sizes, transforms -----------------------

TEST(Extremes, GridsWithNanInfNegativeAndHugeVoxelsRenderFinite) {
    const std::string path = test::tempDir() + "/hostile_values.vdb";
    TestGridSpec spec;
    const double inf = std::numeric_limits<double>::infinity();
    // A 4³ block of density 1 with hostile values scattered through it.
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) spec.voxels.push_back({i, j, k, 1.0});
    spec.voxels[1].value = std::nan("");
    spec.voxels[5].value = inf;
    spec.voxels[9].value = -inf;
    spec.voxels[13].value = -2.0;
    spec.voxels[21].value = 1e30;
    spec.voxelSize = 0.25;
    writeTestGrid(path, spec);
    testing::internal::CaptureStderr();
    FloatGrid grid = loadFloatGrid(path, "density");
    std::string warning = testing::internal::GetCapturedStderr();
    EXPECT_EQ(grid.sanitizedVoxels(), 5u);
    EXPECT_EQ(grid.maxValue(), kMaxVoxelValue);
    EXPECT_NE(warning.find("grid 'density'"), std::string::npos) << warning;
    EXPECT_NE(warning.find("3 voxels were negative or NaN"), std::string::npos) << warning;
    EXPECT_NE(warning.find("2 voxels were +inf or above 1e+10"), std::string::npos) << warning;

    // The clamped voxel is σt = 1e10/m: its majorant cell is that dense, and flights through
    // the cell's thin part end at the collision cap (counted). 4×4 pixels keep that quick.
    RenderScene scene;
    std::vector<FloatGrid> grids{grid};
    scene.media.push_back(
        std::make_unique<Medium>(test::greyShader(0.1f, 0.9f), grids, Transform(), 1.f, 16));
    for (const char* name : {"single", "volpath", "photon"}) {
        PhotonIntegratorSettings p;
        p.photons = 500;
        Rendered r = renderWith(scene, name, 4, 4, 1, p);
        expectFiniteImage(r.image, std::string("hostile voxels / ") + name);
        EXPECT_EQ(r.stats.nonFiniteSamples, 0u) << name;
        EXPECT_EQ(r.nonFinitePhotons, 0u) << name;
        std::printf("hostile voxels, %s: %llu capped paths\n", name,
                    (unsigned long long)r.capped);
    }

    // σt = density_scale × grid max × cross-section beyond 1e30 1/m is refused, naming the
    // shader, component and grid.
    try {
        Medium m(test::greyShader(1e10f, 1e10f), grids, Transform(), 1e12f, 4);
        ADD_FAILURE() << "an overflowing σ product was accepted";
    } catch (const MirageError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("shader 'test'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("grid 'density'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("1e+30"), std::string::npos) << msg;
    }
}

TEST(Extremes, EmptyGridIsRefusedAndSingleVoxelRenders) {
    auto none = [](int, int, int) { return 0.f; };
    std::vector<FloatGrid> empty{test::makeGrid(none, 0, 7, 0.1)};
    try {
        Medium m(test::greyShader(0.5f, 0.5f), empty, Transform(), 1.f, 8);
        ADD_FAILURE() << "an empty grid made a medium";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("no extent"), std::string::npos) << e.what();
    }
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 5.f; }, 3, 3, 0.1, 1.f, 9.f, 0.5f));
    expectFiniteWithEveryIntegrator(scene, "one voxel");
}

TEST(Extremes, VoxelSizesFromTenMicronsToTenKilometres) {
    for (double h : {1e-5, 1e4}) {
        // σt per world metre: 1e5/m across 16 voxels of 1e-5 m is τ = 16; 1e-4/m across
        // 16 voxels of 1e4 m is τ = 16 as well. Albedo 0: α = 1 − e^{−16} ≈ 1.
        float sigmaT = float(1.0 / h);
        RenderScene scene;
        scene.media.push_back(cube(sigmaT, 0.f, 0.f, h));
        auto volpath = makeVolPathIntegrator();
        auto [alpha, L] = parallelRays(*volpath, scene, scene.media[0]->worldBounds(), 400);
        EXPECT_NEAR(alpha, 1.0 - std::exp(-cubeDepth(sigmaT, h)), 1e-3) << "h " << h;
        EXPECT_EQ(L, 0.0);
        RenderScene lit;
        lit.media.push_back(cube(0.1f * sigmaT, 0.9f * sigmaT, 0.3f, h));
        expectFiniteWithEveryIntegrator(lit, "voxel size " + std::to_string(h));
    }
}

TEST(Extremes, NonUniformAndMirroringTransformsKeepOpticalDepthPerWorldMetre) {
    // σ is per world metre: stretching the cube ×2 along x doubles the optical depth along x;
    // mirroring it (determinant −1) changes nothing.
    const float sigmaT = 0.5f;
    struct Case {
        Transform xf;
        double stretch;
        const char* name;
    };
    for (const Case& c : {Case{Transform::scale(Vec3d(2.0, 0.5, 3.0)), 2.0, "scale (2, 0.5, 3)"},
                          Case{Transform::scale(Vec3d(-1.0, 1.0, 1.0)), 1.0, "mirror x"},
                          Case{Transform::scale(Vec3d(-1.0, -1.0, -1.0)), 1.0, "point reflection"}}) {
        RenderScene scene;
        scene.media.push_back(cube(sigmaT, 0.f, 0.f, 1.0 / 16, 16, c.xf));
        auto volpath = makeVolPathIntegrator();
        const int n = 20000;
        auto [alpha, L] = parallelRays(*volpath, scene, scene.media[0]->worldBounds(), n);
        double expected = 1.0 - std::exp(-cubeDepth(sigmaT) * c.stretch);
        EXPECT_NEAR(alpha, expected, 4 * std::sqrt(expected * (1 - expected) / n)) << c.name;
        EXPECT_EQ(L, 0.0);
        RenderScene lit;
        lit.media.push_back(cube(0.2f, 1.8f, 0.5f, 1.0 / 16, 16, c.xf));
        expectFiniteWithEveryIntegrator(lit, c.name);
    }
}

// ---- Caps and guards --------------------------------------------------------------------

TEST(Extremes, CollisionCapBoundsADegenerateMajorantAndIsCounted) {
    // One voxel of density 1e6 and one of 1e-6 eight metres away, in one majorant cell: the
    // majorant is 1e6/m over the whole cell, ~1e6 tentative collisions per metre of flight
    // through its empty part.
    auto twoVoxels = [](int i, int j, int k) {
        if (j != 0 || k != 0) return 0.f;
        return i == 0 ? 1e6f : (i == 8 ? 1e-6f : 0.f);
    };
    RenderScene scene;
    scene.media.push_back(std::make_unique<Medium>(
        test::greyShader(0.5f, 0.5f),
        std::vector<FloatGrid>{test::makeGrid(twoVoxels, 0, 8, 1.0)}, Transform(), 1.f, 1));
    ThreadState ts(scene);
    ts.tracking.setWavelengths(SampledWavelengths::sampleVisible(0.5f));
    ts.tracking.maxCollisions = 1000;
    Sampler s(1, 0, 0);
    // Past the dense voxel, along the empty row: only null collisions, cut at the cap.
    const Ray row{Vec3(2.f, 0.2f, 0.2f), Vec3(1, 0, 0), kInfinity};
    uint64_t events = 0;
    bool through = trackCollisions(ts.tracking, row, kInfinity, s, [&](const Collision&) {
        ++events;
        return Track::Continue;
    });
    EXPECT_FALSE(through);
    EXPECT_EQ(events, 1000u);
    EXPECT_EQ(ts.tracking.cappedFlights, 1u);
    // A cut transmittance estimate is unfinished: opaque, and counted.
    EXPECT_EQ(transmittance(ts.tracking, row, kInfinity, s).maxValue(), 0.f);
    EXPECT_EQ(ts.tracking.cappedFlights, 2u);

    // The render pass at the default cap (2^16): camera rays that cross the cell away from the
    // dense voxel are cut, counted in the render statistics, and the image stays finite.
    Rendered r = renderWith(scene, "single", 4, 4, 1);
    expectFiniteImage(r.image, "capped flights");
    std::printf("collision cap: %llu of 16 camera flights cut\n",
                (unsigned long long)r.stats.cappedFlights);
    EXPECT_GT(r.stats.cappedFlights, 0u);
    EXPECT_EQ(r.capped, r.stats.cappedFlights);  // single scattering has no depth cap
}

TEST(Extremes, NonFiniteLightIsDroppedAndCountedInBothPasses) {
    // A light of infinite irradiance: every photon's power and every camera sample is ∞.
    RenderScene scene;
    scene.media.push_back(cube(0.5f, 1.5f));
    scene.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f),
                                            std::numeric_limits<float>::infinity(), Spectrum(1.f)));
    PhotonIntegratorSettings p;
    p.photons = 1000;
    Rendered r = renderWith(scene, "photon", 4, 4, 2, p);
    expectFiniteImage(r.image, "infinite light");
    EXPECT_EQ(r.nonFinitePhotons, 1000u);
    EXPECT_GT(r.stats.nonFiniteSamples, 0u);
}

// ---- Estimates and sampling: photon counts, k, image size, spp ---------------------------

TEST(Extremes, PhotonCountsKAndImageSizesAtTheirEnds) {
    RenderScene scene;
    scene.media.push_back(cube(0.2f, 1.8f, 0.3f));
    for (uint64_t photons : {uint64_t(0), uint64_t(1), uint64_t(3000)})
        for (int k : {2, 1000000})
            for (PhotonEstimate est : {PhotonEstimate::Beam, PhotonEstimate::Point}) {
                PhotonIntegratorSettings p;
                p.photons = photons;
                p.k = k;
                p.estimate = est;
                Rendered r = renderWith(scene, "photon", 4, 4, 1, p);
                expectFiniteImage(r.image, "photons " + std::to_string(photons) + " k " +
                                               std::to_string(k));
            }
    // k = 1 (a density from one neighbour) is refused, not an internal check failure.
    PhotonIntegratorSettings one;
    one.k = 1;
    EXPECT_THROW(makePhotonIntegrator(one), MirageError);
    for (const char* name : {"single", "volpath", "photon"}) {
        Rendered r = renderWith(scene, name, 1, 1, 1);
        ASSERT_EQ(r.image.rgba.size(), 4u);
        expectFiniteImage(r.image, std::string("1×1, 1 spp, ") + name);
        EXPECT_EQ(r.stats.samples, 1u) << name;
    }
}

// ---- What the user sees: the EXR metadata -----------------------------------------------

TEST(Extremes, ExrCarriesTheGuardCountsOfBothPasses) {
    const std::string dir = test::tempDir();
    TestGridSpec spec;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) spec.voxels.push_back({i, j, k, 2.0});
    spec.voxels[0].value = std::nan("");
    writeTestGrid(dir + "/cube.vdb", spec);
    const std::string exr = dir + "/cube.exr";
    std::string log;
    ASSERT_EQ(test::runMirage("render '" + dir + "/cube.vdb' -o '" + exr +
                                  "' --resolution 8x8 --spp 1 --integrator photon "
                                  "--set render.photons=2000",
                              &log),
              0)
        << log;
    std::map<std::string, std::string> meta;
    Image image = readExr(exr, &meta);
    expectFiniteImage(image, "cube.exr");
    for (const char* key : {"mirage:nonfinite_render", "mirage:nonfinite_photons",
                            "mirage:capped_paths"}) {
        ASSERT_TRUE(meta.count(key)) << key;
        EXPECT_EQ(meta[key], "0") << key;
    }
    EXPECT_NE(log.find("non-finite dropped: 0 samples, 0 photons | capped paths 0"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("1 voxels were negative or NaN"), std::string::npos) << log;
}
