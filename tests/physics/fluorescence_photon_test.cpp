// Fluorescence in the photon map against the reference path tracer. Scene: a 2 m cube of
// chlorophyll-rich sea water (pure water + 30 mg/m³ chlorophyll a, a bloom, with Γ = 0.1, the
// top of Gutierrez et al. 2005's range, band 685 nm / FWHM 25 nm) lit from above by a blue sun
// (400–500 nm only), seen from the front. The photon pass stores every re-emission at its new
// wavelength with the isotropic lobe (photon_pass.h, volume_estimate.h); volpath samples the
// inelastic source backwards (transport/reemission.h). Both carry energy, so both scale a
// re-emission by λi/λo.
//
// Only fluorescence puts light above 550 nm into this scene. volpath measures it directly:
// camera wavelengths drawn in 600–780 nm, reduced to CIE X and Y as the film does. The photon
// map's part of the photon integrator is the beam estimate over the stored photons, in XYZ over
// all wavelengths at once; here it is run, as photon_integrator.cpp runs it, over the photons
// above 550 nm only — the fluorescent ones, stored at re-emission and at every later
// scattering (their disc radii are then set by their own neighbours; without that split the
// blue photons' 50 times larger X would drown the comparison in their noise). The single-
// scatter part of the photon integrator adds nothing there (the sun has no red). The two must
// agree within 3 combined standard errors (photon map: the spread over independent photon
// passes; volpath: over independent camera samples).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "geometry/material.h"
#include "medium/ocean_components.h"
#include "photon/beam_estimate.h"
#include "photon/photon_pass.h"
#include "photon/photon_walk.h"
#include "render/integrator.h"
#include "spectrum/cie.h"

using namespace mirage;

namespace {

constexpr float kChlorophyll = 30.f;  // mg/m³: a bloom
constexpr float kGamma = 0.1f;

RenderScene fluorescentWater(float gamma) {
    ShaderDesc s;
    s.name = "test-ocean";
    MediumComponent water, chl;
    water.name = "water";
    makeWater(&water);
    chl.name = "chlorophyll";
    makeChlorophyll(&chl);
    chl.concentration = kChlorophyll;
    chl.quantumEfficiency = gamma;
    chl.emissionPeakNm = 685.f;
    chl.emissionFwhmNm = 25.f;
    s.components = {water, chl};
    Bounds3 box;
    box.expand(Vec3(0.f));
    box.expand(Vec3(2.f));
    RenderScene scene;
    scene.media.push_back(std::make_unique<Medium>(s, box, Transform(), 1.f));
    Spectrum blue = Spectrum::fromTable({360.f, 399.f, 400.f, 500.f, 501.f, 830.f},
                                        {0.f, 0.f, 1.f, 1.f, 0.f, 0.f});
    scene.lights.push_back(makeDistantLight(normalize(Vec3(0.2f, -1.f, -0.3f)), 1000.f, blue));
    return scene;
}

// A camera ray: from (1, 1, 5) through a random point of the plane of the cube's front face,
// over a square 0.4 m wider on each side than the face, so that the rays see the whole cube
// with a margin: every photon's disc then lies inside the sampled region, and the mean over
// the rays keeps all of its flux. (Over a region that cuts through the cube, the kernel blur
// moves flux across the region's edge: measured −8 % with the rays inset by 0.2 m, where the
// fluorescence near the lit top face is densest.)
Ray cameraRay(Sampler& s) {
    Vec3 o(1.f, 1.f, 5.f);
    Vec3 target(-0.4f + 2.8f * s.get1D(), -0.4f + 2.8f * s.get1D(), 2.f);
    return Ray{o, normalize(target - o), kInfinity};
}

// XYZ of one camera sample at wavelengths w, as the film would add it.
Vec3 sampleXyz(const Integrator& integrator, const RenderScene& scene, ThreadState& ts,
               const SampledWavelengths& w, Sampler& s) {
    ts.tracking.setWavelengths(w);
    Ray ray = cameraRay(s);
    RadianceSample r = integrator.Li(scene, ray, w, s, ts);
    return spectrumToXyz(r.L, w) + r.xyz;
}

// Four stratified wavelengths uniform over [lo, hi] nm.
SampledWavelengths uniformBand(float u, float lo, float hi) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        float up = u + float(i) / kSpectrumSamples;
        if (up >= 1.f) up -= 1.f;
        w.lambda[size_t(i)] = lo + (hi - lo) * up;
        w.pdf[size_t(i)] = 1.f / (hi - lo);
    }
    return w;
}

struct Mean {
    double x = 0, y = 0, seX = 0, seY = 0;
};

}  // namespace

TEST(FluorescencePhotonMap, AgreesWithVolPathOnTheFluorescentBand) {
    RenderScene on = fluorescentWater(kGamma);

    // volpath: the light above 600 nm, independent samples.
    Mean vp;
    {
        auto integrator = makeVolPathIntegrator();
        ThreadState ts(on);
        const int n = 15000000;
        double sx = 0, sx2 = 0, sy = 0, sy2 = 0;
        for (int i = 0; i < n; ++i) {
            Sampler a(5, uint64_t(i), 0);
            Vec3 d = sampleXyz(*integrator, on, ts, uniformBand(a.get1D(), 600.f, 780.f), a);
            sx += d.x;
            sx2 += double(d.x) * d.x;
            sy += d.y;
            sy2 += double(d.y) * d.y;
        }
        vp.x = sx / n;
        vp.y = sy / n;
        vp.seX = std::sqrt(std::max(0.0, sx2 / n - vp.x * vp.x) / n);
        vp.seY = std::sqrt(std::max(0.0, sy2 / n - vp.y * vp.y) / n);
    }

    // Photon map: the beam estimate over the fluorescent photons, one mean per independent
    // photon pass (seed).
    const int passes = 8, rays = 8000;
    std::vector<double> xs, ys;
    size_t fluorescentPhotons = 0;
    const std::vector<const Medium*> media = on.mediaPointers();
    const float maxRadius = 0.1f * length(on.bounds().diagonal());  // the integrator's default
    for (int seed = 0; seed < passes; ++seed) {
        PhotonPassSettings ps;
        ps.photons = 300000;
        ps.seed = uint64_t(100 + seed);
        ps.storeFirstInteraction = false;  // as the photon integrator traces them
        ps.progress = Progress::Mode::Quiet;
        PhotonList red;
        for (const Photon& p : tracePhotons({on.lights[0].get()}, media, ps, nullptr))
            if (p.lambda > 550.f) red.push_back(p);
        fluorescentPhotons += red.size();
        VolumePhotons photons(std::move(red), media);
        BeamEstimator beam(photons, photons.map().photonRadii(16, 1e-4f * maxRadius, maxRadius));
        RayOpticalDepth depth(media);
        std::vector<BeamHit> hits;
        double sx = 0, sy = 0;
        for (int i = 0; i < rays; ++i) {
            Sampler a(ps.seed, uint64_t(i), 1);
            Ray ray = cameraRay(a);
            depth.march(ray, ray.tMax);
            Vec3 xyz = beam.estimate(ray, ray.tMax, depth, &hits);
            sx += xyz.x;
            sy += xyz.y;
        }
        xs.push_back(sx / rays);
        ys.push_back(sy / rays);
    }
    auto meanAndSe = [](const std::vector<double>& v, double* se) {
        double m = 0, m2 = 0;
        for (double x : v) m += x / double(v.size());
        for (double x : v) m2 += (x - m) * (x - m);
        *se = std::sqrt(m2 / double(v.size() - 1) / double(v.size()));
        return m;
    };
    Mean pm;
    pm.x = meanAndSe(xs, &pm.seX);
    pm.y = meanAndSe(ys, &pm.seY);

    double sigmaX = std::sqrt(vp.seX * vp.seX + pm.seX * pm.seX);
    double sigmaY = std::sqrt(vp.seY * vp.seY + pm.seY * pm.seY);
    std::printf("fluorescent X: volpath %.5g ± %.2g, photon map %.5g ± %.2g, ratio %.4f ± %.4f\n"
                "fluorescent Y: volpath %.5g ± %.2g, photon map %.5g ± %.2g, ratio %.4f ± %.4f\n"
                "(photon map: %d passes, %zu fluorescent photons)\n",
                vp.x, vp.seX, pm.x, pm.seX, pm.x / vp.x, sigmaX / vp.x, vp.y, vp.seY, pm.y,
                pm.seY, pm.y / vp.y, sigmaY / vp.y, passes, fluorescentPhotons);
    // The fluorescence is there, resolved well enough for the comparison to mean something…
    ASSERT_GT(vp.x, 10 * vp.seX);
    ASSERT_GT(pm.x, 5 * pm.seX);
    // …and the two agree within 3σ.
    EXPECT_NEAR(pm.x, vp.x, 3 * sigmaX);
    EXPECT_NEAR(pm.y, vp.y, 3 * sigmaY);
}

TEST(FluorescencePhotonMap, ReemittedPhotonsAreStoredAndCreateNoEnergy) {
    RenderScene scene = fluorescentWater(kGamma);
    std::vector<const Light*> lights{scene.lights[0].get()};
    PhotonPassSettings ps;
    ps.photons = 100000;
    ps.seed = 9;
    ps.progress = Progress::Mode::Quiet;
    PhotonList photons = tracePhotons(lights, scene.mediaPointers(), ps, nullptr);
    const float photonPower = lights[0]->emittedPower(scene.bounds()) / float(ps.photons);
    size_t reemitted = 0;
    for (const Photon& p : photons) {
        // Every photon starts with Φ/N (a sun samples its emission exactly), keeps it through
        // elastic events (one HG lobe per path wavelength) and loses λi/λo at each re-emission.
        ASSERT_LE(p.power, photonPower * (1.f + 1e-5f));
        if (!p.reemitted()) continue;
        ++reemitted;
        ASSERT_GE(p.lambda, p.lambdaIn);  // Stokes: the photon's energy hc/λ falls
        ASSERT_LE(p.power, photonPower * p.lambdaIn / p.lambda * (1.f + 1e-5f));
    }
    // Re-emissions are in the map, also those at a photon's first interaction.
    EXPECT_GT(reemitted, size_t(500));
    std::printf("%zu photons stored, %zu of them re-emissions\n", photons.size(), reemitted);
}

TEST(FluorescencePhotonMap, PowerLeavingTheCubeAgreesWithVolPath) {
    // No kernel here: the fluorescent power (as CIE X) leaving the cube, counted exactly from
    // the photon walk's escaping photons, and from volpath as Φ = ∫_A ∫ L cos θ dω dA over the
    // cube's faces (a face point uniform over the 24 m², a cosine-weighted direction).
    RenderScene scene = fluorescentWater(kGamma);
    const std::vector<const Medium*> media = scene.mediaPointers();
    const Light& sun = *scene.lights[0];
    const Bounds3 bounds = scene.bounds();

    const int passes = 8, photons = 200000;
    std::vector<double> walkX;
    PhotonWalk walk(media);
    for (int pass = 0; pass < passes; ++pass) {
        const double power = sun.emittedPower(bounds) / double(photons);
        double x = 0;
        for (int i = 0; i < photons; ++i) {
            Sampler s(uint64_t(200 + pass), uint64_t(i), 0);
            PhotonEmission em;
            if (!sun.emitPhoton(bounds, s, &em)) continue;
            walk.setWavelength(em.lambda);
            double w = power * em.weight;
            Ray ray{em.origin, em.direction, kInfinity};
            for (int events = 0; events < 100000; ++events) {
                FlightEvent ev = walk.fly(ray, kInfinity, s);
                if (ev.end == FlightEnd::Absorbed) break;
                if (ev.end == FlightEnd::Escaped) {
                    if (walk.wavelength() > 550.f)
                        x += w * cieXyz(walk.wavelength()).x / kCieYIntegral;
                    break;
                }
                w *= ev.weight;
                ray = Ray{ev.p, ev.wo, kInfinity};
            }
        }
        walkX.push_back(x);
    }

    auto integrator = makeVolPathIntegrator();
    ThreadState ts(scene);
    const int n = 4000000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Sampler s(7, uint64_t(i), 0);
        int face = std::min(5, int(6.f * s.get1D()));
        int axis = face / 2;
        float side = face % 2 ? 2.f : 0.f;
        Vec3 x(2.f * s.get1D(), 2.f * s.get1D(), 2.f * s.get1D());
        x[axis] = side;
        Vec3 inward(0.f);
        inward[axis] = face % 2 ? -1.f : 1.f;
        Vec3 local = sampleCosineHemisphere(s.get1D(), s.get1D());
        Frame frame(inward);
        Vec3 d = frame.toWorld(local);
        Ray ray{x - d * 1e-3f, d, kInfinity};
        SampledWavelengths w = uniformBand(s.get1D(), 600.f, 780.f);
        ts.tracking.setWavelengths(w);
        RadianceSample r = integrator->Li(scene, ray, w, s, ts);
        double v = spectrumToXyz(r.L, w).x * kPi * 24.0;
        sum += v;
        sum2 += v * v;
    }
    double vp = sum / n, vpSe = std::sqrt(std::max(0.0, sum2 / n - vp * vp) / n);
    double wm = 0, wm2 = 0;
    for (double x : walkX) wm += x / passes;
    for (double x : walkX) wm2 += (x - wm) * (x - wm);
    double wSe = std::sqrt(wm2 / (passes - 1) / passes);
    std::printf("fluorescent power leaving the cube (CIE X, W): photon walk %.5g ± %.2g, volpath "
                "%.5g ± %.2g, ratio %.4f\n",
                wm, wSe, vp, vpSe, wm / vp);
    EXPECT_NEAR(wm, vp, 3 * std::sqrt(wSe * wSe + vpSe * vpSe));
}
