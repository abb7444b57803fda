// Projection maps for the photon pass (Jensen 2001, §5.1.3 and §9.3): caustic photons emitted
// only towards the scene's mirrors and glass, instead of the few of every light's photons that
// happen to meet them.
//
// The split. Every photon path from a light is either caustic — its first event after the light
// is a hit on a specular surface — or not. With projection maps the pass traces two streams:
// the main stream, the lights' ordinary emission (photon_pass.h), whose caustic paths end at
// that first hit; and the caustic stream, drawn from the lights' projection maps (light/
// projection.h), whose paths end unless their first event is that hit. Past it a caustic
// path stores what any path stores (volume caustics, the surface caustic map, and whatever
// follows a diffuse bounce). Each stream estimates its half of path space without bias, so
// their sum is the estimate of one stream that emits everywhere, with the caustic half at the
// density of the caustic stream's own photon count. A projection holds every direction that
// reaches a specular object along a straight line, so the split is exact where light travels
// straight; where a refractive-index field bends it the pass keeps one stream.
//
// Which lights. A light's projection pays where it is a small part of what the light sends
// into the scene: a lamp far from a glass ball, the sun over a small mirror. Where it covers
// half or more (a spot aimed at the ball, a light inside a specular sphere's bounds) the
// caustic stream would add at most twice the density at the cost of a second stream, and the
// light keeps one; so do quad and surface lights, which have no projection.
#pragma once

#include <memory>
#include <vector>

#include "geometry/geometry_scene.h"
#include "light/light.h"

namespace mirage {

// A light whose projection sends at most this share of what it sends into the scene gets one.
constexpr double kProjectionShare = 0.5;

// The mirrors and glass of a scene as the projection sees them: a sphere shape itself, any
// other shape the sphere about its bounding box.
std::vector<TargetSphere> specularTargets(const GeometryScene& geometry);

// The projection maps of one photon pass.
struct ProjectionPlan {
    // Per light (the pass's order): its projection, or null when its caustic paths stay in the
    // main stream.
    std::vector<std::unique_ptr<PhotonProjection>> maps;
    size_t targets = 0;  // specular objects aimed at

    bool any() const;
    double power() const;  // W: Σ of the maps' power()
};

// The plan for these lights and surfaces (null: none) in a scene of the given bounds: empty
// (no map) when `enabled` is false or nothing is specular.
ProjectionPlan planProjection(const std::vector<const Light*>& lights,
                              const GeometryScene* geometry, const Bounds3& sceneBounds,
                              bool enabled);

}  // namespace mirage
