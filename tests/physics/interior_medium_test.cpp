// A closed shape bounding a medium (`interior_medium`): the medium exists only inside the shape.
// Closed form: a sphere of radius r with an index-matched boundary (dielectric, n = 1: no
// reflection, no bending) holding a purely absorbing homogeneous medium σa, in front of an
// emitter of radiance Le. A camera ray at impact parameter b from the centre sees
//     L = Le exp(−σa · 2√(r² − b²))        (b < r),     L = Le        (b > r),
// even where the ray crosses the medium's box outside the sphere (the box is larger than the
// sphere, so an unconfined medium would absorb there). Checked for the single-scatter, volpath
// and photon integrators (within 4σ), for transport's transmittance and the photon estimates'
// deterministic optical depth (exactly), and for a closed triangle mesh (a cube).
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/shape_region.h"
#include "render/photon_integrator.h"
#include "transport/ray_optical_depth.h"
#include "transport/tracking.h"

using namespace mirage;

namespace {

constexpr float kSigmaA = 2.f;  // 1/m
constexpr float kRadius = 0.5f;
constexpr float kLe = 1.f;

ShaderDesc absorber() {
    ShaderDesc s;
    s.name = "ink";
    MediumComponent c;
    c.name = "ink";
    c.sigmaA = Spectrum(kSigmaA);
    c.sigmaS = Spectrum(0.f);
    s.components.push_back(c);
    return s;
}

// Glass (n = 1) holding the absorber, the absorber's box [−1, 1]³ twice the sphere's size, an
// emissive backdrop at z = −3 facing +z, and a weak distant light so the photon pass has work.
// `cube`: a closed cube mesh of side 2r instead of the sphere.
RenderScene scene(bool cube) {
    RenderScene s;
    Bounds3 box;
    box.lo = Vec3(-1.f);
    box.hi = Vec3(1.f);
    s.media.push_back(std::make_unique<Medium>(absorber(), box, Transform(), 1.f));
    s.geometry = std::make_unique<GeometryScene>();
    int glass = s.geometry->addMaterial(Material::dielectric("matched", 1.f));
    int back = s.geometry->addMaterial(
        Material::diffuse("backdrop", Spectrum(0.f), Spectrum(kLe)));
    int shape;
    if (cube) {
        TriangleMesh m;
        const float r = kRadius;
        for (int i = 0; i < 8; ++i)
            m.positions.push_back(Vec3(i & 1 ? r : -r, i & 2 ? r : -r, i & 4 ? r : -r));
        // Two triangles per face, counter-clockwise seen from outside.
        m.indices = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                     2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
        shape = s.geometry->addMesh(m, Transform(), glass, 0);
    } else {
        shape = s.geometry->addSphere(Vec3(0.f), kRadius, glass, 0);
    }
    s.geometry->addQuad(Vec3(-5.f, -5.f, -3.f), Vec3(10.f, 0.f, 0.f), Vec3(0.f, 10.f, 0.f), back);
    s.geometry->commit();
    Confinement inside;
    inside.confineTo(s.geometry->interiorRegion(shape));
    s.media[0]->setConfinement(inside);
    s.lights.push_back(makeDistantLight(Vec3(0.f, 0.f, -1.f), 10.f, Spectrum(1.f)));
    return s;
}

// Chord of the ray x = b, y = 0.1 b (along −z) through the shape.
float chord(float b, bool cube) {
    if (cube) return std::abs(b) < kRadius ? 2.f * kRadius : 0.f;
    float b2 = b * b * 1.01f;
    return b2 < kRadius * kRadius ? 2.f * std::sqrt(kRadius * kRadius - b2) : 0.f;
}

Ray cameraRay(float b) { return Ray{Vec3(b, 0.1f * b, 4.f), Vec3(0.f, 0.f, -1.f), kInfinity}; }

void checkIntegrator(const std::string& name, bool cube) {
    RenderScene s = scene(cube);
    PhotonIntegratorSettings ps;
    ps.photons = 20000;
    ps.progress = Progress::Mode::Quiet;
    auto integrator = makeIntegrator(name, 64, ps);
    integrator->preprocess(s);
    ThreadState ts(s);
    const int n = 4000;
    for (float b : {0.f, 0.3f, 0.7f}) {  // through the centre, off centre, outside the shape
        double sum = 0, sum2 = 0, photonY = 0;
        for (int i = 0; i < n; ++i) {
            Sampler sampler(11, uint64_t(i), 0);
            SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
            ts.tracking.setWavelengths(w);
            RadianceSample r = integrator->Li(s, cameraRay(b), w, sampler, ts);
            double v = r.L.average();
            sum += v;
            sum2 += v * v;
            photonY += r.xyz.y;
        }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        double expected = kLe * std::exp(-double(kSigmaA) * chord(b, cube));
        EXPECT_NEAR(mean, expected, 4 * se + 1e-4) << name << (cube ? " cube" : " sphere")
                                                   << ", b = " << b;
        // A pure absorber scatters nothing into the camera ray.
        EXPECT_LT(photonY / n, 1e-3 * expected) << name << ", b = " << b;
    }
}

}  // namespace

TEST(InteriorMedium, SphereRegionAnswersInsideAndChord) {
    auto region = makeSphereRegion(Vec3(1.f, 0.f, 0.f), 0.5f);
    EXPECT_TRUE(region->contains(Vec3(1.2f, 0.1f, 0.f)));
    EXPECT_FALSE(region->contains(Vec3(1.f, 0.6f, 0.f)));
    float t0 = 0.f, t1 = 10.f;
    ASSERT_TRUE(region->clip(Ray{Vec3(-1.f, 0.f, 0.f), Vec3(1.f, 0.f, 0.f)}, &t0, &t1));
    EXPECT_NEAR(t0, 1.5f, 1e-5f);
    EXPECT_NEAR(t1, 2.5f, 1e-5f);
    t0 = 0.f, t1 = 10.f;
    EXPECT_FALSE(region->clip(Ray{Vec3(-1.f, 0.6f, 0.f), Vec3(1.f, 0.f, 0.f)}, &t0, &t1));
}

TEST(InteriorMedium, TransportTransmittanceAndOpticalDepthSeeOnlyTheInside) {
    for (bool cube : {false, true}) {
        RenderScene s = scene(cube);
        std::vector<const Medium*> media = s.mediaPointers();
        TrackingContext ctx(media);
        SampledWavelengths w = SampledWavelengths::sampleVisible(0.3f);
        ctx.setWavelengths(w);
        RayOpticalDepth depth(media);
        for (float b : {0.f, 0.3f, 0.7f}) {
            const double expected = std::exp(-double(kSigmaA) * chord(b, cube));
            Ray ray = cameraRay(b);
            // Sphere: the closed form, exact; cube: ratio tracking (a mesh is not known to be
            // convex), averaged.
            const int n = cube ? 20000 : 1;
            double sum = 0;
            for (int i = 0; i < n; ++i) {
                Sampler sampler(3, uint64_t(i), 0);
                sum += transmittance(ctx, ray, 10.f, sampler).average();
            }
            const double se = cube ? std::sqrt(expected * (1 - expected) / n) : 0.0;
            EXPECT_NEAR(sum / n, expected, 4 * se + 1e-5) << (cube ? "cube" : "sphere") << " " << b;
            depth.march(ray, 10.f);
            EXPECT_NEAR(depth.transmittance(10.f, 550.f), expected, 1e-4 + 1e-3 * expected)
                << (cube ? "cube" : "sphere") << " " << b;
        }
    }
}

TEST(InteriorMedium, SingleScatterSeesTheClosedForm) { checkIntegrator("single", false); }
TEST(InteriorMedium, VolPathSeesTheClosedForm) { checkIntegrator("volpath", false); }
TEST(InteriorMedium, PhotonSeesTheClosedForm) { checkIntegrator("photon", false); }
TEST(InteriorMedium, VolPathThroughAClosedMesh) { checkIntegrator("volpath", true); }

// Photons and shadow rays. A sun straight down on a floor (albedo ρ, E = 470 W/m², so
// S(λ) = 1/nm) under the sphere. Beside the sphere but under its medium's box, the shadow ray
// crosses the box outside the sphere: L = ρ/π exactly (single scattering, closed form). Under
// the sphere the shadow ray stops at the glass; light arrives as caustic photons that crossed
// the absorber, each surviving its chord with probability T(b) = exp(−σa · chord(b)), so the
// caustic map must find Y = ρ/π · T(b) (the film's Y of a constant spectral radiance is that
// radiance). An unconfined medium would absorb over the box's 2 m instead.
TEST(InteriorMedium, ShadowRaysAndPhotonsCrossOnlyTheInside) {
    const float rho = 0.5f;
    RenderScene s;
    Bounds3 box;
    box.lo = Vec3(-1.f);
    box.hi = Vec3(1.f);
    s.media.push_back(std::make_unique<Medium>(absorber(), box, Transform(), 1.f));
    s.geometry = std::make_unique<GeometryScene>();
    int glass = s.geometry->addMaterial(Material::dielectric("matched", 1.f));
    int floor = s.geometry->addMaterial(Material::diffuse("floor", Spectrum(rho)));
    int sphere = s.geometry->addSphere(Vec3(0.f), kRadius, glass, 0);
    s.geometry->addQuad(Vec3(-1.5f, -2.f, 1.5f), Vec3(3.f, 0.f, 0.f), Vec3(0.f, 0.f, -3.f), floor);
    s.geometry->commit();
    Confinement inside;
    inside.confineTo(s.geometry->interiorRegion(sphere));
    s.media[0]->setConfinement(inside);
    s.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 470.f, Spectrum(1.f)));
    const Vec3 eye(2.5f, -1.f, 0.3f);

    // Beside the sphere: direct light by a shadow ray through the box.
    auto single = makeSingleScatterIntegrator();
    ThreadState ts(s);
    {
        Sampler sampler(1, 0, 0);
        SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
        ts.tracking.setWavelengths(w);
        Vec3 target(0.8f, -2.f, 0.f);
        RadianceSample r =
            single->Li(s, Ray{eye, normalize(target - eye), kInfinity}, w, sampler, ts);
        EXPECT_NEAR(r.L.average(), rho / kPi, 1e-4 * rho / kPi);
    }

    // Under the sphere: the caustic map.
    PhotonIntegratorSettings ps;
    ps.photons = 2000000;
    ps.progress = Progress::Mode::Quiet;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(s);
    const int n = 400;
    double sum = 0, sum2 = 0, expected = 0;
    for (int i = 0; i < n; ++i) {
        Sampler sampler(4, uint64_t(i), 0);
        Vec3 target(-0.1f + 0.2f * sampler.get1D(), -2.f, -0.1f + 0.2f * sampler.get1D());
        SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
        ts.tracking.setWavelengths(w);
        RadianceSample r =
            photon->Li(s, Ray{eye, normalize(target - eye), kInfinity}, w, sampler, ts);
        EXPECT_EQ(r.L.average(), 0.f);  // the shadow ray stops at the glass
        sum += r.xyz.y;
        sum2 += double(r.xyz.y) * r.xyz.y;
        float b2 = target.x * target.x + target.z * target.z;
        expected += rho / kPi * std::exp(-kSigmaA * 2.f * std::sqrt(kRadius * kRadius - b2));
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    expected /= n;
    EXPECT_NEAR(mean, expected, 4 * se + 0.03 * expected);
}

// A glass sphere of absorber A in a fog of absorber B whose box holds the sphere: B is cut out
// of the sphere (the scene loader excludes every other medium from a shape's inside), so a ray
// through the centre sees T = exp(−σB (ℓ_box − 2r) − σA 2r). Ratio tracking (B is no longer a
// plain box) averaged, the photon estimates' march within its 1/64-of-the-sphere step.
TEST(InteriorMedium, OtherMediaAreCutOutOfTheShape) {
    const float sigmaB = 0.5f;
    RenderScene s = scene(false);
    ShaderDesc fog = absorber();
    fog.components[0].sigmaA = Spectrum(sigmaB);
    Bounds3 box;
    box.lo = Vec3(-2.f);
    box.hi = Vec3(2.f);
    s.media.push_back(std::make_unique<Medium>(fog, box, Transform(), 1.f));
    Confinement outside;
    outside.excludeFrom(s.geometry->interiorRegion(0));
    s.media[1]->setConfinement(outside);
    EXPECT_FALSE(s.media[1]->closedFormTransmittance());

    std::vector<const Medium*> media = s.mediaPointers();
    TrackingContext ctx(media);
    ctx.setWavelengths(SampledWavelengths::sampleVisible(0.6f));
    RayOpticalDepth depth(media);
    for (float b : {0.f, 0.3f, 0.7f}) {
        const Ray ray = cameraRay(b);
        const double expected =
            std::exp(-double(sigmaB) * (4.0 - chord(b, false)) - double(kSigmaA) * chord(b, false));
        const int n = 20000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            Sampler sampler(5, uint64_t(i), 0);
            sum += transmittance(ctx, ray, 10.f, sampler).average();
        }
        EXPECT_NEAR(sum / n, expected, 4 * std::sqrt(expected / n) + 1e-5) << "b = " << b;
        depth.march(ray, 10.f);
        EXPECT_NEAR(depth.transmittance(10.f, 550.f), expected, 0.02 * expected) << "b = " << b;
    }
}
