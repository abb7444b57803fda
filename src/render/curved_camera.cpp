// Curved camera rays around an integrator (curved_camera.h says what and what not).
#include "render/curved_camera.h"

#include <utility>

#include "transport/tracking.h"

namespace mirage {

namespace {

class CurvedCameraIntegrator final : public Integrator {
public:
    CurvedCameraIntegrator(std::unique_ptr<Integrator> inner,
                           std::shared_ptr<const Refraction> refraction)
        : mInner(std::move(inner)), mRefraction(std::move(refraction)) {}

    std::string name() const override { return mInner->name() + " (curved camera rays)"; }
    void preprocess(const RenderScene& scene) override { mInner->preprocess(scene); }
    uint64_t cappedPaths() const override { return mInner->cappedPaths(); }
    std::string summary() const override { return mInner->summary(); }

    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        const Refraction& rf = *mRefraction;
        // The path's geometry is the hero wavelength's (curved_tracking.h).
        const double lambda = w.lambda[0];
        SampledSpectrum T(1.f);
        bool atSurface = false;
        Ray next;
        auto visit = [&](const PathState& a, const PathState& b, bool) {
            const Vec3 pa(a.r), pb(b.r);
            const float h = float(b.arc - a.arc), len = length(pb - pa);
            if (!(h > 0.f) || !(len > 0.f)) return true;
            const Vec3 unit = (pb - pa) / len;
            if (scene.hasSurfaces()) {
                Ray chord{pa, unit, len};
                if (scene.geometry->intersect(chord)) {
                    // The wrapped integrator takes this chord: it finds the same surface and
                    // attenuates up to it itself.
                    next = Ray{pa, unit};
                    atSurface = true;
                    return false;
                }
            }
            if (!scene.media.empty()) {
                // Optical depth over arc length: the chord parametrised by arc (|d| = len/h).
                T *= transmittance(ts.tracking, Ray{pa, unit * (len / h)}, h, sampler);
                if (T.maxValue() <= 0.f) return false;
            }
            return true;
        };
        const CurvedPathResult r = traceCurvedPath(*rf.field, Vec3d(ray.o), Vec3d(ray.d), lambda,
                                                   rf.maxArc, rf.path, visit);
        RadianceSample s;
        if (T.maxValue() <= 0.f) {
            s.L = SampledSpectrum(0.f);
            s.alpha = 1.f;
            return s;
        }
        if (!atSurface) next = Ray{Vec3(r.end.r), Vec3(r.end.direction())};
        s = mInner->Li(scene, next, w, sampler, ts);
        // n² law: L/n² is conserved along the path, so L_camera = L_end · (n_camera/n_end)².
        const double nCam = rf.field->index(Vec3d(ray.o), lambda);
        const double nEnd = rf.field->index(Vec3d(next.o), lambda);
        const float k = float((nCam / nEnd) * (nCam / nEnd));
        s.L = s.L * T * k;
        const float tMean = T.average();
        s.xyz = s.xyz * (tMean * k);  // already reduced to XYZ: the mean transmittance
        s.alpha = 1.f - tMean * (1.f - s.alpha);
        return s;
    }

private:
    std::unique_ptr<Integrator> mInner;
    std::shared_ptr<const Refraction> mRefraction;
};

}  // namespace

std::unique_ptr<Integrator> makeCurvedCameraIntegrator(std::unique_ptr<Integrator> inner,
                                                       std::shared_ptr<const Refraction> refraction) {
    return std::make_unique<CurvedCameraIntegrator>(std::move(inner), std::move(refraction));
}

}  // namespace mirage
