#include "volume/grid_precision.h"

#include <nanovdb/NanoVDB.h>

namespace mirage {

const char* precisionName(GridPrecision p) {
    switch (p) {
        case GridPrecision::Half:
            return "half";
        case GridPrecision::Fp8:
            return "fp8";
        case GridPrecision::Fp4:
            return "fp4";
        case GridPrecision::FpN:
            return "fpn";
        case GridPrecision::Float:
            break;
    }
    return "float";
}

bool parsePrecision(const std::string& name, GridPrecision* p) {
    for (GridPrecision q : kAllPrecisions)
        if (name == precisionName(q)) {
            *p = q;
            return true;
        }
    return false;
}

std::string precisionNames() { return "float, half, fp8, fp4 or fpn"; }

int precisionBits(GridPrecision p) {
    switch (p) {
        case GridPrecision::Half:
            return 16;
        case GridPrecision::Fp8:
            return 8;
        case GridPrecision::Fp4:
            return 4;
        case GridPrecision::FpN:
            return 16;
        case GridPrecision::Float:
            break;
    }
    return 32;
}

float quantisationBound(const PrecisionSpec& spec, float maxValue) {
    switch (spec.precision) {
        case GridPrecision::Float:
            return 0.f;
        case GridPrecision::FpN:
            return spec.relativeTolerance * maxValue;
        default:
            break;
    }
    const double steps = double((uint64_t(1) << precisionBits(spec.precision)) - 1);
    return float(double(maxValue) / (2.0 * steps));
}

uint64_t leafNodeBytes(GridPrecision p) {
    switch (p) {
        case GridPrecision::Half:
            return nanovdb::NanoLeaf<nanovdb::Fp16>::DataType::memUsage();
        case GridPrecision::Fp8:
            return uint64_t(nanovdb::NanoLeaf<nanovdb::Fp8>::DataType::memUsage());
        case GridPrecision::Fp4:
            return nanovdb::NanoLeaf<nanovdb::Fp4>::DataType::memUsage();
        case GridPrecision::FpN:
            return nanovdb::NanoLeaf<nanovdb::FpN>::DataType::memUsage(16);
        case GridPrecision::Float:
            break;
    }
    return nanovdb::NanoLeaf<float>::DataType::memUsage();
}

uint64_t treeBytesAt(GridPrecision to, GridPrecision from, uint64_t bytes, uint64_t leaves) {
    if (to == from) return bytes;
    if (from == GridPrecision::FpN) return 0;  // its leaves' sizes vary: the rest is unknown
    return bytes - leaves * leafNodeBytes(from) + leaves * leafNodeBytes(to);
}

}  // namespace mirage
