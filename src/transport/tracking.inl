// Template body of trackCollisions (included from tracking.h).
#pragma once

#include <cmath>
#include <vector>

namespace mirage {

template <typename F>
bool trackCollisions(TrackingContext& ctx, const Ray& worldRay, float tMax, Sampler& sampler,
                     F&& f) {
    // One stream of tentative collisions per medium, every medium of the context: a volume left
    // out would be invisible to tracking yet still attenuate closed-form shadow rays and the
    // photon estimates. A handful of media is the common case and stays on the stack; a shot
    // with hundreds of caches takes one heap block per flight. Local (not kept in ctx) because
    // f may itself track through the same context (a shadow ray at a collision).
    constexpr size_t kInlineMedia = 16;
    struct Stream {
        Ray objectRay;
        float tEnd, tNext, sigmaMaj;
    };
    const size_t n = ctx.size();
    Stream inlineStreams[kInlineMedia];
    std::vector<Stream> heapStreams;
    Stream* streams = inlineStreams;
    if (n > kInlineMedia) {
        heapStreams.resize(n);
        streams = heapStreams.data();
    }
    auto exp1 = [&] { return exponentialDraw(sampler); };

    for (size_t i = 0; i < n; ++i) {
        Stream& s = streams[i];
        s.objectRay = ctx.medium(i).toObject(worldRay, ctx.context(i));
        s.tEnd = tMax;
        if (!nextTentativeCollision(ctx.medium(i).majorant(), s.objectRay, 0.f, s.tEnd, exp1(),
                                    &s.tNext, &s.sigmaMaj, ctx.pathMajorant(i)))
            s.tNext = kInfinity;
    }
    for (uint64_t collisions = 0;; ++collisions) {
        if (collisions >= ctx.maxCollisions) {
            ++ctx.cappedFlights;
            return false;
        }
        size_t m = n;
        float tMin = kInfinity;
        for (size_t i = 0; i < n; ++i)
            if (streams[i].tNext < tMin) { tMin = streams[i].tNext; m = i; }
        if (m == n) return true;

        Stream& s = streams[m];
        Collision c;
        c.medium = int(m);
        c.t = s.tNext;
        c.p = worldRay.at(c.t);
        c.sigmaMaj = s.sigmaMaj;
        ctx.medium(m).eval(s.objectRay.at(c.t), ctx.context(m), &c.mp);
        ++ctx.lookups;
        if ((c.mp.sigmaA + c.mp.sigmaS).maxValue() > c.sigmaMaj) ++ctx.aboveMajorant;
        if (f(static_cast<const Collision&>(c)) == Track::Stop) return false;
        if (!nextTentativeCollision(ctx.medium(m).majorant(), s.objectRay, c.t, s.tEnd, exp1(),
                                    &s.tNext, &s.sigmaMaj, ctx.pathMajorant(m)))
            s.tNext = kInfinity;
    }
}

}  // namespace mirage
