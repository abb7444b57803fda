// Free flights and transmittance along curved paths (transport/curved_tracking.h): optical depth
// accumulates over arc length (not chord displacement), chords stop at the Embree scene's
// surfaces where the exact curved path meets them, and free flights along a curved path are
// exponential in arc length.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/geometry_scene.h"
#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "transport/curved_tracking.h"

namespace mirage {
namespace {

// A grey homogeneous box (−50 … 50 m)³ of σa, σs.
Medium greyBox(float sigmaA, float sigmaS) {
    ShaderDesc s;
    s.name = "fog";
    MediumComponent c;
    c.name = "fog";
    c.sigmaA = Spectrum(sigmaA);
    c.sigmaS = Spectrum(sigmaS);
    s.components.push_back(c);
    Bounds3 b;
    b.lo = Vec3(-50.f);
    b.hi = Vec3(50.f);
    return Medium(s, b, Transform(), 1.f);
}

SampledWavelengths fourWavelengths() {
    SampledWavelengths w;
    w.lambda = {450.f, 520.f, 590.f, 660.f};
    w.pdf.fill(1.f);
    return w;
}

TEST(CurvedTracking, TransmittanceIsBeerLambertOverArcLength) {
    const Medium fog = greyBox(0.1f, 0.2f);
    TrackingContext ctx({&fog});
    ctx.setWavelengths(fourWavelengths());
    Sampler sampler(1, 0, 0);
    // n = 2 − 0.1·y bends the path down hard: 10 m of arc span a shorter chord.
    const LinearIndexField field(2.0, -0.1);
    const Vec3 o(0, 1, 0), d = normalize(Vec3(1, 0.3f, 0));
    CurvedPathSettings set;
    set.tolerance = 1e-9;
    CurvedWalkEnd end;
    const SampledSpectrum T = curvedTransmittance(ctx, CurvedWalk{field, set, 10.f, nullptr},
                                                  Ray{o, d}, 550, sampler, &end);
    EXPECT_EQ(end.kind, CurvedWalkEnd::Kind::Reached);
    EXPECT_NEAR(end.arc, 10.f, 1e-5f);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(T[i], std::exp(-3.0), 2e-6) << i;
    // Beer–Lambert over the straight distance would differ by far more than that.
    const double straight = length(Vec3d(end.p) - Vec3d(o));
    EXPECT_GT(std::exp(-0.3 * straight) - std::exp(-3.0), 1e-3);
    const LinearProfilePath ex =
        exactLinearProfilePath(2.0, -0.1, Vec3d(0, 1, 0), Vec3d(o), Vec3d(d), 10.0);
    EXPECT_LT(length(Vec3d(end.p) - ex.endPoint), 1e-5);
}

TEST(CurvedTracking, ChordsStopAtTheSurfaceWhereTheCurvedPathMeetsIt) {
    GeometryScene geo;
    const int m = geo.addMaterial(Material::diffuse("ground", Spectrum(0.5f)));
    geo.addQuad(Vec3(-100, 0, 100), Vec3(200, 0, 0), Vec3(0, 0, -200), m);  // y = 0
    geo.commit();
    const ChordSurfaceTest surfaces = [&](const Ray& chord, float tMax) {
        Ray r = chord;
        r.tMax = tMax;
        const auto hit = geo.intersect(r);
        return hit ? hit->t : kInfinity;
    };
    TrackingContext ctx({});
    ctx.setWavelengths(fourWavelengths());
    Sampler sampler(2, 0, 0);
    // n = 1 − 0.05·y: a horizontal ray from 1 m bends down to the ground.
    const double k = -0.05;
    const LinearIndexField field(1.0, k);
    CurvedPathSettings set;
    set.tolerance = 1e-9;
    set.maxStep = 0.1;  // sagitta ≤ h²/(8R) = 0.01 / (8 · 19) m
    CurvedWalkEnd end;
    const SampledSpectrum T =
        curvedTransmittance(ctx, CurvedWalk{field, set, 100.f, surfaces},
                            Ray{Vec3(0, 1, 0), Vec3(1, 0, 0)}, 550, sampler, &end);
    ASSERT_EQ(end.kind, CurvedWalkEnd::Kind::Surface);
    EXPECT_EQ(T[0], 1.f);
    // Where the exact path reaches y = 0 (bisection on its arc length).
    double lo = 0, hi = 100;
    for (int i = 0; i < 80; ++i) {
        const double mid = 0.5 * (lo + hi);
        const LinearProfilePath p = exactLinearProfilePath(1.0, k, Vec3d(0, 1, 0), Vec3d(0, 1, 0),
                                                           Vec3d(1, 0, 0), mid);
        (p.endPoint.y > 0 ? lo : hi) = mid;
    }
    const LinearProfilePath hit =
        exactLinearProfilePath(1.0, k, Vec3d(0, 1, 0), Vec3d(0, 1, 0), Vec3d(1, 0, 0), lo);
    EXPECT_NEAR(end.p.y, 0.f, 1e-5f);
    EXPECT_NEAR(end.p.x, hit.endPoint.x, 1e-4);
    EXPECT_NEAR(end.arc, lo, 1e-4);
    EXPECT_GT(end.chords, 30);  // it did walk chord by chord
}

TEST(CurvedTracking, FreeFlightsAreExponentialInArcLength) {
    // Grey homogeneous: the majorant is σt, so every tentative collision is real.
    const float sigmaT = 0.5f;
    const Medium fog = greyBox(0.2f, 0.3f);
    TrackingContext ctx({&fog});
    ctx.setWavelengths(fourWavelengths());
    const LinearIndexField field(1.5, 0.04);
    CurvedPathSettings set;
    set.tolerance = 1e-7;
    const int n = 4000;
    double sum = 0;
    int beyondMean = 0;
    for (int i = 0; i < n; ++i) {
        Sampler sampler(3, uint64_t(i), 0);
        const CurvedWalkEnd end =
            trackCurvedCollisions(ctx, CurvedWalk{field, set, 40.f, nullptr},
                                  Ray{Vec3(0, 0, 0), normalize(Vec3(1, -0.5f, 0.2f))}, 550, sampler,
                                  [](const Collision&, float) { return Track::Stop; });
        ASSERT_EQ(end.kind, CurvedWalkEnd::Kind::Stopped);
        sum += end.arc;
        if (end.arc > 1 / sigmaT) ++beyondMean;
    }
    // Exp(σt): mean 1/σt (standard error 1/(σt·sqrt(n))), P(l > mean) = 1/e.
    EXPECT_NEAR(sum / n, 1 / sigmaT, 4 / (sigmaT * std::sqrt(double(n))));
    const double p = std::exp(-1.0);
    EXPECT_NEAR(double(beyondMean) / n, p, 4 * std::sqrt(p * (1 - p) / n));
}

}  // namespace
}  // namespace mirage
