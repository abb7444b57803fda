// Template body of trackCollisions (included from tracking.h).
#pragma once

#include <cmath>
#include <new>
#include <type_traits>
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
        MajorantGrid::Walk walk;  // kept across the flight's collisions
        float tNext, sigmaMaj;
    };
    const size_t n = ctx.size();
    // Left unconstructed until used: clearing sixteen streams costs more than a short flight.
    union InlineStreams {
        InlineStreams() {}
        Stream s[kInlineMedia];
    } inlineStreams;
    static_assert(std::is_trivially_destructible_v<Stream>);
    std::vector<Stream> heapStreams;
    Stream* streams = inlineStreams.s;
    if (n > kInlineMedia) {
        heapStreams.resize(n);
        streams = heapStreams.data();
    }
    auto exp1 = [&] { return exponentialDraw(sampler); };

    for (size_t i = 0; i < n; ++i) {
        const Medium& medium = ctx.medium(i);
        const Ray objectRay = ctx.context(i).toObject(worldRay);
        Stream& s = *new (&streams[i])
            Stream{objectRay, MajorantGrid::Walk(medium.majorant(), objectRay.o, objectRay.d, 0.f,
                                                 tMax),
                   0.f, 0.f};
        // A ray that misses the medium's bounds draws no number for it.
        if (s.walk.done() || !nextTentativeCollision(s.walk, 0.f, exp1(), &s.tNext, &s.sigmaMaj,
                                                     ctx.pathMajorant(i)))
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
        if (!nextTentativeCollision(s.walk, c.t, exp1(), &s.tNext, &s.sigmaMaj,
                                    ctx.pathMajorant(m)))
            s.tNext = kInfinity;
    }
}

}  // namespace mirage
