// Projection maps for the photon pass (projection_map.h).
#include "photon/projection_map.h"

namespace mirage {

std::vector<TargetSphere> specularTargets(const GeometryScene& geometry) {
    std::vector<TargetSphere> targets;
    for (size_t i = 0; i < geometry.shapeCount(); ++i) {
        const ShapeInfo& shape = geometry.shape(int(i));
        if (!geometry.material(shape.material).specular()) continue;
        if (shape.type == ShapeType::Sphere)
            targets.push_back(TargetSphere{shape.center, shape.radius});
        else
            targets.push_back(
                TargetSphere{shape.bounds.center(), 0.5f * length(shape.bounds.diagonal())});
    }
    return targets;
}

bool ProjectionPlan::any() const {
    for (const auto& m : maps)
        if (m) return true;
    return false;
}

double ProjectionPlan::power() const {
    double sum = 0.0;
    for (const auto& m : maps)
        if (m) sum += m->power();
    return sum;
}

ProjectionPlan planProjection(const std::vector<const Light*>& lights,
                              const GeometryScene* geometry, const Bounds3& sceneBounds,
                              bool enabled) {
    ProjectionPlan plan;
    plan.maps.resize(lights.size());
    if (!enabled || !geometry || geometry->empty()) return plan;
    const ProjectionTargets targets{specularTargets(*geometry), sceneBounds};
    plan.targets = targets.spheres.size();
    if (targets.spheres.empty()) return plan;
    for (size_t l = 0; l < lights.size(); ++l) {
        std::unique_ptr<PhotonProjection> map = lights[l]->projection(targets);
        const double whole = lights[l]->emittedPower(sceneBounds);
        if (map && map->power() > 0.0 && map->power() <= kProjectionShare * whole)
            plan.maps[l] = std::move(map);
    }
    return plan;
}

}  // namespace mirage
