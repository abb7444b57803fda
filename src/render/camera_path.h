// A camera path as every camera estimator walks it: the one per-sample set-up (a RadianceSample,
// its recorder, render/path_recorder.h, and a CameraPath from the camera ray), the flight to the
// next surface, and the steps at a surface and out of the scene that single scattering, the
// path tracer and the photon mapper's specular chain share. A new estimator starts from these
// instead of copying a neighbour's loop.
#pragma once

#include <optional>

#include "render/integrator.h"
#include "render/path_recorder.h"
#include "transport/path_vertex.h"
#include "transport/scatter_guide.h"

namespace mirage {

class SunShade;

// Where a camera path is between two vertices: its ray and throughput (PathSegment), and what
// its vertices so far decide about the next ones.
struct CameraPath : PathSegment {
    CameraPath(const Ray& cameraRay, const SampledWavelengths& w)
        : PathSegment{cameraRay, PathThroughput()}, wavelengths(w) {}

    // The wavelengths the path carries, those of the thread's tracking context; a fluorescent
    // re-emission switches them to the absorbed one (volpath), and `reemitted` says so.
    SampledWavelengths wavelengths;
    bool reemitted = false;
    int depth = 0;              // vertices before the current ray (scattering and specular)
    bool specularChain = true;  // every vertex so far a mirror or glass: escapes see the dome
    // The phase function's density of the ray's direction, where the medium vertex that drew
    // it left the lights at infinity to the ray (MediumLights::SkyByEscape), the share of
    // that vertex's estimates against lobe walks, and the rate it drew those lights' own
    // samples at (render/direct_light.h: SkyDraws); 0, 1 and 1 otherwise.
    float escapePdf = 0.f;
    float escapeShare = 1.f;
    float escapeSkyRate = 1.f;
    void leaveSkyToEscape(float pdf, float share, float skyRate) {
        escapePdf = pdf;
        escapeShare = share;
        escapeSkyRate = skyRate;
    }
    bool skyDark = false;  // SkyDraws::dark, carried to the next medium vertex
    const SunShade* sunShade = nullptr;  // SkyDraws::shade: the frame's, where it has one
    // Lobe walks (render/lobe_walk.h): whether the path draws them, the
    // probability s that a medium vertex starts one (lobeWalkStart), and the sum
    // Σ_j s r_j q^(k−1−j) over the medium vertices of the run the current ray ends.
    bool guided = false;
    float walkStart = 1.f;
    float lobeRatios = 0.f;
    // The weight of the emission the current ray's flight scores: against the line sample of
    // the medium vertex it starts from (volpath, render/line_emission.h); 1 elsewhere.
    float emissionWeight = 1.f;
};

// The flight ahead of a ray: the nearest surface on it, if any, and where the flight through the
// media ends (that surface, or the ray's tMax).
struct SurfaceAhead {
    std::optional<SurfaceHit> hit;
    float tEnd = 0.f;
};
SurfaceAhead surfaceAhead(const RenderScene& scene, const Ray& ray);

// The flight along the path's ray to the surface ahead (or out of the scene), followed to its
// end (transport/scatter_point.h): emission at its every tentative collision, next-event
// estimation (where `nee`) at the scattering points chosen along it, drawn by `guide` (null:
// ∝ T σs), and on the camera ray the pixel's coverage (holdouts show the plate by T and take
// their share of it). β then carries the flight's transmittance. True when the flight reached
// its end. Single scattering walks every flight of its path so; the photon mapper's final
// gather its gather rays' (render/photon_integrator.cpp).
bool scatterAlongFlight(const RenderScene& scene, const SurfaceAhead& ahead,
                        const ScatterGuide* guide, bool nee, Sampler& sampler, ThreadState& ts,
                        CameraPath& path, PathRecorder& rec);

// The light a camera path gathers at the surface its ray reached, before it goes on: the
// surface's emission and, where it is diffuse and `nee`, next-event estimation to the lights
// (render/direct_light.h); then the vertex enters the record. Returns the surface's material.
const Material& gatherAtSurface(const RenderScene& scene, const SurfaceHit& hit, bool nee,
                                Sampler& sampler, ThreadState& ts, CameraPath& path,
                                PathRecorder& rec);

// A path that leaves the scene sees the lights at infinity (the dome) where no next-event
// estimate has counted them: on the camera ray and after mirrors and glass, and after a medium
// vertex that left them to it (escapePdf, render/direct_light.h: skyAtEscape).
void escapeToDome(const RenderScene& scene, const CameraPath& path, ThreadState& ts,
                  PathRecorder& rec);

}  // namespace mirage
