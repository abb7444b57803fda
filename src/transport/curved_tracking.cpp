// Transmittance along curved paths (curved_tracking.h says how chords carry arc length).
#include "transport/curved_tracking.h"

namespace mirage {

SampledSpectrum curvedTransmittance(TrackingContext& ctx, const CurvedWalk& walk, const Ray& start,
                                    float lambdaNm, Sampler& sampler, CurvedWalkEnd* endOut) {
    // The product over chords of each chord's transmittance estimate: the estimates are
    // independent given the (deterministic) path, so the product is unbiased.
    SampledSpectrum T(1.f);
    const CurvedWalkEnd end =
        walkCurvedChords(walk, start, lambdaNm, [&](const CurvedChord& chord, CurvedWalkEnd* e) {
            T *= transmittance(ctx, chord.arcRay, chord.tStop, sampler);
            // Nothing more gets through: stop walking (the estimate is 0 from here on). A
            // surface on this chord ends the walk there instead.
            if (T.maxValue() > 0.f || chord.surfaceAhead) return true;
            e->kind = CurvedWalkEnd::Kind::Stopped;
            e->p = chord.pEnd;
            e->direction = chord.unit;
            e->arc = chord.arcStart + chord.h;
            e->chordT = chord.h / chord.scale;
            return false;
        });
    if (endOut) *endOut = end;
    return T;
}

}  // namespace mirage
