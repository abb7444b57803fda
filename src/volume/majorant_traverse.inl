// MajorantGrid's walk: a 3D-DDA over the majorant cells (Amanatides & Woo 1987, "A fast voxel
// traversal algorithm for ray tracing"), as in pbrt-v4's DDAMajorantIterator. It runs in the
// inner loop of delta and ratio tracking, so it allocates nothing and calls nothing virtual;
// traverse's callback is a template parameter and inlines.
//
// Guarantees the trackers rely on: the segments it reports are in order, each starts where the
// previous one ended (the same float), the first starts at max(tMin, tEnter), the last ends at
// min(tMax, tExit), and none is empty. A ray that misses the bounds reports nothing.
#pragma once

namespace mirage {

inline MajorantGrid::Walk::Walk(const MajorantGrid& grid, const Vec3& o, const Vec3& d, float tMin,
                                float tMax) {
    if (grid.mValues.empty()) return;
    float tStart, tEnd;
    if (!grid.mBounds.intersect(o, d, tMin, tMax, &tStart, &tEnd) || !(tStart < tEnd)) return;

    // Set up the walk: the cell of the entry point (clamped, since rounding can put the entry
    // point just outside the bounds), and per axis the direction of stepping, the index one
    // past the last cell, and the ray parameter of the next cell boundary. An axis the ray is
    // parallel to is never crossed.
    const Vec3 pEnter = o + d * tStart;
    for (int a = 0; a < 3; ++a) {
        mO[a] = o[a];
        mLo[a] = grid.mBounds.lo[a];
        mCellSize[a] = grid.mCellSize[a];
        const int res = grid.mRes[a];
        const float c = (pEnter[a] - mLo[a]) / mCellSize[a];
        mCell[a] = !(c > 0.f) ? 0 : (c >= float(res) ? res - 1 : int(c));
        if (d[a] > 0.f) {
            mStep[a] = 1;
            mStop[a] = res;
            mInvD[a] = 1.f / d[a];
            mTNext[a] = (mLo[a] + float(mCell[a] + 1) * mCellSize[a] - o[a]) * mInvD[a];
        } else if (d[a] < 0.f) {
            mStep[a] = -1;
            mStop[a] = -1;
            mInvD[a] = 1.f / d[a];
            mTNext[a] = (mLo[a] + float(mCell[a]) * mCellSize[a] - o[a]) * mInvD[a];
        } else {
            mStep[a] = 0;
            mStop[a] = -1;
            mInvD[a] = 0.f;
            mTNext[a] = kInfinity;
        }
    }
    mStride[0] = 1;
    mStride[1] = long(grid.mRes[0]);
    mStride[2] = long(grid.mRes[0]) * long(grid.mRes[1]);
    mIndex = mCell[0] * mStride[0] + mCell[1] * mStride[1] + mCell[2] * mStride[2];
    mT = tStart;
    mTEnd = tEnd;
    mLastCell = false;
    mValues = grid.mValues.data();
}

inline bool MajorantGrid::Walk::next(Segment* s) {
    while (mValues) {
        if (mT >= mTEnd) break;
        if (mLastCell) {
            *s = {mT, mTEnd, mValues[mIndex]};
            return true;
        }
        // The axis whose boundary comes first ends this cell.
        const int a = mTNext[0] < mTNext[1] ? (mTNext[0] < mTNext[2] ? 0 : 2)
                                            : (mTNext[1] < mTNext[2] ? 1 : 2);
        const float tCellEnd = mTNext[a] < mTEnd ? mTNext[a] : mTEnd;
        // Crossing an edge or corner (two boundaries at one t), or a clamped entry cell, gives
        // an empty span: skip it rather than report it.
        if (tCellEnd > mT) {
            *s = {mT, tCellEnd, mValues[mIndex]};
            return true;
        }
        mCell[a] += mStep[a];
        if (mCell[a] == mStop[a]) {
            // The last boundary came, by rounding, just before tEnd: the rest of the span is
            // still inside the bounds and belongs to the last cell.
            mLastCell = true;
            continue;
        }
        mIndex += mStep[a] * mStride[a];
        mTNext[a] =
            (mLo[a] + float(mCell[a] + (mStep[a] > 0)) * mCellSize[a] - mO[a]) * mInvD[a];
    }
    mValues = nullptr;
    return false;
}

template <typename F>
bool MajorantGrid::traverse(const Vec3& o, const Vec3& d, float tMin, float tMax, F&& f) const {
    Walk walk(*this, o, d, tMin, tMax);
    for (Walk::Segment s; walk.next(&s); walk.advanceTo(s.t1))
        if (!f(s.t0, s.t1, s.sigmaMaj)) return false;
    return true;
}

}  // namespace mirage
