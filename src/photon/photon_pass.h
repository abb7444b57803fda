// The photon pass (Jensen & Christensen 1998, with the full RTE of Gutierrez et al. 2005):
// photons are emitted from the lights and emissive media (medium_emitter.h) in proportion to
// their power, fly by delta tracking
// through the media, and at each real collision an albedo roulette decides between scattering
// (new direction from the phase function, power unchanged) and absorption. Scattering events
// are stored as volume photons. Parallel and deterministic: photon i's random numbers depend
// only on (seed, i), and the stored list is ordered by photon index.
//
// Surfaces (tracePhotonMaps): a flight ends at the nearest surface. Mirrors and glass reflect or
// refract the photon (glass by Fresnel roulette, at the photon's own wavelength, so dispersion
// needs no special case); a diffuse surface stores a surface photon, then an albedo roulette
// decides between absorption and a cosine-distributed bounce (power unchanged). Surface photons
// go to the caustic map when the photon's path so far is L S+ D (only specular bounces), to the
// global map when it has met a diffuse surface or scattered in a medium; a photon arriving
// straight from the light is direct light, which the render pass computes by NEE, and is not
// stored. The volume-photon rule is the same: a medium event is stored unless it is the first
// interaction of the photon (NEE computes that one) — light → glass → fog (a volume caustic) is
// stored, since no shadow ray passes through glass.
//
// Projection maps (projection_map.h): where a light's mirrors and glass are a small part of
// what it lights, its caustic paths — first event a specular hit — come from a stream of photons
// emitted towards them alone, and its ordinary photons end at such a hit.
//
// Fluorescence: a re-emission (photon_walk.h) is stored as a volume photon at the new
// wavelength, with the power after it and the absorbed wavelength as its flag (Photon::
// lambdaIn), first interaction or not: it is the inelastic source term of the transfer
// equation, which no shadow ray computes.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/progress.h"
#include "geometry/geometry_scene.h"
#include "light/light.h"
#include "medium/index_field.h"
#include "medium/medium.h"
#include "photon/photon.h"
#include "transport/curved_path.h"

namespace mirage {

struct PhotonPassSettings {
    uint64_t photons = 100000;  // photons emitted, over all lights
    uint64_t seed = 0;
    int maxBounces = 10000;  // cap on scattering events per photon (capped paths counted)
    // When the render pass computes single scattering by shadow rays, the first interaction
    // of each photon must not be stored, or direct light would be counted twice.
    bool storeFirstInteraction = false;
    // Curved light (docs/curved-light.md): with a field, every flight follows its Fermat path
    // (PhotonWalk::flyCurved) over at most curvedMaxArc metres of path, then goes on straight.
    // Shadow rays do not follow such paths, so the caller then sets storeFirstInteraction, and
    // it also stores light arriving straight from a light at a diffuse surface (global map).
    std::shared_ptr<const IndexField> field;
    CurvedPathSettings curvedPath;
    float curvedMaxArc = 1000.f;
    Progress::Mode progress = Progress::Mode::Auto;
    // Motion blur: each photon draws its time uniformly in [shutterOpen, shutterClose] (seconds
    // relative to the frame) and meets every medium as it is then; equal: the frame's time.
    float shutterOpen = 0.f, shutterClose = 0.f;
    // Projection maps (projection_map.h): a second stream of causticPhotons photons emitted
    // towards the mirrors and glass, for the lights whose projection is narrow; 0: as many as
    // `photons`. Never where light curves (field): the maps are straight-line geometry. Off by
    // default: a k-nearest estimate's noise is set by k, not by the photons' density, so the
    // caustic stream sharpens caustics more than it quietens them, and in media its faint,
    // dense photons share the one volume map with the main stream's bright ones and multiply
    // the noise (measured: docs/scene-file.md, "Projection maps").
    enum class Projection { Off, On };
    Projection projection = Projection::Off;
    uint64_t causticPhotons = 0;
    uint64_t causticPhotonsOrDefault() const {
        return causticPhotons > 0 ? causticPhotons : photons;
    }
};

struct PhotonPassStats {
    // Photons traced: both streams where projection maps split them (projection_map.h).
    uint64_t emitted = 0, stored = 0;
    // Cut at maxBounces or at the collision cap of one flight, or a curved flight stopped by
    // the ODE step cap (CurvedPathSettings::maxSteps) and continued straight.
    uint64_t cappedPaths = 0;
    uint64_t nonFinite = 0;  // photons dropped for a non-finite power/position (path ended)
    uint64_t fromMedia = 0;  // photons emitted by emissive media (fire)
    double mediumPower = 0;  // W over 360–830 nm, the media emitters' tabulated power
    // W, Σ of the main stream's photons' power as they left their sources (the caustic stream's
    // stand for part of the same power).
    double emittedPower = 0;
    double seconds = 0;
    // An interrupt (core/interrupt.h) stopped the pass between blocks of photons: the maps hold
    // only the blocks that finished, and the render that follows stops before its first tile.
    bool interrupted = false;

    // Adds the figures of another pass of the same scene (a render in passes traces one per
    // pass): counts, power and time sum; the media's tabulated power is the scene's, once.
    void add(const PhotonPassStats& pass);
};

struct PhotonMapLists {
    PhotonList volume;          // medium scattering events
    PhotonList surfaceGlobal;   // diffuse surfaces, after a diffuse bounce or a medium event
    PhotonList surfaceCaustic;  // diffuse surfaces, after specular bounces only (L S+ D)
};

// A finished photon pass: its maps and figures (what a .photons file holds, photon_file.h).
struct PhotonPassResult {
    PhotonMapLists maps;
    PhotonPassStats stats;
};

// The photon pass with surfaces (geometry may be null: then the same photons as tracePhotons).
PhotonMapLists tracePhotonMaps(const std::vector<const Light*>& lights,
                               const std::vector<const Medium*>& media,
                               const GeometryScene* geometry, const PhotonPassSettings& settings,
                               PhotonPassStats* stats);

// Whether a pass with these settings traces projection maps: On, and not where light curves.
bool projectionWanted(const PhotonPassSettings& settings);

PhotonList tracePhotons(const std::vector<const Light*>& lights,
                        const std::vector<const Medium*>& media, const PhotonPassSettings& settings,
                        PhotonPassStats* stats);

}  // namespace mirage
