#include "volume/grid_quantise.h"

#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/NanoToOpenVDB.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

#include "core/error.h"
#include "volume/grid_lookup.h"
#include "volume/nano_name_padding.h"

namespace mirage {

namespace {

using Handle = nanovdb::GridHandle<nanovdb::HostBuffer>;

template <typename BuildT>
Handle encode(const openvdb::FloatGrid& grid) {
    Handle handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, BuildT>(
        grid, nanovdb::StatsMode::All, nanovdb::ChecksumMode::Partial);
    zeroNamePadding(handle);
    return handle;
}

// FpN with an absolute tolerance (grid units): NanoVDB's oracle tests all 512 values of a leaf,
// inactive ones too, at each bit width in turn.
Handle encodeFpn(const openvdb::FloatGrid& grid, float tolerance) {
    nanovdb::OpenToNanoVDB<float, nanovdb::FpN, nanovdb::AbsDiff> converter;
    converter.oracle() = nanovdb::AbsDiff(tolerance);
    Handle handle = converter(grid, nanovdb::StatsMode::All, nanovdb::ChecksumMode::Partial, 0);
    zeroNamePadding(handle);
    return handle;
}

}  // namespace

FloatGrid quantiseGrid(const FloatGrid& grid, const PrecisionSpec& spec) {
    if (spec.precision == GridPrecision::Float || grid.precision() != GridPrecision::Float)
        return grid;
    Handle handle;
    try {
        const openvdb::FloatGrid::Ptr open = nanovdb::nanoToOpenVDB(*grid.grid());
        switch (spec.precision) {
            case GridPrecision::Half:
                handle = encode<nanovdb::Fp16>(*open);
                break;
            case GridPrecision::Fp8:
                handle = encode<nanovdb::Fp8>(*open);
                break;
            case GridPrecision::Fp4:
                handle = encode<nanovdb::Fp4>(*open);
                break;
            case GridPrecision::FpN:
                handle = encodeFpn(*open, spec.relativeTolerance * grid.maxValue());
                break;
            case GridPrecision::Float:
                break;
        }
    } catch (const std::exception& e) {
        throw MirageError("grid '" + grid.name() + "': could not encode it at precision " +
                          precisionName(spec.precision) + ": " + boundedMessage(e.what()));
    }
    return FloatGrid(std::move(handle), grid.name(), grid.sanitizedVoxels());
}

std::vector<FloatGrid> quantiseGrids(std::vector<FloatGrid> grids, const PrecisionSpec& spec) {
    for (FloatGrid& g : grids) g = quantiseGrid(g, spec);
    return grids;
}

std::vector<FloatGrid> loadGridsAt(const std::string& path,
                                   const std::vector<std::string>& gridNames,
                                   const std::vector<GridExpression>& expressions,
                                   std::vector<double>* expressionSeconds,
                                   const PrecisionSpec& spec) {
    return quantiseGrids(
        loadFloatGrids(path, gridNames, expressions, expressionSeconds, spec.precision), spec);
}

}  // namespace mirage
