// The photon map's kd-tree against brute force: k-nearest and radius queries on random point
// sets (with duplicates, coincident coordinates, empty and one-photon maps, k > n), the
// left-balanced kd layout, per-photon radii, and determinism across thread counts.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>

#include "core/rng.h"
#include "photon/photon_map.h"

using namespace mirage;

namespace {

// n photons in the unit cube. A quarter are exact copies of earlier ones and a quarter have
// coordinates snapped to a coarse lattice, so distance ties and points on splitting planes are
// common rather than accidental.
PhotonList randomPhotons(size_t n, uint64_t seed) {
    PhotonList list;
    Sampler s(seed, 0, 0);
    for (size_t i = 0; i < n; ++i) {
        float u = s.get1D();
        Photon ph;
        if (i > 0 && u < 0.25f) {
            ph = list[size_t(s.get1D() * float(i))];
        } else {
            ph.p = Vec3(s.get1D(), s.get1D(), s.get1D());
            if (u > 0.75f) ph.p = Vec3(std::floor(ph.p.x * 8) / 8, std::floor(ph.p.y * 8) / 8,
                                       std::floor(ph.p.z * 8) / 8);
            ph.wi = Vec3(0, 0, 1);
            ph.lambda = 400.f + 300.f * s.get1D();
            ph.power = float(i);  // identifies the photon after the reordering
        }
        list.push_back(ph);
    }
    return list;
}

std::vector<PhotonNeighbour> bruteNearest(const PhotonMap& map, const Vec3& q, int k, float r) {
    std::vector<PhotonNeighbour> all;
    for (size_t i = 0; i < map.size(); ++i) {
        Vec3 d = map[i].p - q;
        float d2 = dot(d, d);
        if (d2 <= r * r) all.push_back({d2, uint32_t(i)});
    }
    std::sort(all.begin(), all.end(), neighbourBefore);
    if (int(all.size()) > k) all.resize(size_t(std::max(k, 0)));
    return all;
}

size_t subtreeSize(size_t node, size_t n) {
    if (node >= n) return 0;
    return 1 + subtreeSize(2 * node + 1, n) + subtreeSize(2 * node + 2, n);
}

// Calls f(slot) for every slot of the subtree rooted at `node`.
template <typename F>
void forSubtree(size_t node, size_t n, F&& f) {
    if (node >= n) return;
    f(node);
    forSubtree(2 * node + 1, n, f);
    forSubtree(2 * node + 2, n, f);
}

const size_t kSizes[] = {0, 1, 2, 3, 7, 8, 100, 1000, 4097};

}  // namespace

TEST(PhotonMap, NearestEqualsBruteForce) {
    for (size_t n : kSizes) {
        PhotonMap map(randomPhotons(n, n + 1));
        ASSERT_EQ(map.size(), n);
        Sampler s(7, n, 0);
        for (int query = 0; query < 60; ++query) {
            // Half the queries sit on photons (exact ties at distance 0 and on planes).
            Vec3 q = n > 0 && query % 2 ? map[size_t(s.get1D() * float(n))].p
                                        : Vec3(s.get1D(), s.get1D(), s.get1D()) * 1.2f - Vec3(0.1f);
            for (int k : {1, 4, 32, int(n) + 3}) {
                for (float r : {0.05f, 0.3f, 10.f}) {
                    std::vector<PhotonNeighbour> heap(static_cast<size_t>(k));
                    int found = map.nearest(q, k, r, heap.data());
                    auto expected = bruteNearest(map, q, k, r);
                    ASSERT_EQ(size_t(found), expected.size()) << "n " << n << " k " << k;
                    heap.resize(size_t(found));
                    // The buffer is a max-heap: its first entry is the farthest neighbour.
                    if (found > 0) {
                        EXPECT_EQ(heap[0].d2, expected.back().d2);
                        EXPECT_EQ(heap[0].index, expected.back().index);
                    }
                    std::sort(heap.begin(), heap.end(), neighbourBefore);
                    for (int i = 0; i < found; ++i) {
                        EXPECT_EQ(heap[i].index, expected[i].index) << "n " << n << " k " << k;
                        EXPECT_EQ(heap[i].d2, expected[i].d2);
                    }
                }
            }
        }
    }
}

TEST(PhotonMap, ZeroKOrNegativeRadiusFindsNothing) {
    PhotonMap map(randomPhotons(50, 3));
    PhotonNeighbour buffer[4];
    EXPECT_EQ(map.nearest(Vec3(0.5f), 0, 1.f, buffer), 0);
    EXPECT_EQ(map.nearest(Vec3(0.5f), 4, -1.f, buffer), 0);
    int visits = 0;
    map.forEachInRadius(Vec3(0.5f), -1.f, [&](uint32_t, float) { ++visits; });
    EXPECT_EQ(visits, 0);
}

TEST(PhotonMap, RadiusQueryEqualsBruteForce) {
    for (size_t n : kSizes) {
        PhotonMap map(randomPhotons(n, 100 + n));
        Sampler s(11, n, 0);
        for (int query = 0; query < 60; ++query) {
            Vec3 q = n > 0 && query % 2 ? map[size_t(s.get1D() * float(n))].p
                                        : Vec3(s.get1D(), s.get1D(), s.get1D());
            for (float r : {0.f, 0.125f, 0.4f, 3.f}) {
                std::vector<uint32_t> found;
                map.forEachInRadius(q, r, [&](uint32_t i, float d2) {
                    Vec3 d = map[i].p - q;
                    EXPECT_EQ(d2, dot(d, d));
                    found.push_back(i);
                });
                std::sort(found.begin(), found.end());
                std::vector<uint32_t> expected;
                for (auto& nb : bruteNearest(map, q, int(n), r)) expected.push_back(nb.index);
                std::sort(expected.begin(), expected.end());
                EXPECT_EQ(found, expected) << "n " << n << " r " << r;
            }
        }
    }
}

TEST(PhotonMap, LeftBalancedKdLayout) {
    for (size_t n : kSizes) {
        PhotonList input = randomPhotons(n, 200 + n);
        PhotonMap map(input);
        // A permutation of the input: the same multiset of (position, power).
        auto key = [](const Photon& a, const Photon& b) {
            return std::make_tuple(a.power, a.p.x, a.p.y, a.p.z) <
                   std::make_tuple(b.power, b.p.x, b.p.y, b.p.z);
        };
        PhotonList sortedIn = input, sortedMap = map.photons();
        std::sort(sortedIn.begin(), sortedIn.end(), key);
        std::sort(sortedMap.begin(), sortedMap.end(), key);
        for (size_t i = 0; i < n; ++i) {
            EXPECT_EQ(sortedIn[i].p, sortedMap[i].p);
            EXPECT_EQ(sortedIn[i].power, sortedMap[i].power);
        }
        for (size_t node = 0; node < n; ++node) {
            int axis = map.splitAxis(node);
            float split = map[node].p[axis];
            forSubtree(2 * node + 1, n, [&](size_t i) { EXPECT_LE(map[i].p[axis], split); });
            forSubtree(2 * node + 2, n, [&](size_t i) { EXPECT_GE(map[i].p[axis], split); });
            // Left-balanced: the left subtree is full down to the last level, which is filled
            // from the left, so it has at least as many nodes as the right one and, unless the
            // right is empty, at most twice as many plus one.
            size_t l = subtreeSize(2 * node + 1, n), r = subtreeSize(2 * node + 2, n);
            EXPECT_GE(l, r);
            EXPECT_LE(l, 2 * r + 1);
            // The split axis is the widest extent of the subtree.
            Bounds3 b;
            forSubtree(node, n, [&](size_t i) { b.expand(map[i].p); });
            Vec3 ext = b.diagonal();
            if (l + r > 0) {
                EXPECT_EQ(ext[axis], std::max({ext.x, ext.y, ext.z}));
            }
        }
    }
}

TEST(PhotonMap, PhotonRadiiEqualBruteForce) {
    for (size_t n : {size_t(0), size_t(1), size_t(20), size_t(2000)}) {
        PhotonMap map(randomPhotons(n, 300 + n));
        const int k = 16;
        const float rMin = 0.01f, rMax = 0.2f;
        std::vector<float> radii = map.photonRadii(k, rMin, rMax);
        ASSERT_EQ(radii.size(), n);
        for (size_t i = 0; i < n; ++i) {
            std::vector<float> d2;
            for (size_t j = 0; j < n; ++j) {
                Vec3 d = map[j].p - map[i].p;
                d2.push_back(dot(d, d));
            }
            std::sort(d2.begin(), d2.end());
            // The photon itself is its nearest neighbour (distance 0).
            float expected = d2.size() >= size_t(k) && d2[k - 1] <= rMax * rMax
                                 ? std::sqrt(d2[k - 1])
                                 : rMax;
            EXPECT_EQ(radii[i], clamp(expected, rMin, rMax)) << "photon " << i;
        }
    }
}

TEST(PhotonMap, RadiiFromAnotherMapAreItsNearestPhotonsRadius) {
    // Each photon takes the radius of the nearest source photon (ties: the lower slot, as the
    // k-nearest query breaks them), or maxRadius when none lies within it.
    const PhotonMap source(randomPhotons(500, 401));
    std::vector<float> sourceRadii(source.size());
    for (size_t j = 0; j < source.size(); ++j) sourceRadii[j] = 0.001f * float(j + 1);
    const float rMax = 0.05f;
    for (size_t n : {size_t(0), size_t(300)}) {
        const PhotonMap map(randomPhotons(n, 402));
        const std::vector<float> radii = map.radiiFrom(source, sourceRadii, rMax);
        ASSERT_EQ(radii.size(), n);
        for (size_t i = 0; i < n; ++i) {
            PhotonNeighbour best{kInfinity, 0};
            for (size_t j = 0; j < source.size(); ++j) {
                const Vec3 d = source[j].p - map[i].p;
                const PhotonNeighbour c{dot(d, d), uint32_t(j)};
                if (neighbourBefore(c, best)) best = c;
            }
            const float expected = best.d2 <= rMax * rMax ? sourceRadii[best.index] : rMax;
            EXPECT_EQ(radii[i], expected) << "photon " << i;
        }
    }
    // No source photons: every radius is maxRadius.
    const std::vector<float> none = source.radiiFrom(PhotonMap(), {}, rMax);
    for (float r : none) EXPECT_EQ(r, rMax);
}

TEST(PhotonMap, SameTreeAndRadiiForOneAndTwoThreads) {
    // Large enough that the two halves of the top levels are built in parallel.
    PhotonList input = randomPhotons(100000, 5);
    PhotonList trees[2];
    std::vector<float> radii[2];
    for (int threads : {1, 2}) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        PhotonMap map(input);
        trees[threads - 1] = map.photons();
        radii[threads - 1] = map.photonRadii(16, 1e-4f, 0.1f);
    }
    ASSERT_EQ(trees[0].size(), trees[1].size());
    EXPECT_EQ(0, std::memcmp(trees[0].data(), trees[1].data(), trees[0].size() * sizeof(Photon)));
    EXPECT_EQ(radii[0], radii[1]);
}
