// Sample numbers. A sample's stream is a pure function of (seed, pixel or photon index, sample
// index, dimension), so an image or a photon map depends on the seed only, never on the thread
// count or the order tiles are scheduled in.
//
// Two generators behind one class:
//  - random: counter-based independent uniforms, mix64(key + d·golden) per dimension d;
//  - sobol: a low-discrepancy sequence over the samples of one pixel. Dimensions are taken in
//    pairs (2k, 2k+1); each pair is the (0,2)-sequence formed by the first two Sobol dimensions
//    (van der Corput and its Pascal-matrix partner), Owen-scrambled with a seed of its own, its
//    sample index shuffled by a nested scramble of its own ("padded" Sobol, Burley 2020,
//    "Practical Hash-based Owen Scrambling"). Any 2^m consecutive samples from 0 of one pair
//    are a (0,m,2)-net: stratified in every elementary interval of area 2^-m, so the error of a
//    smooth integrand falls faster than 1/N. Each single sample is still a vector of independent
//    uniforms (Owen 1995), so every estimator stays unbiased whatever it does with them.
//    Dimensions from kSobolDimensions on fall back to the random generator.
//
// Dimension allocation of a camera sample (render/renderer.cpp, then the integrator in order):
//   0, 1  pixel jitter (x, y)              — one pair: jointly stratified
//   2     hero wavelength                  — paired with
//   3     the integrator's first number: single, the scattering points' reservoir
//         (transport/scatter_point.h); volpath, the first free flight (distance)
//   4 …   per tentative collision: the next distance, and volpath's event (absorb/scatter/
//         null) or the camera walk's roulette; at a scattering event each light's two numbers
//         (get2D: one pair), the shadow ray's distances and roulette, then volpath's phase
//         function's two numbers and the path's roulette, bounce after bounce.
// The sequence of draws depends on the path, so only the leading dimensions line up across
// samples; past kSobolDimensions the numbers are random.
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

enum class SamplerKind { Sobol, Random };

namespace sobol {

inline uint32_t reverseBits(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

// A nested scramble of a bit-reversed 32-bit fraction: bit k of the result depends only on bits
// 0…k of x (addition and multiplication by even numbers carry upwards only), i.e. on the more
// significant digits of the fraction, which is what Owen scrambling asks for (Laine & Karras
// 2011, constants of Burley 2020).
inline uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// Owen scrambling of a 32-bit fraction (MSB first): a random permutation of each digit that
// depends on the digits above it. Maps every elementary interval onto one of the same size, so
// a (t,m,s)-net stays a (t,m,s)-net.
inline uint32_t owenScramble(uint32_t x, uint32_t seed) {
    return reverseBits(laineKarras(reverseBits(x), seed));
}

// Sobol dimension 1: primitive polynomial x + 1, direction numbers m_k = 2 m_{k-1} ⊕ m_{k-1},
// m_1 = 1 (the Pascal matrix mod 2). Dimension 0 is the van der Corput sequence, reverseBits.
inline uint32_t dimension1(uint32_t index) {
    uint32_t x = 0, v = 1u << 31;
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1u) x ^= v;
    return x;
}

}  // namespace sobol

class Sampler {
public:
    // Leading dimensions drawn from the Sobol sequence; later ones are random.
    static constexpr uint32_t kSobolDimensions = 32;

    // Independent random numbers: the stream of path `index`, sample `sample`.
    Sampler(uint64_t seed, uint64_t index, uint64_t sample)
        : Sampler(SamplerKind::Random, seed, index, sample) {}
    // Sample `sample` of pixel `index`: with Sobol, the samples of one pixel are one
    // low-discrepancy sequence (scrambled per pixel and seed).
    Sampler(SamplerKind kind, uint64_t seed, uint64_t index, uint64_t sample)
        : mPixelKey(hashCombine(mix64(seed), index)),
          mKey(hashCombine(mPixelKey, sample)),
          mSample(uint32_t(sample)),
          mSobol(kind == SamplerKind::Sobol) {}

    // Uniform in [0, 1): the top 24 bits, exactly representable in a float.
    float get1D() { return float(next() >> 40) * 0x1p-24f; }
    double get1Dd() { return double(next() >> 11) * 0x1p-53; }
    // Two numbers from one pair of dimensions (jointly stratified with Sobol): skips a dimension
    // when the next one is odd.
    void get2D(float* u1, float* u2) {
        if (mSobol && (mDim & 1u)) ++mDim;
        *u1 = get1D();
        *u2 = get1D();
    }
    uint32_t dimension() const { return mDim; }
    void setDimension(uint32_t d) { mDim = d; }

private:
    uint64_t next() {
        const uint32_t d = mDim++;
        const uint64_t random = mix64(mKey + 0x9e3779b97f4a7c15ull * (uint64_t(d) + 1));
        if (!mSobol || d >= kSobolDimensions) return random;
        // The Sobol value fills the top 32 bits; random low bits keep get1Dd continuous.
        return (uint64_t(sobolValue(d)) << 32) | (random & 0xffffffffull);
    }

    uint32_t sobolValue(uint32_t d) const {
        const uint64_t pairKey = hashCombine(mPixelKey, d >> 1);
        // The pair's own order of the samples: a nested scramble of the index (bit j flips with
        // the bits above it), so samples 0 … 2^m − 1 map onto one aligned block of 2^m indices,
        // whose points are a (0,m,2)-net too.
        const uint32_t index = sobol::owenScramble(mSample, uint32_t(pairKey));
        const uint32_t x = (d & 1u) ? sobol::dimension1(index) : sobol::reverseBits(index);
        return sobol::owenScramble(x, uint32_t(pairKey >> 32) ^ (d & 1u ? 0x5bd1e995u : 0u));
    }

    uint64_t mPixelKey, mKey;
    uint32_t mSample;
    uint32_t mDim = 0;
    bool mSobol;
};

}  // namespace mirage
