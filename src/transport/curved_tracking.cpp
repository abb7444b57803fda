// Transmittance along curved paths (curved_tracking.h says how chords carry arc length).
#include "transport/curved_tracking.h"

namespace mirage {

SampledSpectrum curvedTransmittance(TrackingContext& ctx, const IndexField& field,
                                    const CurvedPathSettings& settings,
                                    const ChordSurfaceTest& surfaces, const Vec3& origin,
                                    const Vec3& dir, float lambdaNm, float maxArc,
                                    Sampler& sampler, CurvedWalkEnd* endOut) {
    // The product over chords of each chord's transmittance estimate: the estimates are
    // independent given the (deterministic) path, so the product is unbiased.
    SampledSpectrum T(1.f);
    CurvedWalkEnd end;
    auto visit = [&](const PathState& a, const PathState& b, bool) {
        ++end.chords;
        const Vec3 pa(a.r), pb(b.r);
        const float h = float(b.arc - a.arc), len = length(pb - pa);
        if (!(h > 0.f) || !(len > 0.f)) return true;
        const Vec3 unit = (pb - pa) / len;
        end.chord = Ray{pa, unit};
        const float tSurface = surfaces ? surfaces(end.chord, len) : kInfinity;
        const float scale = h / len;  // arc length per metre of chord
        const Ray arcRay{pa, unit / scale};
        T *= transmittance(ctx, arcRay, std::min(h, tSurface * scale), sampler);
        if (tSurface < len) {
            end.kind = CurvedWalkEnd::Kind::Surface;
            end.p = end.chord.at(tSurface);
            end.direction = unit;
            end.arc = float(a.arc) + tSurface * scale;
            end.chordT = tSurface;
            return false;
        }
        // Nothing more gets through: stop walking (the estimate is 0 from here on).
        if (T.maxValue() <= 0.f) {
            end.kind = CurvedWalkEnd::Kind::Stopped;
            end.p = pb;
            end.direction = unit;
            end.arc = float(b.arc);
            end.chordT = len;
            return false;
        }
        return true;
    };
    const CurvedPathResult r = traceCurvedPath(field, Vec3d(origin), Vec3d(dir), lambdaNm,
                                               maxArc, settings, visit);
    if (!r.stopped) {
        end.kind = r.capped ? CurvedWalkEnd::Kind::Capped : CurvedWalkEnd::Kind::Reached;
        end.p = Vec3(r.end.r);
        end.direction = Vec3(r.end.direction());
        end.arc = float(r.end.arc);
    }
    if (endOut) *endOut = end;
    return T;
}

}  // namespace mirage
