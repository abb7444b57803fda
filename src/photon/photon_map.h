// The volume photon map: a left-balanced kd-tree stored in the photon array itself (Jensen 2001,
// "Realistic Image Synthesis Using Photon Mapping", §6.3; Jensen & Christensen 1998).
//
// Layout: the photons are permuted into heap order. Node i (0-based) has children 2i+1 and
// 2i+2; the tree is complete except for its last level, which is filled from the left, so the
// n photons occupy exactly slots 0..n−1 and no child pointers are stored. Each node splits at
// its own photon on the axis of the widest extent of its subtree. The queries read a compact
// copy of the tree, each node's position and split axis in 16 bytes (a Photon is 44): a
// k-nearest search touches scattered nodes, and on dense smoke the radii's search was most of
// a one-pass render's photon work (docs/performance-history.md, "Passes of one sample").
//
// Queries never allocate: k nearest neighbours go into a caller-provided bounded max-heap, and
// the radius query calls a visitor. Ties in distance are broken by the photon's slot, so the
// k nearest are one well-defined set (brute force finds the same one) and every query result is
// a pure function of its input.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/photon.h"

namespace mirage {

// One neighbour found by PhotonMap::nearest: squared distance (m²) and slot in the map.
struct PhotonNeighbour {
    float d2;
    uint32_t index;
};

// The order of the k-nearest heap: by distance, then by slot.
inline bool neighbourBefore(const PhotonNeighbour& a, const PhotonNeighbour& b) {
    return a.d2 < b.d2 || (a.d2 == b.d2 && a.index < b.index);
}

class PhotonMap {
public:
    PhotonMap() = default;
    // Builds the tree in O(n log n) (median split by nth_element on the widest axis); the
    // photons are reordered, so slot i of the map is not photon i of the list.
    explicit PhotonMap(PhotonList photons);

    size_t size() const { return mPhotons.size(); }
    bool empty() const { return mPhotons.empty(); }
    const Photon& operator[](size_t i) const { return mPhotons[i]; }
    const PhotonList& photons() const { return mPhotons; }
    int splitAxis(size_t i) const { return int(mNodes[i].axis); }
    const Bounds3& bounds() const { return mBounds; }

    // The k photons nearest to q within maxRadius (inclusive), in buffer[0..count) as a max-heap
    // under neighbourBefore: buffer[0] is the farthest of them. `buffer` holds k entries.
    // Returns count = min(k, photons within maxRadius).
    int nearest(const Vec3& q, int k, float maxRadius, PhotonNeighbour* buffer) const;

    // Calls f(slot, d2) for every photon with |p − q|² ≤ radius², in tree order.
    template <typename F>
    void forEachInRadius(const Vec3& q, float radius, F&& f) const;

    // Per-photon radius for the beam estimate (Jarosz et al. 2008, §4.2): the distance from each
    // photon to its k-th nearest photon, itself included as the first, so that its disc holds
    // about k photons; maxRadius when fewer than k lie within it, and never below minRadius
    // (coincident photons would otherwise get a zero radius and an infinite kernel). Computed in
    // parallel; slot order, deterministic.
    std::vector<float> photonRadii(int k, float minRadius, float maxRadius) const;

    // Per-photon radii read off another map: each photon takes the radius sourceRadii[j] of its
    // nearest photon j in `source` (within maxRadius; maxRadius where there is none). A later
    // pass of progressive photon mapping takes its bandwidth from the first pass's k-nearest
    // radii this way, one nearest-neighbour query per photon instead of k (photon_integrator).
    // Computed in parallel; slot order, deterministic.
    std::vector<float> radiiFrom(const PhotonMap& source, const std::vector<float>& sourceRadii,
                                 float maxRadius) const;

private:
    void build(Photon* begin, Photon* end, size_t slot);

    // A node as the queries read it: the photon's position and the split axis.
    struct KdNode {
        Vec3 p;
        uint32_t axis;
    };

    PhotonList mPhotons;
    std::vector<KdNode> mNodes;  // mNodes[i] is mPhotons[i]'s position and split axis
    Bounds3 mBounds;
};

template <typename F>
void PhotonMap::forEachInRadius(const Vec3& q, float radius, F&& f) const {
    const size_t n = mPhotons.size();
    if (n == 0 || !(radius >= 0.f)) return;
    const float r2 = radius * radius;
    // Depth-first with an explicit stack; a left-balanced tree of 2^32 photons is 32 deep.
    size_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        size_t node = stack[--top];
        const KdNode& nd = mNodes[node];
        Vec3 d = nd.p - q;
        float d2 = dot(d, d);
        if (d2 <= r2) f(uint32_t(node), d2);
        float delta = q[int(nd.axis)] - nd.p[int(nd.axis)];
        size_t left = 2 * node + 1, right = left + 1;
        // The left subtree lies at or below the splitting plane, the right at or above it. The
        // test is on squares, as the distance test is: a photon across the plane has
        // d2 ≥ delta² in float arithmetic too, so nothing brute force accepts is pruned.
        bool planeInRange = delta * delta <= r2;
        if (right < n && (delta >= 0.f || planeInRange)) stack[top++] = right;
        if (left < n && (delta <= 0.f || planeInRange)) stack[top++] = left;
    }
}

}  // namespace mirage
