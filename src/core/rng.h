// Counter-based random numbers. A sample's random stream is a pure function of
// (seed, pixel or photon index, sample index, dimension), so an image or a photon map depends
// on the seed only, never on the thread count or the order tiles are scheduled in.
#pragma once

#include <cstdint>

namespace mirage {

// 64-bit finaliser of SplitMix64 / Murmur3 (Steele et al. 2014): a bijective avalanche mix.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

inline uint64_t hashCombine(uint64_t a, uint64_t b) {
    return mix64(a ^ (b + 0x9e3779b97f4a7c15ull + (a << 6) + (a >> 2)));
}

// Stream of uniform numbers for one (seed, index, sample). Dimension d of the stream is
// mix64(key + d·golden): independent of how many numbers other streams consumed.
class Sampler {
public:
    Sampler(uint64_t seed, uint64_t index, uint64_t sample)
        : mKey(hashCombine(hashCombine(mix64(seed), index), sample)) {}

    // Uniform in [0, 1): the top 24 bits of a 64-bit hash, exactly representable in a float.
    float get1D() { return float(next() >> 40) * 0x1p-24f; }
    double get1Dd() { return double(next() >> 11) * 0x1p-53; }
    uint32_t dimension() const { return mDim; }
    void setDimension(uint32_t d) { mDim = d; }

private:
    uint64_t next() { return mix64(mKey + 0x9e3779b97f4a7c15ull * (uint64_t(mDim++) + 1)); }
    uint64_t mKey;
    uint32_t mDim = 0;
};

}  // namespace mirage
