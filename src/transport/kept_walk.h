// A majorant walk kept to be walked again (see KeptWalk).
#pragma once

#include <array>
#include <optional>

#include "core/math.h"
#include "volume/majorant.h"

namespace mirage {

// The majorant's cells along a ray, walked twice: the constructor walks them, sums their
// optical depth and keeps the non-empty spans (up to kSpans); next() and advanceTo() then walk
// those again as MajorantGrid::Walk would, for nextTentativeCollisionIn, going on with a walk
// of the grid past the last one kept. The camera ray's points for the lights at infinity need
// the optical depth of the whole segment before they are placed along it
// (render/lamp_sampling.cpp: drawSky): a second walk of the grid had cost as much as the
// first.
template <int kSpans = 128>
class KeptWalk {
public:
    using Segment = MajorantGrid::Walk::Segment;
    // pathMajorant ≥ 0 replaces the grid's value (TrackingContext::pathMajorant).
    KeptWalk(const MajorantGrid& grid, const Ray& r, float tEnd, float pathMajorant)
        : mGrid(grid), mRay(r), mTEnd(tEnd) {
        MajorantGrid::Walk walk(grid, r.o, r.d, 0.f, tEnd);
        for (Segment s; walk.next(&s); walk.advanceTo(s.t1)) {
            const float sigma = pathMajorant >= 0.f ? pathMajorant : s.sigmaMaj;
            if (!(sigma > 0.f)) continue;
            mDepth += sigma * (s.t1 - s.t0);
            if (mCount < kSpans)
                mSpans[mCount++] = s;
            else
                mFull = true;
        }
    }
    // The majorant's optical depth over the segment.
    float depth() const { return mDepth; }

    bool next(Segment* s) {
        while (mNext < mCount && !(mSpans[mNext].t1 > mT)) ++mNext;
        if (mNext < mCount) {
            *s = mSpans[mNext];
            if (mT > s->t0) s->t0 = mT;
            return true;
        }
        if (!mFull) return false;
        // Past the spans kept: the grid's walk again from the last of them.
        if (!mRest) mRest.emplace(mGrid, mRay.o, mRay.d, mT, mTEnd);
        return mRest->next(s);
    }
    void advanceTo(float t) {
        mT = t;
        if (mRest) mRest->advanceTo(t);
    }

private:
    const MajorantGrid& mGrid;
    Ray mRay;
    float mTEnd, mDepth = 0.f, mT = 0.f;
    std::array<Segment, kSpans> mSpans;
    int mCount = 0, mNext = 0;
    bool mFull = false;
    std::optional<MajorantGrid::Walk> mRest;
};

}  // namespace mirage
