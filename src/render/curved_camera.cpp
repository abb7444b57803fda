// Curved camera rays around an integrator (curved_camera.h says what and what not).
#include "render/curved_camera.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cmath>
#include <optional>
#include <utility>

#include "transport/ray_optical_depth.h"
#include "transport/surface_step_cap.h"
#include "transport/tracking.h"

namespace mirage {

namespace {

class CurvedCameraIntegrator final : public Integrator {
public:
    CurvedCameraIntegrator(std::unique_ptr<Integrator> inner,
                           std::shared_ptr<const Refraction> refraction)
        : mInner(std::move(inner)), mRefraction(std::move(refraction)) {}

    const IntegratorInfo& info() const override { return mInner->info(); }
    std::string name() const override { return mInner->name() + " (curved camera rays)"; }
    using Integrator::preprocess;
    void preprocess(const RenderScene& scene, uint64_t frameSamples) override {
        mInner->preprocess(scene, frameSamples);
        mPhotonPart = mInner->info().photonPass;
        const std::vector<const Medium*> media = scene.mediaPointers();
        mDepth = std::make_unique<tbb::enumerable_thread_specific<RayOpticalDepth>>(
            [media] { return RayOpticalDepth(media); });
        // The step cap near surfaces (surface_step_cap.h): short chords where a path meets or
        // grazes a surface, so that the hit found on the chord is the path's.
        mPath = mRefraction->path;
        if (mPath.capNearSurfaces && scene.hasSurfaces()) {
            const GeometryScene* geometry = scene.geometry.get();
            mPath.stepCap = surfaceStepCap(mRefraction->field.get(), mPath.tolerance,
                                           [geometry](const Vec3d& o, const Vec3d& d) {
                                               return geometry->surfaceDistance(o, d);
                                           });
        }
    }
    void beginPass(const RenderScene& scene, int pass) override { mInner->beginPass(scene, pass); }
    // The wrapped integrator's figures (its photon pass among them), and the camera rays whose
    // curved path reached the ODE step cap (CurvedPathSettings::maxSteps) and went on straight
    // from there: a bias, counted beside the wrapped integrator's caps.
    IntegratorStats stats() const override {
        IntegratorStats s = mInner->stats();
        s.cappedPaths += mCapped.load();
        return s;
    }

    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        const Refraction& rf = *mRefraction;
        // The path's geometry is the hero wavelength's (curved_tracking.h).
        const double lambda = w.lambda[0];
        const double nCam = rf.field->index(Vec3d(ray.o), lambda);
        // Radiance arriving at the camera: Σ over chords of (transmittance of the chords before)
        // × (what the wrapped integrator sees along this chord alone), then the final ray. The
        // transmittances are separate estimates (transmittance()), independent of the chords'
        // radiance estimates, so each product is unbiased. L/n² is conserved along the path
        // (the n² law): radiance found at index n counts (nCam/n)² at the camera.
        RadianceSample out;
        out.L = SampledSpectrum(0.f);
        SampledSpectrum T(1.f);
        // The photon part (XYZ, each photon at its own wavelength) is attenuated by the chords
        // before inside the estimate, through ts.photonView: T at the photon's wavelength.
        ViewWeight& prefix = ts.photonView;
        prefix = ViewWeight();
        // The sample's passes: each chord's go to a scratch first, weighted as its radiance.
        AovSample* const aov = ts.aov;
        std::optional<AovSample> chordAov;
        if (aov) chordAov.emplace(*aov);  // the same parts, reset per chord
        // The chords are not the straight camera ray the data passes describe: they walk it
        // themselves (render/camera_ray_data.h).
        CameraRayData* const data = ts.cameraData;
        auto inner = [&](const Ray& r) {
            if (aov) {
                chordAov->reset();
                ts.aov = &*chordAov;
            }
            ts.cameraData = nullptr;
            RadianceSample s = mInner->Li(scene, r, w, sampler, ts);
            ts.aov = aov;
            ts.cameraData = data;
            return s;
        };
        auto add = [&](const RadianceSample& s, double n) {
            const float k = float((nCam / n) * (nCam / n));
            out.L += s.L * T * k;
            out.xyz += s.xyz * k;
            if (aov) aov->addWeighted(*chordAov, T, k);
        };
        bool atSurface = false;
        Ray next;
        double nNext = nCam;  // the index where the wrapped integrator's last ray finds light
        auto visit = [&](const PathState& a, const PathState& b, bool) {
            const Vec3 pa(a.r), pb(b.r);
            const float h = float(b.arc - a.arc), len = length(pb - pa);
            if (!(h > 0.f) || !(len > 0.f)) return true;
            const Vec3 unit = (pb - pa) / len;
            if (scene.hasSurfaces()) {
                Ray chord{pa, unit, len};
                if (const auto hit = scene.geometry->intersect(chord)) {
                    // The wrapped integrator takes this chord and everything beyond it. What
                    // it finds there (the surface's radiance) is radiance at the index of the
                    // hit, not of the chord's start, which may be a long chord away.
                    next = Ray{pa, unit};
                    nNext = rf.field->index(Vec3d(hit->p), lambda);
                    atSurface = true;
                    return false;
                }
            }
            bool inMedium = false;
            for (const auto& m : scene.media) {
                float t0, t1;
                inMedium |= m->worldBounds().intersect(pa, unit, 0.f, len, &t0, &t1);
            }
            if (!inMedium) return true;  // nothing to see or to attenuate on this chord
            // What the media along this chord emit and scatter towards it (the wrapped
            // integrator, stopped at the chord's end), then their transmittance over arc
            // length (the chord parametrised by arc: |d| = len/h).
            add(inner(Ray{pa, unit, len}), rf.field->index(a.r, lambda));
            const SampledSpectrum chordT =
                transmittance(ts.tracking, Ray{pa, unit * (len / h)}, h, sampler);
            T *= chordT;
            if (mPhotonPart)
                attenuate(Ray{pa, unit}, len, h, chordT, w, ts.tracking.timeOffset(), &prefix);
            return T.maxValue() > 0.f;
        };
        const CurvedPathResult r = traceCurvedPath(*rf.field, Vec3d(ray.o), Vec3d(ray.d), lambda,
                                                   rf.maxArc, mPath, visit);
        if (r.capped) mCapped.fetch_add(1, std::memory_order_relaxed);
        if (T.maxValue() <= 0.f) {
            out.alpha = 1.f;
            return out;
        }
        if (!atSurface) {
            // Beyond the curved part the path is taken as straight, through constant n.
            next = Ray{Vec3(r.end.r), Vec3(r.end.direction())};
            nNext = rf.field->index(r.end.r, lambda);
        }
        const RadianceSample last = inner(next);
        add(last, nNext);
        prefix = ViewWeight();
        out.alpha = 1.f - T.average() * (1.f - last.alpha);
        return out;
    }

private:
    // The chord's transmittance at every wavelength, into the photon estimates' prefix. The
    // path stops where the ratio-tracked T̂ of its four wavelengths reaches 0 (its roulette), so
    // the photon part must carry T̂ too, or the light of the chords a killed path never visits
    // is lost without the survivors' compensation (a 2 % darkening, measured). Its colour comes
    // from the chord's optical depth marched at every wavelength (stretched from the straight
    // chord's length len to the arc length h the path covers):
    //     W(λ) = mean_i T̂(λi) · T_m(λ) / mean_i T_m(λi),
    // whose expectation is T(λ) up to the march's own error; in grey media it is T̂'s mean.
    // The march is made at the camera sample's time (motion blur), like the chord's T̂.
    void attenuate(const Ray& chord, float len, float h, const SampledSpectrum& chordT,
                   const SampledWavelengths& w, float time, ViewWeight* prefix) const {
        RayOpticalDepth& depth = mDepth->local();
        depth.setTimeOffset(time);
        depth.march(chord, len);
        if (depth.empty() || depth.grey()) {
            prefix->scale(chordT.average());
            return;
        }
        const float stretch = h / len;
        auto marched = [&](float lambda) { return std::pow(depth.transmittance(len, lambda), stretch); };
        float mean = 0.f;
        for (float lambda : w.lambda) mean += marched(lambda) / float(kSpectrumSamples);
        prefix->scale(mean > 0.f ? chordT.average() / mean : 0.f);
        prefix->multiply(marched);
    }

    std::unique_ptr<Integrator> mInner;
    std::shared_ptr<const Refraction> mRefraction;
    CurvedPathSettings mPath;  // the refraction's, with the step cap near this scene's surfaces
    mutable std::atomic<uint64_t> mCapped{0};
    bool mPhotonPart = false;  // the wrapped integrator returns a photon part (XYZ)
    std::unique_ptr<tbb::enumerable_thread_specific<RayOpticalDepth>> mDepth;
};

}  // namespace

std::unique_ptr<Integrator> makeCurvedCameraIntegrator(std::unique_ptr<Integrator> inner,
                                                       std::shared_ptr<const Refraction> refraction) {
    return std::make_unique<CurvedCameraIntegrator>(std::move(inner), std::move(refraction));
}

}  // namespace mirage
