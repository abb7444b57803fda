// Left-balanced kd-tree construction and the k-nearest query (see photon_map.h for the layout).
#include "photon/photon_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"

namespace mirage {

namespace {

// Size of the left subtree of a left-balanced tree of m nodes. With H = ⌊log₂ m⌋ the depth of
// the last level, the levels above it hold 2^H − 1 nodes and the last level the remaining
// L = m − (2^H − 1) ≤ 2^H, filled from the left: the left subtree gets the full levels
// 1..H−1 of its half (2^(H−1) − 1 nodes) and the first min(L, 2^(H−1)) nodes of the last.
size_t leftSubtreeSize(size_t m) {
    if (m <= 1) return 0;
    int H = 0;
    while ((size_t(2) << H) <= m) ++H;
    size_t half = size_t(1) << (H - 1);
    size_t last = m - ((size_t(1) << H) - 1);
    return (half - 1) + std::min(last, half);
}

// Below this many photons a subtree is built on the calling thread; above it the two halves
// are built in parallel (they write disjoint slots, so the result does not depend on it).
constexpr size_t kParallelBuildMin = size_t(1) << 15;

}  // namespace

PhotonMap::PhotonMap(PhotonList photons) {
    MIRAGE_CHECK(photons.size() < size_t(std::numeric_limits<uint32_t>::max()));
    mPhotons.resize(photons.size());
    mNodes.resize(photons.size());
    for (const Photon& ph : photons) mBounds.expand(ph.p);
    build(photons.data(), photons.data() + photons.size(), 0);
}

// Places the photons of [begin, end) into the heap slots of the subtree rooted at `slot`. The
// work array is partitioned in place by nth_element (expected linear time), so each level of
// the tree costs O(n) and the build O(n log n).
void PhotonMap::build(Photon* begin, Photon* end, size_t slot) {
    const size_t m = size_t(end - begin);
    if (m == 0) return;
    if (m == 1) {
        mPhotons[slot] = *begin;
        mNodes[slot] = {begin->p, 0};
        return;
    }
    // Split on the axis of widest extent (the first such axis on a tie, for determinism).
    Bounds3 b;
    for (const Photon* p = begin; p != end; ++p) b.expand(p->p);
    Vec3 ext = b.diagonal();
    int axis = ext.x >= ext.y ? (ext.x >= ext.z ? 0 : 2) : (ext.y >= ext.z ? 1 : 2);

    Photon* median = begin + leftSubtreeSize(m);
    std::nth_element(begin, median, end,
                     [axis](const Photon& a, const Photon& c) { return a.p[axis] < c.p[axis]; });
    mPhotons[slot] = *median;
    mNodes[slot] = {median->p, uint32_t(axis)};

    auto left = [&] { build(begin, median, 2 * slot + 1); };
    auto right = [&] { build(median + 1, end, 2 * slot + 2); };
    if (m >= kParallelBuildMin) {
        tbb::parallel_invoke(left, right);
    } else {
        left();
        right();
    }
}

int PhotonMap::nearest(const Vec3& q, int k, float maxRadius, PhotonNeighbour* heap) const {
    const size_t n = mPhotons.size();
    if (n == 0 || k <= 0 || !(maxRadius >= 0.f)) return 0;
    // maxD2 is the squared radius of the current search sphere: the caller's bound until k
    // photons are held, then the distance of the farthest of them.
    float maxD2 = maxRadius * maxRadius;
    int count = 0;

    auto siftDown = [&](int i) {
        for (;;) {
            int l = 2 * i + 1, r = l + 1, largest = i;
            if (l < count && neighbourBefore(heap[largest], heap[l])) largest = l;
            if (r < count && neighbourBefore(heap[largest], heap[r])) largest = r;
            if (largest == i) return;
            std::swap(heap[i], heap[largest]);
            i = largest;
        }
    };
    auto consider = [&](uint32_t index, float d2) {
        PhotonNeighbour c{d2, index};
        if (count < k) {
            int i = count++;
            heap[i] = c;
            while (i > 0) {  // sift up
                int parent = (i - 1) / 2;
                if (!neighbourBefore(heap[parent], heap[i])) break;
                std::swap(heap[parent], heap[i]);
                i = parent;
            }
        } else if (neighbourBefore(c, heap[0])) {
            heap[0] = c;
            siftDown(0);
        }
        if (count == k) maxD2 = heap[0].d2;
    };

    // Descend towards q, deferring each far child with its squared distance to the splitting
    // plane; a deferred subtree is skipped if the sphere has shrunk past that plane by the time
    // it is popped. At most one pending sibling per level: the stack never exceeds the depth.
    struct Pending {
        size_t node;
        float planeD2;
    };
    Pending stack[64];
    int top = 0;
    size_t node = 0;
    for (;;) {
        while (node < n) {
            const KdNode& nd = mNodes[node];
            Vec3 d = nd.p - q;
            float d2 = dot(d, d);
            if (d2 <= maxD2) consider(uint32_t(node), d2);
            const int axis = int(nd.axis);
            float delta = q[axis] - nd.p[axis];
            size_t left = 2 * node + 1, right = left + 1;
            size_t nearChild = delta <= 0.f ? left : right;
            size_t farChild = delta <= 0.f ? right : left;
            // ≤, not <: a photon on the plane at the current distance may still win the tie.
            if (farChild < n && delta * delta <= maxD2) stack[top++] = {farChild, delta * delta};
            node = nearChild;
        }
        for (;;) {
            if (top == 0) return count;
            Pending p = stack[--top];
            if (p.planeD2 <= maxD2) {
                node = p.node;
                break;
            }
        }
    }
}

std::vector<float> PhotonMap::photonRadii(int k, float minRadius, float maxRadius) const {
    MIRAGE_CHECK(k > 0 && minRadius >= 0.f && maxRadius >= minRadius);
    std::vector<float> radii(mPhotons.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mPhotons.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& r) {
                          std::vector<PhotonNeighbour> heap(static_cast<size_t>(k));
                          for (size_t i = r.begin(); i < r.end(); ++i) {
                              int found = nearest(mNodes[i].p, k, maxRadius, heap.data());
                              float ri = found == k ? std::sqrt(heap[0].d2) : maxRadius;
                              radii[i] = clamp(ri, minRadius, maxRadius);
                          }
                      });
    return radii;
}

std::vector<float> PhotonMap::radiiFrom(const PhotonMap& source,
                                        const std::vector<float>& sourceRadii,
                                        float maxRadius) const {
    MIRAGE_CHECK(sourceRadii.size() == source.size() && maxRadius >= 0.f);
    std::vector<float> radii(mPhotons.size(), maxRadius);
    if (source.empty()) return radii;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mPhotons.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& r) {
                          PhotonNeighbour nearestOne;
                          for (size_t i = r.begin(); i < r.end(); ++i)
                              if (source.nearest(mPhotons[i].p, 1, maxRadius, &nearestOne) == 1)
                                  radii[i] = sourceRadii[nearestOne.index];
                      });
    return radii;
}

}  // namespace mirage
