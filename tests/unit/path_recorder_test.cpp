// The path recorder (render/path_recorder.h) on hand-made sequences of events: the beauty as
// the plain sum of what was added; each contribution's light-path class (core/light_path.h) and
// light group; the place of its deep sample along the camera ray (past mirrors, then at the
// first scattering vertex); a branch's history of its own; the holdout and alpha rules of the
// camera ray; the photon estimates' parts; and the hero-only estimate applied to every part.
#include "render/path_recorder.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "render/camera_ray_data.h"

using namespace mirage;

namespace {

// Every pass a recorder fills, with one named light group ("key", slot 1).
AovLayout everyRadiancePass() {
    return AovLayout({"emission", "volume_direct", "volume_indirect", "surface_direct",
                      "surface_indirect", "caustic", "lightgroup_emission", "lightgroup_key"},
                     {"key"});
}

SampledSpectrum spectrum(float a, float b, float c, float d) {
    SampledSpectrum s;
    s[0] = a;
    s[1] = b;
    s[2] = c;
    s[3] = d;
    return s;
}

void expectSpectrumEq(const SampledSpectrum& a, const SampledSpectrum& b) {
    for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(a[i], b[i]) << "wavelength " << i;
}

// A sample's passes and deep record, and a thread state that hands them to a recorder.
struct Harness {
    Harness() : layout(everyRadiancePass()), aov(layout), ts(scene) {
        ts.aov = &aov;
        ts.deep = &deep;
        ts.lightSplit.assign(size_t(layout.groupSlots()), SampledSpectrum(0.f));
    }
    // The split a light estimate leaves (render/direct_light.h): all of it from group slot 1.
    void splitToKey(const SampledSpectrum& lit) {
        ts.lightSplit[0] = SampledSpectrum(0.f);
        ts.lightSplit[1] = lit;
    }
    RenderScene scene;
    AovLayout layout;
    AovSample aov;
    DeepSample deep;
    ThreadState ts;
};

}  // namespace

TEST(PathRecorder, WithoutPassesTheBeautyIsThePlainSum) {
    RenderScene scene;
    ThreadState ts(scene);
    RadianceSample out;
    PathRecorder rec(&out, ts);
    const SampledSpectrum e = spectrum(0.1f, 0.2f, 0.3f, 0.4f), beta = spectrum(0.5f, 0.25f, 1, 2),
                          lit = spectrum(3, 1, 0.7f, 0.1f);
    rec.emittedInMedium(e, 1.f);
    rec.litInMedium(beta, lit, 1.5f);
    rec.scatteredInMedium(1.5f);
    rec.litAtSurface(beta, lit, 2.f);
    rec.escaped(e);
    SampledSpectrum sum;
    sum += e;
    sum += beta * lit;
    sum += beta * lit;
    sum += e;
    expectSpectrumEq(out.L, sum);
    // A flight's emission goes straight into the beauty.
    const EmissionSink sink = rec.flightEmission(beta);
    EXPECT_EQ(sink.L, &out.L);
    EXPECT_EQ(sink.parts, nullptr);
    expectSpectrumEq(sink.beta, beta);
}

TEST(PathRecorder, ClassesGroupsAndDeepPlacesFollowThePath) {
    Harness h;
    RadianceSample out;
    PathRecorder rec(&out, h.ts);
    const SampledSpectrum one(1.f), lit = spectrum(2, 2, 2, 2), half(0.5f);
    // Camera → glass at 1 m → smoke emitting at 0.5 m further: emission, placed along the view.
    rec.passedSpecular(1.f);
    rec.emittedInMedium(one, 0.5f);
    // A diffuse floor 2 m past the glass: its direct light, the light of the key group.
    h.splitToKey(lit);
    rec.litAtSurface(half, lit, 2.f);
    rec.scatteredAtSurface(2.f);
    // Then a mirror, then a medium vertex: light through a specular vertex after the first
    // diffuse one is a caustic, placed at the first scattering vertex.
    rec.passedSpecular(0.7f);
    rec.litInMedium(half, lit, 0.3f);
    rec.scatteredInMedium(0.3f);
    // Emission and the dome met later are classed by the vertex nearest the camera.
    rec.emittedInMedium(one, 0.1f);
    rec.escaped(one);

    const std::array<SampledSpectrum, kLightPathCount>& path = h.aov.path;
    expectSpectrumEq(path[size_t(LightPath::Emission)], one);
    expectSpectrumEq(path[size_t(LightPath::SurfaceDirect)], half * lit);
    SampledSpectrum caustic = half * lit;
    caustic += one;
    caustic += one;
    expectSpectrumEq(path[size_t(LightPath::Caustic)], caustic);
    EXPECT_TRUE(path[size_t(LightPath::VolumeDirect)].isZero());
    EXPECT_TRUE(path[size_t(LightPath::VolumeIndirect)].isZero());
    EXPECT_TRUE(path[size_t(LightPath::SurfaceIndirect)].isZero());
    // Emission is the emission group's; light estimates go to the groups they were split into.
    SampledSpectrum emission = one;
    emission += one;
    emission += one;
    expectSpectrumEq(h.aov.group[0], emission);
    SampledSpectrum key = half * lit;
    key += half * lit;
    expectSpectrumEq(h.aov.group[1], key);

    // Deep: along the view (1 m of glass, then the event) until the floor, then at the floor.
    const std::vector<DeepSample::Radiance>& r = h.deep.radiance;
    ASSERT_EQ(r.size(), 5u);
    const float expected[5] = {1.5f, 3.f, 3.f, 3.f, 0.f};
    const bool surface[5] = {false, true, true, true, false};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(r[size_t(i)].at.t, expected[i]) << i;
        EXPECT_EQ(r[size_t(i)].at.surface, surface[i]) << i;
    }
    EXPECT_TRUE(std::isnan(r[4].at.t)) << "the dome is placed by the pixel";
    SampledSpectrum total;
    for (const DeepSample::Radiance& d : r) total += d.L;
    expectSpectrumEq(total, out.L);
}

TEST(PathRecorder, ABranchKeepsAHistoryOfItsOwn) {
    Harness h;
    RadianceSample out;
    PathRecorder rec(&out, h.ts);
    const SampledSpectrum lit(1.f), beta(0.25f);
    rec.scatteredInMedium(2.f);
    PathRecorder walk = rec.branch();
    walk.scatteredInMedium(5.f);
    walk.litInMedium(beta, lit, 1.f);  // a third vertex's light: volume_indirect
    rec.litAtSurface(beta, lit, 4.f);  // the path's second vertex, a surface after a medium one
    SampledSpectrum both = beta * lit;
    both += beta * lit;
    expectSpectrumEq(h.aov.path[size_t(LightPath::VolumeIndirect)], both);
    EXPECT_TRUE(h.aov.path[size_t(LightPath::SurfaceIndirect)].isZero());
    ASSERT_EQ(h.deep.radiance.size(), 2u);
    EXPECT_EQ(h.deep.radiance[0].at.t, 2.f);  // both at the path's first vertex
    EXPECT_EQ(h.deep.radiance[1].at.t, 2.f);
    expectSpectrumEq(out.L, both);
}

TEST(PathRecorder, HoldoutsAndAlphaBelongToTheCameraRay) {
    Harness h;
    GeometryScene geometry;
    const int m = geometry.addMaterial(Material::diffuse("black", Spectrum(0.f)));
    geometry.addQuad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), m);
    geometry.setHoldout(0, true);
    geometry.commit();
    SurfaceHit hit{};
    hit.shape = 0;

    RadianceSample out;
    Sampler sampler(SamplerKind::Random, 1, 0, 0);
    const Ray ray{Vec3(0.f), Vec3(0, 0, 1), kInfinity};
    CameraRayData data(h.scene, ray, SampledWavelengths(), sampler, h.ts, nullptr, nullptr);
    h.ts.cameraData = &data;
    PathRecorder rec(&out, h.ts);
    EXPECT_TRUE(rec.holdout(geometry, hit));
    EXPECT_EQ(rec.cameraRayData(), &data);
    // The camera ray reached the plate through T = 0.25, a holdout medium taking 0.125.
    rec.coverage(true, 0.25f, 0.125f);
    EXPECT_EQ(out.alpha, 0.625f);
    rec.coverage(false, 0.25f);
    EXPECT_EQ(out.alpha, 1.f);
    rec.stoppedInHoldout();
    EXPECT_EQ(out.alpha, 0.f);
    // Past a mirror, the camera ray is done: its coverage stands, its data record is no more.
    rec.passedSpecular(1.f);
    EXPECT_EQ(rec.cameraRayData(), nullptr);
    EXPECT_TRUE(rec.holdout(geometry, hit)) << "a holdout seen in a mirror is still a holdout";
    rec.coverage(true, 0.5f);
    EXPECT_EQ(out.alpha, 0.f);
    // Light that scattered meets a holdout as any surface.
    rec.scatteredAtSurface(1.f);
    EXPECT_FALSE(rec.holdout(geometry, hit));
    EXPECT_FALSE(rec.branch().holdout(geometry, hit));
    h.ts.cameraData = nullptr;
}

TEST(PathRecorder, FlightEmissionIsTaggedAndPlacedWithPasses) {
    Harness h;
    RadianceSample out;
    PathRecorder rec(&out, h.ts);
    const SampledSpectrum beta(0.5f);
    const EmissionSink sink = rec.flightEmission(beta);
    ASSERT_NE(sink.parts, nullptr);
    EXPECT_EQ(sink.L, nullptr);
    sink.parts->push_back({1.f, SampledSpectrum(2.f)});
    sink.parts->push_back({3.f, SampledSpectrum(4.f)});
    rec.recordFlightEmission();
    expectSpectrumEq(out.L, SampledSpectrum(6.f));
    expectSpectrumEq(h.aov.path[size_t(LightPath::Emission)], SampledSpectrum(6.f));
    ASSERT_EQ(h.deep.radiance.size(), 2u);
    EXPECT_EQ(h.deep.radiance[1].at.t, 3.f);
    // The next flight starts from an empty list.
    rec.flightEmission(beta);
    EXPECT_TRUE(h.ts.emitted.empty());
}

TEST(PathRecorder, PhotonEstimatesTakeTheirClassesAndGroups) {
    Harness h;
    RadianceSample out;
    PathRecorder rec(&out, h.ts);
    const std::vector<int> slotOfLight = {1};
    PhotonGroups groups = rec.photonGroups(slotOfLight);
    ASSERT_TRUE(groups.active());
    Photon fromKey;
    fromKey.light = 0;
    groups.add(fromKey, Vec3(1, 2, 3));
    rec.photonsInMedium(Vec3(1, 2, 3));
    EXPECT_EQ(h.aov.pathXyz[size_t(LightPath::VolumeIndirect)], Vec3(1, 2, 3));
    EXPECT_EQ(h.aov.groupXyz[1], Vec3(1, 2, 3));
    // At a diffuse surface behind a mirror: caustic and global parts, one deep sample there.
    rec.passedSpecular(2.f);
    groups = rec.photonGroups(slotOfLight);
    groups.add(fromKey, Vec3(0.5f));
    rec.photonsAtSurface(Vec3(0.25f), Vec3(0.5f), 1.f);
    EXPECT_EQ(h.aov.pathXyz[size_t(LightPath::Caustic)], Vec3(0.25f));
    EXPECT_EQ(h.aov.pathXyz[size_t(LightPath::SurfaceIndirect)], Vec3(0.5f));
    EXPECT_EQ(h.aov.groupXyz[1], Vec3(1.5f, 2.5f, 3.5f));
    EXPECT_EQ(out.xyz, Vec3(1.75f, 2.75f, 3.75f));
    ASSERT_EQ(h.deep.radiance.size(), 2u);
    EXPECT_TRUE(std::isnan(h.deep.radiance[0].at.t));
    EXPECT_EQ(h.deep.radiance[1].at.t, 3.f);
    EXPECT_TRUE(h.deep.radiance[1].at.surface);
    // Without light-group passes an estimate has no groups to fill.
    RenderScene scene;
    ThreadState plain(scene);
    RadianceSample bare;
    EXPECT_FALSE(PathRecorder(&bare, plain).photonGroups(slotOfLight).active());
}

TEST(PathRecorder, FinishMakesTheHeroOnlyEstimateOfEveryPart) {
    Harness h;
    RadianceSample out;
    PathRecorder rec(&out, h.ts);
    const SampledSpectrum e = spectrum(1, 2, 3, 4);
    rec.emittedInMedium(e, 1.f);
    PathThroughput hero;
    hero.keepHeroOnly();
    rec.finish(hero);
    const SampledSpectrum expected = spectrum(4, 0, 0, 0);
    expectSpectrumEq(out.L, expected);
    expectSpectrumEq(h.aov.path[size_t(LightPath::Emission)], expected);
    expectSpectrumEq(h.aov.group[0], expected);
    expectSpectrumEq(h.deep.radiance[0].L, expected);
}
