// The photon radiance estimates on synthetic photon sets whose answer is known, the beam query
// against brute force, and the deterministic optical depth along a ray against quadrature.
//
// Known answer: photons of power Φ spread uniformly with density ρ (1/m³), with isotropic
// directions, in a medium with any phase function. The estimated quantity is the in-scattered
// radiance times σs, σs L_s = Σ p ΔΦ / V → ρ Φ ∫ p dω / (4π) = ρΦ/(4π) (W·m⁻³·sr⁻¹), the same
// at every point; along a camera ray, the beam and the marched point estimates are
// ∫ T(t) ρΦ/(4π) dt. The photons' wavelengths are spread evenly over 360–830 nm, so they carry
// a flat spectrum of ρΦ/(4π · 470 nm) per nm, whose Y in the film's normalisation is that
// spectral value itself, and X ≈ Z ≈ Y (the CIE matching functions have nearly equal
// integrals): the test checks the units of the XYZ derivation as well as the density.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "geometry/geometry_scene.h"
#include "photon/beam_estimate.h"
#include "spectrum/cie.h"
#include "test_support.h"
#include "volume/grid_lookup.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;

// A box of 32³ voxels of density 1 (≈ [0, 1]³ m) with the given grey σa, σs and HG g.
std::unique_ptr<Medium> boxMedium(float sigmaA, float sigmaS, float g) {
    return test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, sigmaA, sigmaS, g);
}

// ∫ σt along the ray from 0 to t by a fine midpoint rule on the grid's trilinear field, clipped
// to the medium's box as the trackers clip it.
double referenceOpticalDepth(const Medium& m, const Ray& ray, double t, double sigmaT,
                             double constantSigmaT = 0) {
    const FloatGrid& g = m.binding().grids()[0];
    auto acc = g.accessor();
    float t0, t1;
    if (!m.objectBounds().intersect(ray.o, ray.d, 0.f, float(t), &t0, &t1)) return 0.0;
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        Vec3 p = ray.at(float(t0 + (t1 - t0) * (i + 0.5) / n));
        sum += sigmaT * g.sample(acc, p) + constantSigmaT;
    }
    return sum * (t1 - t0) / n;
}

// n photons uniform in `box`, isotropic directions, all at `lambda` nm, or with wavelengths
// stratified over 360–830 nm when lambda is 0.
PhotonList uniformPhotons(size_t n, const Bounds3& box, float power, uint64_t seed,
                          float lambda = 0.f) {
    PhotonList list(n);
    Vec3 ext = box.diagonal();
    for (size_t i = 0; i < n; ++i) {
        Sampler s(seed, i, 0);
        list[i].p = box.lo + Vec3(s.get1D() * ext.x, s.get1D() * ext.y, s.get1D() * ext.z);
        list[i].wi = sampleUniformSphere(s.get1D(), s.get1D());
        list[i].lambda = lambda > 0.f ? lambda
                                      : kLambdaMin + (kLambdaMax - kLambdaMin) *
                                                         (float(i) + 0.5f) / float(n);
        list[i].power = power;
    }
    return list;
}

float volume(const Bounds3& b) {
    Vec3 e = b.diagonal();
    return e.x * e.y * e.z;
}

// The sharpest field a grid holds: each voxel 0 or 1 at random, so the density jumps by 1
// across one voxel's trilinear ramp, in every direction.
float binarySmoke(int i, int j, int k) {
    uint32_t h = uint32_t(i) * 73856093u ^ uint32_t(j) * 19349663u ^ uint32_t(k) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (h & 1u) ? 1.f : 0.f;
}

}  // namespace

TEST(RayOpticalDepth, MatchesQuadratureForGreyAndSpectralComponents) {
    // A grey grid component plus a homogeneous component whose σa rises linearly with λ.
    ShaderDesc s;
    s.name = "mixed";
    MediumComponent grid;
    grid.grid = "density";
    grid.sigmaA = Spectrum(0.5f);
    grid.sigmaS = Spectrum(1.5f);
    MediumComponent haze;
    haze.sigmaA = Spectrum::fromTable({360.f, 830.f}, {0.2f, 1.2f});
    haze.concentration = 0.5f;
    s.components = {grid, haze};
    auto wave = [](int i, int j, int k) {
        return 0.6f + 0.4f * std::sin(0.3f * float(i + 2 * j + k));
    };
    std::vector<FloatGrid> grids{test::makeGrid(wave, 0, 31, kH)};
    Medium m(s, std::move(grids), Transform(), 2.f, 16);  // densityScale 2

    RayOpticalDepth depth({&m});
    Ray ray{Vec3(-0.3f, 0.31f, 0.47f), normalize(Vec3(1.f, 0.2f, 0.1f)), kInfinity};
    depth.march(ray, kInfinity);
    ASSERT_FALSE(depth.empty());
    EXPECT_FALSE(depth.grey());
    EXPECT_EQ(depth.transmittance(0.1f, 500.f), 1.f);  // before the box
    for (float t : {0.4f, 0.7f, 1.0f, 1.5f, 3.f}) {
        for (float lambda : {400.f, 600.f, 800.f}) {
            float hazeSigma = 0.5f * 2.f * (0.2f + (lambda - 360.f) / 470.f);
            double tau = referenceOpticalDepth(m, ray, t, 2.0 * 2.0, hazeSigma);
            EXPECT_NEAR(-std::log(depth.transmittance(t, lambda)), tau, 2e-3 * tau + 1e-5)
                << "t " << t << " λ " << lambda;
        }
    }
    // A ray that misses every medium has T = 1 everywhere.
    depth.march(Ray{Vec3(5, 5, 5), Vec3(0, 1, 0), kInfinity}, kInfinity);
    EXPECT_TRUE(depth.empty());
    EXPECT_EQ(depth.transmittance(10.f, 500.f), 1.f);
}

TEST(RayOpticalDepth, StopsWhereTheRayTurnsOpaque) {
    // Dense grey smoke: the march stops once τ passes kOpaqueDepth, and the beam estimate clips
    // its query there (reach()); T up to that point is the full march's.
    auto m = test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 100.f, 900.f);
    RayOpticalDepth depth({m.get()});
    const Ray ray{Vec3(0.5f, 0.5f, -1.f), Vec3(0, 0, 1), kInfinity};
    depth.march(ray, kInfinity);
    ASSERT_FALSE(depth.empty());
    const float entry = depth.tBegin();
    // σt = 1000/m: τ = 30 at 3 cm into the box; the march stops within one step beyond.
    EXPECT_LT(depth.reach(), entry + 0.03f + 2.f * depth.step());
    EXPECT_GT(depth.reach(), entry + 0.03f - 1e-4f);
    const double tau =
        test::opticalDepth(m->binding().grids()[0], ray.at(entry), ray.at(entry + 0.04f), 1000.0);
    EXPECT_NEAR(-std::log(depth.transmittance(entry + 0.04f, 550.f)), tau, 1e-3 * tau);
    EXPECT_LT(tau, double(RayOpticalDepth::kOpaqueDepth));
    EXPECT_LT(depth.transmittance(depth.reach(), 550.f),
              std::exp(-RayOpticalDepth::kOpaqueDepth) * 1.01f);
    // Thin smoke is marched to the far side: nothing is opaque.
    auto thin = test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 1.f, 9.f);
    RayOpticalDepth thinDepth({thin.get()});
    thinDepth.march(ray, kInfinity);
    EXPECT_EQ(thinDepth.reach(), kInfinity);
}

TEST(BeamEstimate, QueryEqualsBruteForce) {
    auto m = boxMedium(0.f, 1.f, 0.f);
    // A cloud with duplicates; several rays start inside it, where Embree's self-intersection
    // avoidance would drop discs near the origin if the query did not back off.
    PhotonList list = uniformPhotons(20000, Bounds3{Vec3(0.f), Vec3(1.f)}, 1.f, 3);
    for (size_t i = 0; i < 2000; ++i) list.push_back(list[i * 7]);
    VolumePhotons photons(list, {m.get()});
    std::vector<float> radii(photons.size());
    for (size_t i = 0; i < radii.size(); ++i)
        radii[i] = 0.005f + 0.05f * float((i * 37) % 101) / 100.f;
    BeamEstimator beam(photons, radii);

    std::vector<BeamHit> hits;
    int checked = 0;
    for (int r = 0; r < 100; ++r) {
        Sampler s(5, uint64_t(r), 0);
        Vec3 o = r % 2 ? Vec3(s.get1D(), s.get1D(), s.get1D())
                       : Vec3(-1.f, s.get1D(), s.get1D());
        Vec3 d = r % 2 ? sampleUniformSphere(s.get1D(), s.get1D())
                       : normalize(Vec3(1.f, s.get1D() - 0.5f, s.get1D() - 0.5f));
        Ray ray{o, d, kInfinity};
        float tMin = r % 3 == 0 ? 0.2f : 0.f, tMax = r % 4 == 0 ? 1.1f : kInfinity;
        beam.query(ray, tMin, tMax, &hits);
        for (size_t i = 1; i < hits.size(); ++i) ASSERT_LT(hits[i - 1].slot, hits[i].slot);
        std::vector<bool> found(photons.size(), false);
        for (const BeamHit& h : hits) found[h.slot] = true;
        for (size_t i = 0; i < photons.size(); ++i) {
            Vec3 v = photons.map()[i].p - o;
            float t = dot(v, d);
            Vec3 perp = v - d * t;
            float d2 = dot(perp, perp), r2 = radii[i] * radii[i];
            // Discs within rounding of the edge or of the span's ends may go either way.
            if (std::abs(d2 - r2) < 1e-5f * r2 || std::abs(t - tMin) < 1e-5f ||
                std::abs(t - tMax) < 1e-5f)
                continue;
            bool inside = d2 <= r2 && t >= tMin && t <= tMax;
            EXPECT_EQ(found[i], inside) << "ray " << r << " photon " << i << " t " << t;
            checked += inside;
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(BeamEstimate, EmptyMapFindsNothing) {
    auto m = boxMedium(0.f, 1.f, 0.f);
    VolumePhotons photons(PhotonList{}, {m.get()});
    BeamEstimator beam(photons, {});
    std::vector<BeamHit> hits{{1, 2.f, 3.f}};
    beam.query(Ray{Vec3(0.5f), Vec3(0, 0, 1), kInfinity}, 0.f, kInfinity, &hits);
    EXPECT_TRUE(hits.empty());
}

TEST(BeamEstimate, KernelsAreNormalised) {
    auto m = boxMedium(0.f, 1.f, 0.f);
    VolumePhotons photons(PhotonList{}, {m.get()});
    for (BeamKernel k : {BeamKernel::Biweight, BeamKernel::Box}) {
        BeamEstimator beam(photons, {}, k);
        // ∫ K dA = ∫₀^r K(s) 2πs ds by the midpoint rule.
        const float r = 0.3f;
        const int n = 10000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            float s = r * (float(i) + 0.5f) / float(n);
            sum += beam.kernelValue(s * s, r) * 2 * M_PI * s * (r / n);
        }
        EXPECT_NEAR(sum, 1.0, 1e-4);
        EXPECT_EQ(beam.kernelValue(r * r * 1.01f, r), 0.f);
    }
}

TEST(VolumePhotons, PhaseIsTheScatteringWeightedMixtureOfLobes) {
    ShaderDesc s;
    s.name = "two lobes";
    MediumComponent a, b;
    a.grid = b.grid = "density";
    a.sigmaS = Spectrum(1.f);
    b.sigmaS = Spectrum(3.f);
    a.g = 0.f;
    b.g = 0.8f;
    s.components = {a, b};
    std::vector<FloatGrid> grids{test::makeGrid([](int, int, int) { return 1.f; }, 0, 31, kH)};
    Medium m(s, std::move(grids), Transform(), 1.f, 16);
    Photon ph{Vec3(0.5f), Vec3(0, 0, 1), 550.f, 2.f};
    VolumePhotons photons({ph}, {&m});
    EXPECT_EQ(photons.fluxXyz(0), cieXyz(550.f) * (2.f / kCieYIntegral));
    for (float c : {-0.9f, 0.f, 0.7f}) {
        Vec3 wo(std::sqrt(1 - c * c), 0.f, c);
        float expected = 0.25f * HGPhase(0.f).eval(c) + 0.75f * HGPhase(0.8f).eval(c);
        EXPECT_NEAR(photons.phase(0, wo), expected, 1e-5f * expected);
    }
}

TEST(VolumeEstimate, UniformPhotonDensityGivesTheKnownRadiance) {
    // Photons fill a region larger than the medium's box, so that neither the point queries nor
    // the discs crossing the ray see an edge of the photon cloud; the medium only attenuates.
    const float sigmaT = 1.f, power = 1e-3f;
    auto m = boxMedium(0.2f, sigmaT - 0.2f, 0.3f);  // anisotropic: p averages to 1/(4π)
    const Bounds3 cloud{Vec3(-0.4f), Vec3(1.4f)};
    const size_t n = 400000;
    VolumePhotons photons(uniformPhotons(n, cloud, power, 17), {m.get()});
    const double rho = double(n) / volume(cloud);
    // Spectral value of σs L_s: ρΦ/(4π) spread evenly over 470 nm; Y equals it.
    const double density = rho * power / (4 * M_PI) / 470.0;

    // Point estimate at interior points: ρΦ/(4π), the (k − 1)/k of volume_estimate.h included.
    const int k = 32;
    std::vector<PhotonNeighbour> buffer(k);
    double sumY = 0, sumX = 0, sumZ = 0;
    const int points = 2000;
    for (int i = 0; i < points; ++i) {
        Sampler s(23, uint64_t(i), 0);
        Vec3 x(s.get1D(), s.get1D(), s.get1D());
        Vec3 est = pointEstimate(photons, x, sampleUniformSphere(s.get1D(), s.get1D()),
                                 PhotonSearch{k, 0.3f, buffer.data()});
        sumX += est.x;
        sumY += est.y;
        sumZ += est.z;
    }
    double pointY = sumY / points, expectedPoint = density;
    EXPECT_NEAR(pointY / expectedPoint, 1.0, 0.02) << "point Y " << pointY;
    // X and Z carry the variance of the matching functions over random wavelengths as well.
    EXPECT_NEAR(sumX / sumY, 1.0, 0.05);
    EXPECT_NEAR(sumZ / sumY, 1.0, 0.05);

    // Along rays through the box. Photons are stored where scattering happens, so their density
    // follows σs: the cloud is thinned to ρ·σs(x)/σs,max (rejection on the grid value, whose
    // maximum is 1), and both estimates must then integrate ρΦ/(4π) · σs(t)/σs,max · T(t)
    // along the ray — the marched point estimate through its σs(x)/σs(x_p) weights, the beam
    // estimate through where its discs are. One wavelength here: the test is of the kernels and
    // the transmittance, and the wavelength noise would need many more rays to average out.
    PhotonList thinned;
    {
        auto acc = m->binding().grids()[0].accessor();
        Sampler keep(31, 0, 0);
        for (const Photon& p : uniformPhotons(n, cloud, power, 29, 555.f))
            if (keep.get1D() < m->binding().grids()[0].sample(acc, p.p)) thinned.push_back(p);
    }
    VolumePhotons mono(std::move(thinned), {m.get()});
    const double monoDensity = rho * power / (4 * M_PI) * cieXyz(555.f).y / kCieYIntegral;
    std::vector<float> radii = mono.map().photonRadii(16, 1e-4f, 0.3f);
    BeamEstimator beam(mono, radii);
    RayOpticalDepth depth({m.get()});
    std::vector<BeamHit> hits;
    ScatteringProbe probe({m.get()});
    double beamY = 0, beamExpected = 0, marchY = 0, marchExpected = 0;
    const int rays = 256;
    for (int i = 0; i < rays; ++i) {
        // Parallel rays along +z on a 16×16 lattice over [0.1, 0.9]².
        Vec3 o(0.1f + 0.8f * float(i % 16) / 15.f, 0.1f + 0.8f * float(i / 16) / 15.f, -1.f);
        Ray ray{o, Vec3(0, 0, 1), kInfinity};
        depth.march(ray, kInfinity);
        beamY += beam.estimate(ray, kInfinity, depth, &hits).y;
        marchY += pointEstimateAlongRay(mono, ray, depth, PhotonSearch{k, 0.3f, buffer.data()},
                                        PointMarch{0.02f, 0.5f, &probe})
                      .y;
        // ∫ (σs/σs,max) T dt by quadrature, over the cloud and over the medium's span.
        const int steps = 2000;
        const double dt = 1.8 / steps;
        double tau = referenceOpticalDepth(*m, ray, 0.6, sigmaT);
        auto acc = m->binding().grids()[0].accessor();
        for (int j = 0; j < steps; ++j) {
            float t = 0.6f + float(dt * (j + 0.5));  // z from −0.4 to 1.4
            // Outside the box the grid reads its background, 0.
            double sigma = sigmaT * m->binding().grids()[0].sample(acc, ray.at(t));
            double T = std::exp(-(tau + 0.5 * sigma * dt));
            tau += sigma * dt;
            double stored = sigma / sigmaT;  // σs(t)/σs,max: the thinning of the cloud
            beamExpected += monoDensity * stored * T * dt;
            if (t > depth.tBegin() && t < depth.tEnd())
                marchExpected += monoDensity * stored * T * dt;
        }
    }
    std::printf("point %.4f beam %.4f march %.4f (ratios to the expected values)\n",
                pointY / expectedPoint, beamY / beamExpected, marchY / marchExpected);
    EXPECT_NEAR(beamY / beamExpected, 1.0, 0.03) << "beam " << beamY / rays;
    EXPECT_NEAR(marchY / marchExpected, 1.0, 0.03) << "march " << marchY / rays;
}

namespace {

// The beam estimate Y along each ray, over the given rays, with discs of one radius r.
std::vector<double> beamAlong(const VolumePhotons& photons, const Medium& m,
                              const std::vector<Ray>& rays, float r) {
    BeamEstimator beam(photons, std::vector<float>(photons.size(), r));
    RayOpticalDepth depth({&m});
    std::vector<BeamHit> hits;
    std::vector<double> y;
    for (const Ray& ray : rays) {
        depth.march(ray, kInfinity);
        y.push_back(beam.estimate(ray, kInfinity, depth, &hits).y);
    }
    return y;
}

}  // namespace

TEST(BeamEstimate, SharpDensityEdgeKeepsEachSidesLight) {
    // Smoke of density 1 for x < 0.47 m and 0.1 beyond 0.5 m (one voxel of trilinear ramp),
    // σs = 0.5/m per unit density. Photons are stored where scattering happens, so their density
    // is ρ·d(x); along a ray the answer is ρΦ/(4π) ∫ d(t) T(t) dt, on either side of the edge,
    // even within a disc radius of it. Without σs(x')/σs(x_p) a ray 4 cm into the thin side
    // gathers the dense side's photons from the part of its discs across the edge.
    const float sigmaS = 0.5f, power = 1e-3f, r = 0.08f;
    auto edge = [](int i, int, int) { return i < 16 ? 1.f : 0.1f; };
    auto m = test::gridMedium(edge, 0, 31, kH, 0.f, sigmaS, 0.f);
    const Bounds3 cloud{Vec3(0.f), Vec3(1.f)};
    const size_t n = 1600000;
    PhotonList stored;
    {
        auto acc = m->binding().grids()[0].accessor();
        Sampler keep(41, 0, 0);
        for (const Photon& p : uniformPhotons(n, cloud, power, 43, 555.f))
            if (keep.get1D() < m->binding().grids()[0].sample(acc, p.p)) stored.push_back(p);
    }
    VolumePhotons photons(std::move(stored), {m.get()});
    const double density = double(n) / volume(cloud) * power / (4 * M_PI) * cieXyz(555.f).y /
                           kCieYIntegral;
    for (float x : {0.42f, 0.54f, 0.57f}) {
        std::vector<Ray> rays;
        for (int i = 0; i < 16; ++i)
            rays.push_back(Ray{Vec3(x, 0.3f + 0.4f * float(i) / 15.f, -1.f), Vec3(0, 0, 1),
                               kInfinity});
        const std::vector<double> y = beamAlong(photons, *m, rays, r);
        double got = 0, expected = 0;
        auto acc = m->binding().grids()[0].accessor();
        for (size_t i = 0; i < rays.size(); ++i) {
            got += y[i];
            const int steps = 2000;
            const double dt = 1.2 / steps;
            double tau = 0;
            for (int j = 0; j < steps; ++j) {
                const float t = 0.9f + float(dt * (j + 0.5));  // z from −0.1 to 1.1
                const double d = m->binding().grids()[0].sample(acc, rays[i].at(t));
                const double T = std::exp(-(tau + 0.5 * sigmaS * d * dt));
                tau += sigmaS * d * dt;
                expected += density * d * T * dt;
            }
        }
        std::printf("x = %.2f m: beam / expected = %.4f\n", x, got / expected);
        EXPECT_NEAR(got / expected, 1.0, 0.05) << "x = " << x;
    }
}

// One photon of 1 W stored in thin smoke (density 0.001, x = 0.55 m) beside dense smoke
// (density 1, x < 0.5 m), σs = 0.5/m per unit density: the density-ratio cap's case.
struct ThinSidePhoton {
    static constexpr float kSigmaS = 0.5f;
    std::unique_ptr<Medium> medium = test::gridMedium(
        [](int i, int, int) { return i < 16 ? 1.f : 0.001f; }, 0, 31, kH, 0.f, kSigmaS, 0.f);
    VolumePhotons photons{PhotonList{photon()}, {medium.get()}};

    static Photon photon() {
        Photon p;
        p.p = Vec3(0.55f, 0.5f, 0.5f);
        p.wi = Vec3(0.f, -1.f, 0.f);
        p.lambda = 555.f;
        p.power = 1.f;
        return p;
    }
};

// One photon stored in thin smoke (density 0.001) whose disc reaches a ray in dense smoke
// (density 1): the σs ratio, 1000 there, is capped at 16 (volume_estimate.h, kMaxDensityRatio),
// so that a rare photon of the thin side does not light the dense side as a blotch. Against
// the mirror ray on the thin side (ratio 1, the same kernel and phase), the dense side gets 16 ×
// its transmittance; uncapped it would get about 780 times as much.
TEST(BeamEstimate, AThinSidePhotonLightsTheDenseSideAtMostSixteenfold) {
    const float sigmaS = ThinSidePhoton::kSigmaS;
    ThinSidePhoton side;
    const auto& m = side.medium;
    const VolumePhotons& photons = side.photons;
    const Ray dense{Vec3(0.45f, 0.5f, -1.f), Vec3(0, 0, 1), kInfinity};
    const Ray thin{Vec3(0.65f, 0.5f, -1.f), Vec3(0, 0, 1), kInfinity};
    const std::vector<double> y = beamAlong(photons, *m, {dense, thin}, 0.2f);
    ASSERT_GT(y[1], 0.0);
    // T to the photon's projection on the dense ray: 0.5 m of σs = 0.5/m from the box's face.
    const double expected = 16.0 * std::exp(-0.5 * sigmaS);
    EXPECT_NEAR(y[0] / y[1], expected, 0.03 * expected);
}

// The same photon and rays for the point estimate: its search ball (maxRadius, fewer than k
// photons) reaches both rays alike, and the dense ray gets 16 × its mean transmittance over
// the ball's chord, not ~780 times as much.
TEST(VolumeEstimate, AThinSidePhotonLightsTheDenseSideAtMostSixteenfold) {
    const float sigmaS = ThinSidePhoton::kSigmaS, radius = 0.2f;
    ThinSidePhoton side;
    const auto& m = side.medium;
    const VolumePhotons& photons = side.photons;
    RayOpticalDepth depth({m.get()});
    ScatteringProbe probe({m.get()});
    std::vector<PhotonNeighbour> buffer(2);
    auto along = [&](float x) {
        const Ray ray{Vec3(x, 0.5f, -1.f), Vec3(0, 0, 1), kInfinity};
        depth.march(ray, kInfinity);
        return pointEstimateAlongRay(photons, ray, depth, PhotonSearch{2, radius, buffer.data()},
                                     PointMarch{0.005f, 0.5f, &probe})
            .y;
    };
    const float dense = along(0.45f), thin = along(0.65f);
    ASSERT_GT(thin, 0.f);
    // The chord: z = 0.5 ± √(r² − 0.1²) from the box's face; T = e^(−σs z) on it, ~1 on the
    // thin side.
    const double half = std::sqrt(double(radius) * radius - 0.01);
    const double meanT = (std::exp(-sigmaS * (0.5 - half)) - std::exp(-sigmaS * (0.5 + half))) /
                         (sigmaS * 2.0 * half);
    const double expected = 16.0 * meanT;
    EXPECT_NEAR(dense / thin, expected, 0.03 * expected);
}

TEST(BeamEstimate, FogInAGlassBallStaysInTheBall) {
    // Homogeneous fog confined to a glass sphere of radius 0.5 m (its box twice as wide), the
    // photons uniform in the ball, and a thin absorbing haze (σa = 0.05/m, no scattering) over
    // [−2, 2]³ around it. A ray through the ball sees ρΦ/(4π) ∫ T dt over its chord; a ray that
    // passes the glass outside, closer than a disc radius, crosses only haze, which scatters
    // nothing, and must get nothing, though the discs of the photons just inside reach it.
    const float sigmaS = 0.5f, haze = 0.05f, power = 1e-3f, r = 0.08f, radius = 0.5f;
    ShaderDesc s = test::greyShader(0.f, sigmaS);
    s.components[0].grid.clear();
    Medium fog(s, Bounds3{Vec3(-1.f), Vec3(1.f)}, Transform(), 1.f);
    ShaderDesc h = test::greyShader(haze, 0.f);
    h.components[0].grid.clear();
    Medium air(h, Bounds3{Vec3(-2.f), Vec3(2.f)}, Transform(), 1.f);
    GeometryScene geometry;
    const int glass = geometry.addMaterial(Material::dielectric("glass", 1.5f));
    const int ball = geometry.addSphere(Vec3(0.f), radius, glass, 0);
    geometry.commit();
    Confinement interior;
    interior.confineTo(geometry.interiorRegion(ball));
    fog.setConfinement(interior);
    const Bounds3 cube{Vec3(-radius), Vec3(radius)};
    const size_t n = 1000000;
    PhotonList inside;
    for (const Photon& p : uniformPhotons(n, cube, power, 47, 555.f))
        if (length(p.p) < radius) inside.push_back(p);
    VolumePhotons photons(std::move(inside), {&fog, &air});
    const double density = double(n) / volume(cube) * power / (4 * M_PI) * cieXyz(555.f).y /
                           kCieYIntegral;
    BeamEstimator beam(photons, std::vector<float>(photons.size(), r));
    RayOpticalDepth depth({&fog, &air});
    std::vector<BeamHit> hits;
    for (float b : {0.f, 0.2f, 0.52f, 0.55f}) {
        double got = 0;
        for (int i = 0; i < 16; ++i) {
            const float phi = 2.f * kPi * float(i) / 16.f;
            const Ray ray{Vec3(b * std::cos(phi), b * std::sin(phi), -3.f), Vec3(0, 0, 1),
                          kInfinity};
            depth.march(ray, kInfinity);
            got += beam.estimate(ray, kInfinity, depth, &hits).y;
        }
        // Per ray: the haze's T over 2 − L/2 m to the chord, then ∫ e^{−(σs + σa) s} ds over
        // the chord of length L.
        const double L = b < radius ? 2.0 * std::sqrt(double(radius * radius - b * b)) : 0.0;
        const double k = double(sigmaS) + haze;
        const double expected =
            16 * density * std::exp(-haze * (2.0 - 0.5 * L)) * (1.0 - std::exp(-k * L)) / k;
        std::printf("b = %.2f m: beam %.6g, expected %.6g\n", b, got, expected);
        if (b < radius)
            EXPECT_NEAR(got / expected, 1.0, 0.05) << "b = " << b;
        else
            EXPECT_EQ(got, 0.0) << "b = " << b;
    }
}

TEST(RayOpticalDepth, MarchBiasOnSharpSmokeIsBelowThePhotonNoise) {
    // The photon estimates take T from a midpoint-rule march (ray_optical_depth.h), a bias that
    // does not fall with more photons. It must stay far below the estimate's noise at every
    // quality preset; the smallest is the final preset's, relMSE 0.011 on the preset scene
    // (docs/performance.md, "Quality presets"): ~10 % RMS per pixel. The march step does not depend
    // on the preset, so one measurement serves all three.
    //
    // The sharpest field a grid holds: binary smoke, each voxel of a 32³ grid 0 or 1 at random
    // (density jumps by 1 across one voxel's trilinear ramp, in every direction), at σt = 4/m
    // (τ ≈ 2 across the 1 m box) and 40/m (τ ≈ 20: the light comes from the first few voxels).
    // Per random ray, what an estimate integrates is ∫ T(t) σs L dt; with L uniform that is
    // I = ∫ T(t) σt(t) dt, by a fine quadrature of the trilinear field with the march's T and
    // with the exact T. The relative error of I is the pixel's bias from the march.
    const double finalPresetNoise = std::sqrt(0.011);
    for (float sigmaT : {4.f, 40.f}) {
        auto m = test::gridMedium(binarySmoke, 0, 31, kH, 0.1f * sigmaT, 0.9f * sigmaT, 0.f);
        auto acc = m->binding().grids()[0].accessor();
        RayOpticalDepth depth({m.get()});
        double sum = 0, sum2 = 0, worst = 0;
        int rays = 0;
        for (int r = 0; r < 200; ++r) {
            Sampler s(53, uint64_t(r), 0);
            const Vec3 o(s.get1D() - 0.5f, s.get1D() - 0.5f, -1.f);
            const Vec3 target(s.get1D(), s.get1D(), 1.5f);
            const Ray ray{o, normalize(target - o), kInfinity};
            depth.march(ray, kInfinity);
            if (depth.empty()) continue;
            const int steps = 20000;
            const double t0 = depth.tBegin(), dt = (depth.tEnd() - t0) / steps;
            double tau = 0, marched = 0, exact = 0;
            for (int j = 0; j < steps; ++j) {
                const float t = float(t0 + (j + 0.5) * dt);
                const double sigma = sigmaT * m->binding().grids()[0].sample(acc, ray.at(t));
                exact += std::exp(-(tau + 0.5 * sigma * dt)) * sigma * dt;
                marched += depth.transmittance(t, 550.f) * sigma * dt;
                tau += sigma * dt;
            }
            if (!(exact > 1e-3)) continue;  // a ray through empty voxels only
            const double rel = marched / exact - 1.0;
            sum += rel;
            sum2 += rel * rel;
            worst = std::max(worst, std::abs(rel));
            ++rays;
        }
        const double bias = sum / rays, rms = std::sqrt(sum2 / rays);
        std::printf("march on binary smoke, sigma_t %g/m: per-ray bias of the in-scattered "
                    "light mean %+.2e, RMS %.2e, worst %.2e over %d rays\n",
                    sigmaT, bias, rms, worst, rays);
        EXPECT_GT(rays, 150);
        // A tenth of the final preset's per-pixel noise, in RMS over rays and on the mean; the
        // worst ray below the noise itself.
        EXPECT_LT(rms, 0.1 * finalPresetNoise) << "sigma_t " << sigmaT;
        EXPECT_LT(std::abs(bias), 0.1 * finalPresetNoise) << "sigma_t " << sigmaT;
        EXPECT_LT(worst, finalPresetNoise) << "sigma_t " << sigmaT;
    }
}

// Light groups (photon/photon_groups.h): each photon's term goes to the group of the light it
// left. The beam estimate is a sum over photons given their radii, so a group's part equals
// the estimate of that group's photons alone, with the same radii; the point estimate's k
// nearest depend on all photons, so there the groups are checked to sum to it.
TEST(PhotonGroups, EstimatesSplitExactlyByTheLightOfEachPhoton) {
    auto m = boxMedium(0.1f, 0.9f, 0.3f);
    PhotonList all = uniformPhotons(20000, Bounds3{Vec3(0.f), Vec3(1.f)}, 1e-3f, 11);
    // Light 0 → slot 2, light 1 → slot 1, a medium's photons → slot 0 (emission).
    const std::vector<int> slotOfLight = {2, 1};
    std::vector<PhotonList> bySlot(3);
    for (size_t i = 0; i < all.size(); ++i) {
        all[i].light = i % 3 == 0 ? 0u : i % 3 == 1 ? 1u : Photon::kFromMedium;
        bySlot[i % 3 == 0 ? 2 : i % 3 == 1 ? 1 : 0].push_back(all[i]);
    }
    const float r = 0.04f;
    VolumePhotons photons(all, {m.get()});
    BeamEstimator beam(photons, std::vector<float>(photons.size(), r));
    RayOpticalDepth depth({m.get()});
    ScatteringProbe probe({m.get()});
    std::vector<BeamHit> hits;
    std::vector<PhotonNeighbour> buffer(16);
    for (int i = 0; i < 20; ++i) {
        Sampler s(9, uint64_t(i), 0);
        // Through the box: entering it within [0.2, 0.8]² of its x = 0 face.
        const float y = 0.3f + 0.4f * s.get1D(), z = 0.3f + 0.4f * s.get1D();
        const Ray ray{Vec3(-1.f, y, z),
                      normalize(Vec3(1.f, 0.2f * (s.get1D() - 0.5f), 0.2f * (s.get1D() - 0.5f))),
                      kInfinity};
        depth.march(ray, kInfinity);
        std::vector<Vec3> groups(3, Vec3(0.f));
        const Vec3 total = beam.estimate(ray, kInfinity, depth, &hits, ViewWeight(),
                                         PhotonGroups(&slotOfLight, &groups));
        ASSERT_GT(total.y, 0.f);
        Vec3 sum(0.f);
        for (size_t g = 0; g < 3; ++g) {
            VolumePhotons alone(bySlot[g], {m.get()});
            BeamEstimator beamAlone(alone, std::vector<float>(alone.size(), r));
            const Vec3 expected = beamAlone.estimate(ray, kInfinity, depth, &hits);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(groups[g][c], expected[c], 1e-5f * total[c]) << "ray " << i;
            sum += groups[g];
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], total[c], 1e-5f * total[c]);
        // The marched point estimate: its groups sum to it.
        std::fill(groups.begin(), groups.end(), Vec3(0.f));
        const Vec3 point = pointEstimateAlongRay(
            photons, ray, depth, PhotonSearch{16, 0.2f, buffer.data()},
            PointMarch{0.05f, 0.5f, &probe}, ViewWeight(), PhotonGroups(&slotOfLight, &groups));
        ASSERT_GT(point.y, 0.f);
        const Vec3 pointSum = groups[0] + groups[1] + groups[2];
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(pointSum[c], point[c], 1e-5f * point[c]);
        for (size_t g = 0; g < 3; ++g) EXPECT_GT(groups[g].y, 0.f);
    }
}
