// Curved camera rays around an integrator (curved_camera.h says what and what not).
#include "render/curved_camera.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cmath>
#include <optional>
#include <utility>

#include "render/curved_transport.h"
#include "render/path_recorder.h"
#include "transport/curved_tracking.h"
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
        // The wrapped integrator's shadow rays and scattered paths bend on the same terms
        // (render/curved_transport.h); the photon mapper's light has bent in its photon pass.
        mTransport = mPhotonPart || !mRefraction->bendTransport
                         ? nullptr
                         : std::make_unique<CurvedTransport>(mRefraction->field, mPath,
                                                             mRefraction->maxArc, scene);
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

    // Radiance arriving at the camera: Σ over chords of (transmittance of the chords before)
    // × (what the wrapped integrator sees along this chord alone), then the final ray. The
    // transmittances are separate estimates (transmittance()), independent of the chords'
    // radiance estimates, so each product is unbiased. L/n² is conserved along the path (the n²
    // law): radiance found at index n counts (nCam/n)² at the camera.
    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        PathRecorder rec(&out, ts);
        const CameraSample sample{scene, w, sampler, ts, rec};
        CurvedRay r(*mRefraction->field, ray, w);
        ts.curved = mTransport.get();
        // The photon part (XYZ, each photon at its own wavelength) is attenuated by the chords
        // before inside the estimate, through ts.photonView: T at the photon's wavelength.
        ts.photonView = ViewWeight();
        const CurvedPathResult path = traceCurvedPath(
            *mRefraction->field, Vec3d(ray.o), Vec3d(ray.d), r.lambda, mRefraction->maxArc, mPath,
            [&](const PathState& a, const PathState& b, bool) {
                return visitChord(sample, a, b, &r);
            });
        if (path.capped) mCapped.fetch_add(1, std::memory_order_relaxed);
        if (r.T.maxValue() <= 0.f) {
            rec.coverageThrough(r.T, 1.f);
            return out;
        }
        if (!r.atSurface) {
            // Beyond the curved part the path is taken as straight, through constant n.
            r.next = Ray{Vec3(path.end.r), Vec3(path.end.direction())};
            r.nNext = mRefraction->field->index(path.end.r, r.lambda);
        }
        const RadianceSample last = estimateAlong(sample, r, r.next, r.nNext);
        ts.photonView = ViewWeight();
        rec.coverageThrough(r.T, last.alpha);
        return out;
    }

private:
    // One camera sample, as every chord's estimate needs it.
    struct CameraSample {
        const RenderScene& scene;
        const SampledWavelengths& w;
        Sampler& sampler;
        ThreadState& ts;
        PathRecorder& rec;
    };

    // A curved camera ray as its chords are visited.
    struct CurvedRay {
        CurvedRay(const IndexField& field, const Ray& ray, const SampledWavelengths& w)
            : lambda(w.lambda[0]), nCam(field.index(Vec3d(ray.o), lambda)), nNext(nCam) {}
        double lambda;  // nm: the path's geometry is the hero wavelength's (curved_tracking.h)
        double nCam;    // the index at the camera
        SampledSpectrum T{1.f};  // the transmittance of the chords so far
        // The ray the wrapped integrator takes last: from the chord that met a surface
        // (atSurface), else straight on from the path's end; nNext is the index where it finds
        // its light.
        Ray next;
        double nNext;
        bool atSurface = false;
    };

    // The chord a → b of the camera ray's path: where it meets a surface, the wrapped
    // integrator takes it and everything beyond (the path stops); where it crosses a medium's
    // bounds, what the media along it emit and scatter towards it (the wrapped integrator,
    // stopped at the chord's end), then their transmittance over arc length (the chord
    // parametrised by arc: |d| = len/h). False ends the path.
    bool visitChord(const CameraSample& s, const PathState& a, const PathState& b,
                    CurvedRay* r) const {
        const Vec3 pa(a.r), pb(b.r);
        const float h = float(b.arc - a.arc), len = length(pb - pa);
        if (!(h > 0.f) || !(len > 0.f)) return true;
        const Vec3 unit = (pb - pa) / len;
        if (s.scene.hasSurfaces()) {
            Ray chord{pa, unit, len};
            if (const auto hit = s.scene.geometry->intersect(chord)) {
                // What the wrapped integrator finds there (the surface's radiance) is radiance
                // at the index of the hit, not of the chord's start, which may be a long chord
                // away.
                r->next = Ray{pa, unit};
                r->nNext = mRefraction->field->index(Vec3d(hit->p), r->lambda);
                r->atSurface = true;
                return false;
            }
        }
        if (!crossesMedia(s.scene, pa, unit, len)) return true;  // nothing to see or attenuate
        estimateAlong(s, *r, Ray{pa, unit, len}, mRefraction->field->index(a.r, r->lambda));
        const SampledSpectrum chordT =
            transmittance(s.ts.tracking, Ray{pa, unit * (len / h)}, h, s.sampler);
        r->T *= chordT;
        if (mPhotonPart)
            attenuate(Ray{pa, unit}, len, h, chordT, s.w, s.ts.tracking.timeOffset(),
                      &s.ts.photonView);
        return r->T.maxValue() > 0.f;
    }

    static bool crossesMedia(const RenderScene& scene, const Vec3& o, const Vec3& unit, float len) {
        bool inMedium = false;
        for (const auto& m : scene.media) {
            float t0, t1;
            inMedium |= m->worldBounds().intersect(o, unit, 0.f, len, &t0, &t1);
        }
        return inMedium;
    }

    // The wrapped integrator's estimate along `ray`, found at index n, added to the sample seen
    // through the chords before it (T) and by the n² law.
    RadianceSample estimateAlong(const CameraSample& s, const CurvedRay& r, const Ray& ray,
                                 double n) const {
        const RadianceSample est =
            s.rec.nested([&] { return mInner->Li(s.scene, ray, s.w, s.sampler, s.ts); });
        s.rec.addNested(est, r.T, radianceIndexScale(n, r.nCam));
        return est;
    }

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
        auto marched = [&](float lambda) {
            return std::pow(depth.transmittance(len, lambda), stretch);
        };
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
    std::unique_ptr<const CurvedTransport> mTransport;  // null for the photon mapper
};

}  // namespace

std::unique_ptr<Integrator> makeCurvedCameraIntegrator(
    std::unique_ptr<Integrator> inner, std::shared_ptr<const Refraction> refraction) {
    return std::make_unique<CurvedCameraIntegrator>(std::move(inner), std::move(refraction));
}

}  // namespace mirage
