// Free flights and transmittance along curved light paths (Gutierrez et al. 2005: photons and
// camera rays follow Fermat paths where the refractive index varies). The path stepper
// (curved_path.h) hands over one chord per accepted step; each chord is
//   - tested against the surfaces (a callback, so that transport does not depend on geometry:
//     the renderer passes GeometryScene::intersect), and the walk ends at the first hit;
//   - tracked with the straight-line trackers of tracking.h, parametrised by arc length: the
//     chord ray runs from the step's start to its end with direction (end − start)/h, so its
//     parameter t ∈ [0, h] is arc length and the optical depth the trackers accumulate,
//     ∫σ dt, is the optical depth over arc length (the chord is only where σ is looked up).
// The Poisson processes of tentative collisions are memoryless, so restarting them at every
// chord is exact. The path's geometry is that of one wavelength (the hero wavelength, as for
// dispersive glass); in air the spread is ~1e−4 of the bending (air_index.h).
//
// Surface hits are found on the chord, which departs from the path by at most its sagitta
// h²/(8R), R ≥ n/|∇n| the path's radius of curvature: CurvedPathSettings::maxStep or stepCap
// bound it.
#pragma once

#include <cmath>
#include <functional>

#include "medium/index_field.h"
#include "transport/curved_path.h"
#include "transport/tracking.h"

namespace mirage {

// The nearest surface along a chord: `chord` has a unit direction, the answer is its distance in
// (0, tMax), or +∞ for none.
using ChordSurfaceTest = std::function<float(const Ray& chord, float tMax)>;

// A sphere a walk may be bound to: the scene's, beyond which light is straight
// (curved_connection.h).
struct SceneSphere {
    Vec3 center;
    float radius = 0.f;
    bool contains(const Vec3& p) const { return length(p - center) <= radius; }
};

// A walk along curved paths as the trackers take it: the field and the stepper's settings
// (curved_path.h), the arc length it may cover (m), the surfaces it may meet (an empty test:
// none), and the sphere it ends on leaving (null: none). It starts from a ray's origin along its
// unit direction, on the path of one wavelength.
struct CurvedWalk {
    const IndexField& field;
    const CurvedPathSettings& settings;
    float maxArc;
    ChordSurfaceTest surfaces;
    const SceneSphere* bounds = nullptr;
};

struct CurvedWalkEnd {
    // Reached: maxArc walked; Left: the chord that left `bounds` walked, `direction` the path's
    // there.
    enum class Kind { Reached, Surface, Stopped, Capped, Left } kind = Kind::Reached;
    Vec3 p;              // where the walk ended (world, m)
    Vec3 direction;      // unit path direction there (at a surface: the chord's direction)
    float arc = 0;       // arc length from the origin, m
    Ray chord;           // the last chord, unit direction (for the caller's surface query)
    float chordT = 0;    // distance along `chord` of the end
    int64_t chords = 0;  // chords walked
};

// Radiance along a path through a varying index keeps L/n² (the n² law): the factor that takes
// radiance at index nFrom to index nTo.
inline float radianceIndexScale(double nFrom, double nTo) {
    return float((nTo / nFrom) * (nTo / nFrom));
}

// One chord of a curved path as the trackers see it: `arcRay` starts at the chord's start with
// direction unit/scale, so its parameter is arc length (scale = arc per metre of chord, ≥ 1),
// tracked over [0, tStop] (the chord's arc h, or up to the surface found on it).
struct CurvedChord {
    Ray arcRay;
    float tStop = 0, h = 0, arcStart = 0, scale = 1;
    Vec3 unit, pEnd;            // chord direction (unit) and end point
    bool surfaceAhead = false;  // a surface cuts the chord at tStop
};

// The chord walk shared by the curved trackers: each accepted step of the path stepper is a
// chord, tested against the surfaces, then handed to step(chord, &end), which tracks the media
// along it and returns false when the walk ends inside it (having filled end). A surface on the
// chord ends the walk there; otherwise the walk ends where the path does (Reached) or at the
// stepper's cap (Capped).
template <typename Step>
CurvedWalkEnd walkCurvedChords(const CurvedWalk& walk, const Ray& start, float lambdaNm,
                               Step&& step) {
    const ChordSurfaceTest& surfaces = walk.surfaces;
    CurvedWalkEnd end;
    auto visit = [&](const PathState& a, const PathState& b, bool) {
        ++end.chords;
        const Vec3 pa(a.r), pb(b.r);
        const float h = float(b.arc - a.arc), len = length(pb - pa);
        if (!(h > 0.f) || !(len > 0.f)) return true;
        const Vec3 unit = (pb - pa) / len;
        end.chord = Ray{pa, unit};
        const float tSurface = surfaces ? surfaces(end.chord, len) : kInfinity;
        CurvedChord c;
        c.scale = h / len;
        c.arcRay = Ray{pa, unit / c.scale};
        c.h = h;
        c.tStop = std::min(h, tSurface * c.scale);
        c.arcStart = float(a.arc);
        c.unit = unit;
        c.pEnd = pb;
        c.surfaceAhead = tSurface < len;
        if (!step(c, &end)) return false;
        if (c.surfaceAhead) {
            end.kind = CurvedWalkEnd::Kind::Surface;
            end.p = end.chord.at(tSurface);
            end.direction = unit;
            end.arc = c.arcStart + tSurface * c.scale;
            end.chordT = tSurface;
            return false;
        }
        if (walk.bounds && !walk.bounds->contains(pb)) {
            end.kind = CurvedWalkEnd::Kind::Left;
            end.p = pb;
            end.direction = Vec3(b.direction());
            end.arc = float(b.arc);
            end.chordT = len;
            return false;
        }
        return true;
    };
    const CurvedPathResult r = traceCurvedPath(walk.field, Vec3d(start.o), Vec3d(start.d), lambdaNm,
                                               walk.maxArc, walk.settings, visit);
    if (r.stopped) return end;
    end.kind = r.capped ? CurvedWalkEnd::Kind::Capped : CurvedWalkEnd::Kind::Reached;
    end.p = Vec3(r.end.r);
    end.direction = Vec3(r.end.direction());
    end.arc = float(r.end.arc);
    return end;
}

// Calls f(const Collision&, float arc) at every tentative collision along the curved path of
// the walk from `start` (Collision::t is the arc length within the chord, Collision::p lies on
// the chord). f returns Track::Stop to end the walk there.
template <typename F>
CurvedWalkEnd trackCurvedCollisions(TrackingContext& ctx, const CurvedWalk& walk, const Ray& start,
                                    float lambdaNm, Sampler& sampler, F&& f) {
    return walkCurvedChords(
        walk, start, lambdaNm, [&](const CurvedChord& chord, CurvedWalkEnd* end) {
            bool stopped = false;
            trackCollisions(ctx, chord.arcRay, chord.tStop, sampler, [&](const Collision& c) {
                if (f(c, chord.arcStart + c.t) == Track::Continue) return Track::Continue;
                stopped = true;
                end->kind = CurvedWalkEnd::Kind::Stopped;
                end->p = c.p;
                end->direction = chord.unit;
                end->arc = chord.arcStart + c.t;
                end->chordT = c.t / chord.scale;
                return Track::Stop;
            });
            return !stopped;
        });
}

// Transmittance along the curved path of the walk from `start`, up to the first surface (the
// walk ends there: end->kind says Surface, and a shadow query treats that as blocked).
// Homogeneous media take the closed form exp(−σt·arc), the others ratio tracking, chord by
// chord.
SampledSpectrum curvedTransmittance(TrackingContext& ctx, const CurvedWalk& walk, const Ray& start,
                                    float lambdaNm, Sampler& sampler, CurvedWalkEnd* end = nullptr);

}  // namespace mirage
