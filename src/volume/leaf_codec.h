// One 8³ leaf's 512 values written into a NanoVDB leaf at the precision it holds (float, Fp16,
// Fp8 or Fp4: volume/grid_precision.h), and its active values read back as a lookup decodes
// them: what the streaming converter (volume/openvdb_to_nano.h) does per leaf.
//
// The quantised leaves are bit for bit NanoVDB 32.4's encoder (nanovdb/util/OpenToNanoVDB.h,
// processLeafs for Fp4/Fp8/Fp16, dithering off, as openToNanoVDB calls it): the leaf's minimum
// m and maximum M over all 512 values, active or not; the step q = (M − m)/(2^b − 1) in float;
// each code the integer part of e·(v − m) + ½, with e = (2^b − 1)/(M − m) in double for 16 bits
// and in float below, written with the same operations in the same types. A leaf of one value
// (M = m) makes e infinite and e·0 a NaN, which NanoVDB converts to an integer as the x86 SSE
// conversion does (0x80000000, whose low bits are 0): its codes are written as 0 here, so that
// the result no longer rests on that conversion. Fp4 packs two codes a byte, the even voxel in
// the low nibble.
//
// NanoVDB only: no OpenVDB here.
#pragma once

#include <nanovdb/NanoVDB.h>

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace mirage {

template <typename BuildT>
struct LeafCodec {
    using Data = typename nanovdb::NanoLeaf<BuildT>::DataType;
    static constexpr bool kQuantised = !std::is_same_v<BuildT, float>;
    static constexpr uint32_t kSize = nanovdb::NanoLeaf<BuildT>::SIZE;
    static_assert(kSize == 512, "8³ leaves");

    // The statistics fields zeroed, as NanoVDB's converter leaves a leaf before its statistics.
    static void clearStats(Data& data) {
        if constexpr (kQuantised) {
            data.mDev = data.mAvg = data.mMax = data.mMin = 0u;
        } else {
            data.mMaximum = data.mMinimum = 0.f;
            data.mStdDevi = data.mAverage = 0.f;
        }
    }

    // Writes `values` (512 of them, under the voxel rule; their smallest `lo` and largest `hi`)
    // into the leaf; returns the largest value a lookup decodes from it: `hi` itself for float,
    // else the decoded code of `hi` (the codes and their decoding are both monotonic).
    static float encode(Data& data, const float* values, float lo, float hi) {
        if constexpr (!kQuantised) {
            std::memcpy(data.mValues, values, sizeof(data.mValues));
            return hi;
        } else {
            constexpr int bits = Data::bitWidth();
            data.init(lo, hi, uint8_t(bits));
            if (hi == lo) {
                std::memset(data.mCode, 0, sizeof(data.mCode));
                return data.getValue(0);
            }
            // In double for 16 bits, as NanoVDB: a float product keeps 8 bits below a code's unit.
            using Real = std::conditional_t<bits >= 16, double, float>;
            const Real e = Real((1 << bits) - 1) / (hi - lo);
            using Code = typename Data::ArrayType;
            auto code = [&](float v) { return Code(e * (v - lo) + 0.5f); };
            if constexpr (bits == 4) {
                for (uint32_t i = 0; i < kSize; i += 2)
                    data.mCode[i / 2] = Code(code(values[i + 1]) << 4 | code(values[i]));
            } else {
                for (uint32_t i = 0; i < kSize; ++i) data.mCode[i] = code(values[i]);
            }
            return float(code(hi)) * data.mQuantum + data.mMinimum;
        }
    }

    // The leaf's active values as a lookup reads them, in mask order (GridStats' order), into
    // `out`; returns their count.
    static uint32_t activeValues(const Data& data, float* out) {
        uint32_t n = 0;
        for (uint32_t w = 0; w < kSize / 64; ++w) {
            uint64_t word = data.mValueMask.template getWord<uint64_t>(w);
            if constexpr (!kQuantised) {
                const float* values = data.mValues + 64 * w;
                if (word == ~uint64_t(0)) {
                    std::memcpy(out + n, values, 64 * sizeof(float));
                    n += 64;
                    continue;
                }
                for (; word != 0; word &= word - 1) out[n++] = values[__builtin_ctzll(word)];
            } else {
                for (; word != 0; word &= word - 1)
                    out[n++] = data.getValue(64 * w + uint32_t(__builtin_ctzll(word)));
            }
        }
        return n;
    }
};

}  // namespace mirage
