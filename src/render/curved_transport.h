// Curved light for the estimators behind the curved camera (render/curved_camera.h): what
// `single` and `volpath` need to bend their shadow rays (render/curved_shadow.h) and their
// scattered segments (volpath.cpp) as the photon pass bends photons — the same index field, the
// same Fermat stepper and its settings, the same step cap near surfaces
// (transport/surface_step_cap.h), the same curved length, and the sphere beyond which light at
// infinity is straight (transport/curved_connection.h). The curved camera builds it once per
// frame and hands it to the wrapped integrator through ThreadState::curved; without a
// [refraction] field it does not exist and every estimator stays straight, bit for bit.
#pragma once

#include <memory>

#include "render/render_scene.h"
#include "transport/curved_connection.h"

namespace mirage {

class CurvedTransport {
public:
    // `path` carries the step cap near this scene's surfaces already (as the camera's).
    CurvedTransport(std::shared_ptr<const IndexField> field, const CurvedPathSettings& path,
                    float maxArc, const RenderScene& scene)
        : mField(std::move(field)), mPath(path), mMaxArc(maxArc), mGeometry(scene.geometry.get()) {
        const Bounds3 b = scene.bounds();
        if (!b.empty()) mSphere = SceneSphere{b.center(), 0.5f * length(b.diagonal())};
        if (!scene.hasSurfaces()) mGeometry = nullptr;
    }

    // A path's flight: it ends at the nearest surface on a chord (*hit holds it), or on leaving
    // the scene's sphere.
    CurvedWalk flight(std::optional<SurfaceHit>* hit) const {
        const GeometryScene* geometry = mGeometry;
        return CurvedWalk{*mField, mPath, mMaxArc,
                          [geometry, hit](const Ray& chord, float tMax) {
                              if (!geometry) return kInfinity;
                              *hit = geometry->intersect(Ray{chord.o, chord.d, tMax});
                              return *hit ? (*hit)->t : kInfinity;
                          },
                          &mSphere};
    }
    // A shadow path's walk: any surface on a chord blocks it; it ends on leaving the sphere.
    CurvedWalk shadow() const {
        const GeometryScene* geometry = mGeometry;
        return CurvedWalk{
            *mField, mPath, mMaxArc,
            [geometry](const Ray& chord, float tMax) {
                return geometry && geometry->occluded(chord.o, chord.d, tMax) ? 0.f : kInfinity;
            },
            &mSphere};
    }
    double index(const Vec3& p, double lambdaNm) const { return mField->index(Vec3d(p), lambdaNm); }

private:
    std::shared_ptr<const IndexField> mField;
    CurvedPathSettings mPath;
    float mMaxArc;
    const GeometryScene* mGeometry;
    SceneSphere mSphere;
};

}  // namespace mirage
