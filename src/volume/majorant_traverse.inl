// MajorantGrid::traverse: a 3D-DDA over the majorant cells (Amanatides & Woo 1987, "A fast
// voxel traversal algorithm for ray tracing"), as in pbrt-v4's DDAMajorantIterator. It runs
// in the inner loop of delta and ratio tracking, so it allocates nothing and calls nothing
// virtual; the callback is a template parameter and inlines.
//
// Guarantees the trackers rely on: the segments it reports are in order, each starts where the
// previous one ended (the same float), the first starts at max(tMin, tEnter), the last ends at
// min(tMax, tExit), and none is empty. A ray that misses the bounds reports nothing.
#pragma once

namespace mirage {

template <typename F>
bool MajorantGrid::traverse(const Vec3& o, const Vec3& d, float tMin, float tMax, F&& f) const {
    if (mValues.empty()) return true;
    float tStart, tEnd;
    if (!mBounds.intersect(o, d, tMin, tMax, &tStart, &tEnd) || !(tStart < tEnd)) return true;

    // Set up the walk: the cell of the entry point (clamped, since rounding can put the entry
    // point just outside the bounds), and per axis the direction of stepping, the index one
    // past the last cell, and the ray parameter of the next cell boundary. An axis the ray is
    // parallel to is never crossed.
    const Vec3 pEnter = o + d * tStart;
    int cell[3], step[3], stop[3];
    float tNext[3], invD[3];
    const long stride[3] = {1, long(mRes[0]), long(mRes[0]) * long(mRes[1])};
    for (int a = 0; a < 3; ++a) {
        float c = (pEnter[a] - mBounds.lo[a]) / mCellSize[a];
        cell[a] = !(c > 0.f) ? 0 : (c >= float(mRes[a]) ? mRes[a] - 1 : int(c));
        if (d[a] > 0.f) {
            step[a] = 1;
            stop[a] = mRes[a];
            invD[a] = 1.f / d[a];
            tNext[a] = (mBounds.lo[a] + float(cell[a] + 1) * mCellSize[a] - o[a]) * invD[a];
        } else if (d[a] < 0.f) {
            step[a] = -1;
            stop[a] = -1;
            invD[a] = 1.f / d[a];
            tNext[a] = (mBounds.lo[a] + float(cell[a]) * mCellSize[a] - o[a]) * invD[a];
        } else {
            step[a] = 0;
            stop[a] = -1;
            invD[a] = 0.f;
            tNext[a] = kInfinity;
        }
    }
    const float* values = mValues.data();
    long index = cell[0] * stride[0] + cell[1] * stride[1] + cell[2] * stride[2];

    float t = tStart;
    for (;;) {
        // The axis whose boundary comes first ends this cell.
        int a = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
        float tCellEnd = tNext[a] < tEnd ? tNext[a] : tEnd;
        // Crossing an edge or corner (two boundaries at one t), or a clamped entry cell, gives
        // an empty span: skip it rather than report it.
        if (tCellEnd > t) {
            if (!f(t, tCellEnd, values[index])) return false;
            t = tCellEnd;
        }
        if (t >= tEnd) return true;
        cell[a] += step[a];
        if (cell[a] == stop[a]) {
            // The last boundary came, by rounding, just before tEnd: the rest of the span is
            // still inside the bounds and belongs to the last cell.
            return f(t, tEnd, values[index]);
        }
        index += step[a] * stride[a];
        tNext[a] = (mBounds.lo[a] + float(cell[a] + (step[a] > 0)) * mCellSize[a] - o[a]) * invD[a];
    }
}

}  // namespace mirage
