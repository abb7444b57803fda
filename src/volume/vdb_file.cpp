// OpenVDB and NanoVDB files → NanoVDB grids (float; half, fp8, fp4 as read). One of the TUs allowed
// to include OpenVDB (with asset_writer.cpp and grid_expression.cpp): it costs ~28 s and ~1 GB
// to compile. Grid expressions run here, between reading and conversion, through
// openvdb_expression.h (the AX headers stay in grid_expression.cpp).
//
// Every path goes through vdbformat::scanFile first, which checks the file's own index against
// its size; OpenVDB is only asked to read files whose offsets are known to be inside the file,
// and whatever it throws is reported with a bounded message.
#include "volume/vdb_file.h"

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridStats.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/Compression.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/grid_name.h"
#include "volume/grid_lookup.h"
#include "volume/load_progress.h"
#include "volume/nano_name_padding.h"
#include "volume/openvdb_describe.h"
#include "volume/openvdb_expression.h"
#include "volume/openvdb_read.h"
#include "volume/openvdb_to_nano.h"
#include "volume/openvdb_topology.h"
#include "volume/vdb_format.h"
#include "volume/vdb_tree.h"
#include "volume/voxel_rule.h"

namespace mirage {

namespace {

using vdbformat::compressionName;
using vdbformat::describeValueType;
using vdbformat::FileLayout;
using vdbformat::Format;
using vdbformat::GridRecord;
using vdbformat::nanoClassName;

std::atomic<uint64_t> gGridReads{0};

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

void initOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

using vdbtext::describeTransform;
using vdbtext::fmt;
using vdbtext::nanoVdbGridInfo;

int requireGrid(const std::string& path, const FileLayout& layout, const std::string& name) {
    int index = vdbformat::findGrid(layout, name);
    if (index < 0)
        fail(path, "no grid '" + boundedMessage(name, 60) +
                       "' (grids: " + vdbformat::gridList(layout) + ")");
    return index;
}

void checkFogClass(const std::string& path, const std::string& label, const std::string& cls) {
    if (cls == "level set")
        fail(path, "grid " + label +
                       " is a level set (signed distance), expected a fog volume "
                       "(density); convert it to a fog volume first (e.g. vdb_tool or Houdini)");
    if (cls != "fog volume" && cls != "unknown")
        fail(path, "grid " + label + " is a " + cls + " grid, expected a fog volume (density)");
}

// Lazy: the leaves' values read when first touched (OpenVDB's delayed loading: the file mapped,
// not copied, until the grid is dropped), then on every core (openvdb_read.h).
enum class ReadMode { Metadata, Values, Lazy };

// With `leaves`, a float tree's leaf data are indexed by the walk (vdb_tree.h) and OpenVDB reads
// its topology alone (openvdb_topology.h): its leaves are then for the index's decoder only.
openvdb::GridBase::Ptr readOpenVdbGrid(const std::string& path, const FileLayout& layout, int index,
                                       ReadMode mode, vdbformat::LeafDataIndex* leaves = nullptr) {
    const GridRecord& record = layout.grids[size_t(index)];
    const std::string label = vdbformat::gridLabel(layout, index);
    // The tree's counts and block sizes are checked before OpenVDB trusts them (vdb_tree.h).
    if (mode != ReadMode::Metadata) {
        vdbformat::checkOpenVdbTree(path, layout, index, leaves);
        ++gGridReads;
    }
    initOpenVdb();
    try {
        // OpenVDB reads a lazy grid's topology in one call, leaf by leaf (a second at 10⁹
        // voxels): a stage of one step.
        LoadStage topology("reading the topology of", path, label,
                           mode == ReadMode::Lazy ? record.endPos - record.gridPos : 0, 1, "step");
        const bool topologyOnly = leaves && !leaves->offsets.empty() && mode == ReadMode::Lazy &&
                                  record.instanceParent.empty();
        openvdb::io::File file(path);
        file.setCopyMaxBytes(0);
        file.open(/*delayLoad=*/mode == ReadMode::Lazy && !topologyOnly);
        const std::string name = openvdb::io::GridDescriptor::nameAsString(record.uniqueName);
        openvdb::GridBase::Ptr grid;
        if (topologyOnly) grid = readFloatTopology(file, path, layout, record, name, *leaves);
        if (!grid)
            grid = mode == ReadMode::Metadata ? file.readGridMetadata(name) : file.readGrid(name);
        file.close();
        topology.advance(1);
        topology.finish();
        // A singular index → object map (a zero or denormal voxel size in a corrupt file) reads
        // without complaint, but OpenVDB throws ArithmeticError wherever the map is later
        // inverted or turned affine: build the affine form now, inside this handler.
        const openvdb::math::MapBase::ConstPtr map = grid->transform().baseMap();
        if (map->isLinear()) map->getAffineMap();
        return grid;
    } catch (const openvdb::ArithmeticError& e) {
        fail(path, "grid " + label + " has a singular index → object transform (" +
                       boundedMessage(e.what()) + "); expected a non-zero voxel size");
    } catch (const std::bad_alloc&) {
        // OpenVDB allocates whatever size the file claims for a compressed block.
        fail(path,
             "OpenVDB ran out of memory reading grid " + label + "; its data is probably corrupt");
    } catch (const std::exception& e) {
        fail(path, "OpenVDB could not read grid " + label + ": " + boundedMessage(e.what()));
    }
}

// Reads a grid and returns it as a float grid (double grids are converted; float grids stored
// as half come back as float already), after checking that it is a scalar fog volume. A float
// grid's leaves are still in the file (delayed loading): toNanoVdb or readLeavesInParallel
// reads them.
openvdb::FloatGrid::Ptr readFogVolume(const std::string& path, const FileLayout& layout, int index,
                                      vdbformat::LeafDataIndex* leaves = nullptr) {
    const GridRecord& record = layout.grids[size_t(index)];
    const std::string label = vdbformat::gridLabel(layout, index);
    const std::string valueType = vdbformat::valueTypeOf(record);
    if (valueType != "float" && valueType != "half" && valueType != "double")
        fail(path, "grid " + label + " holds " + describeValueType(valueType) +
                       " values, expected a scalar float fog volume (density)");
    openvdb::GridBase::Ptr base = readOpenVdbGrid(path, layout, index, ReadMode::Lazy, leaves);
    checkFogClass(path, label, openvdb::GridBase::gridClassToString(base->getGridClass()));
    if (!base->transform().baseMap()->isLinear())
        fail(path, "grid " + label + " has a " + base->transform().mapType() +
                       " transform; only affine index → object maps are supported");

    openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!grid) {
        auto dgrid = openvdb::gridPtrCast<openvdb::DoubleGrid>(base);
        if (!dgrid) fail(path, "grid " + label + " has an unexpected tree type " + record.type);
        // Value-converting deep copy: same topology, values rounded to float.
        grid = openvdb::FloatGrid::create(std::make_shared<openvdb::FloatTree>(dgrid->tree()));
        grid->setTransform(dgrid->transform().copy());
        grid->insertMeta(*dgrid);
    }
    // A fog volume is 0 outside its active voxels; a non-zero background fills all of space
    // (level sets store their narrow-band width there).
    if (grid->background() != 0.f)
        fail(path, "grid " + label + " has background value " + fmt(grid->background()) +
                       ", expected 0 for a fog volume (is it a level set?)");
    return grid;
}

// Reads a NanoVDB grid's bytes, decompressing with OpenVDB's Blosc/zip readers: their stream
// format (an int64 byte count, then the compressed bytes) is the one nanovdb::io writes, and it
// spares Mirage a direct dependency on libblosc.
nanovdb::GridHandle<nanovdb::HostBuffer> readNanoVdbGrid(const std::string& path,
                                                         const GridRecord& record,
                                                         const std::string& label) {
    constexpr uint64_t kChunkBytes = uint64_t(1) << 30;  // nanovdb::io's Blosc chunk size
    // Smaller than a grid, a tree and a root header cannot be a grid.
    constexpr uint64_t kMinGridBytes = sizeof(nanovdb::NanoGrid<float>) +
                                       sizeof(nanovdb::NanoTree<float>) +
                                       sizeof(nanovdb::NanoRoot<float>);
    ++gGridReads;
    if (record.nanoGridBytes < kMinGridBytes)
        fail(path, "corrupt: NanoVDB grid " + label + " claims only " +
                       std::to_string(record.nanoGridBytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot be opened");
    in.seekg(std::streamoff(record.gridPos));
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(record.nanoGridBytes);
    char* data = reinterpret_cast<char*>(buffer.data());
    try {
        if (record.compression == 0) {
            in.read(data, std::streamsize(record.nanoGridBytes));
        } else {
            uint64_t pos = record.gridPos, remaining = record.nanoGridBytes;
            do {
                // Check the chunk's byte count against the grid's extent before OpenVDB
                // allocates a buffer of that size.
                int64_t bytes = 0;
                in.read(reinterpret_cast<char*>(&bytes), 8);
                if (!in || bytes <= 0 || pos + 8 + uint64_t(bytes) > record.endPos)
                    fail(path, "corrupt: compressed NanoVDB grid " + label + " has a chunk of " +
                                   std::to_string(bytes) + " bytes at byte " + std::to_string(pos) +
                                   " that does not fit in the grid");
                in.seekg(std::streamoff(pos));
                uint64_t chunk =
                    record.compression == 2 ? std::min(remaining, kChunkBytes) : remaining;
                if (record.compression == 2)
                    openvdb::io::bloscFromStream(in, data, chunk);
                else
                    openvdb::io::unzipFromStream(in, data, chunk);
                pos += 8 + uint64_t(bytes);
                in.seekg(std::streamoff(pos));
                data += chunk;
                remaining -= chunk;
            } while (remaining > 0);
        }
    } catch (const MirageError&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, "could not decompress NanoVDB grid " + label + ": " + boundedMessage(e.what()));
    }
    if (!in) fail(path, "read error in NanoVDB grid " + label);

    nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
    const nanovdb::GridMetaData* meta = handle.gridMetaData();
    if (!meta || !meta->isValid() || meta->gridSize() != record.nanoGridBytes ||
        meta->gridIndex() >= meta->gridCount())
        fail(path, "corrupt: NanoVDB grid " + label + " does not hold a valid grid");
    // A grid keeps the index it had among the grids written together; GridHandle::grid(n)
    // steps from grid to grid by their sizes until it meets index n, past this one-grid buffer
    // for any n but the grid's own (fuzz_vdb found a read past the buffer that way).
    nanovdb::FloatGrid* grid = handle.grid<float>(meta->gridIndex());
    if (!grid) fail(path, "corrupt: NanoVDB grid " + label + " is not the float grid it claims");
    // NanoVDB's validator computes the checksum first, walking the root's tile table and the
    // node arrays by the counts and offsets the file states: bound those by the buffer before
    // it reads a byte through them (a corrupt table size sent it far past the buffer).
    if (!vdbformat::nanoLayoutFits(*grid, record.nanoGridBytes))
        fail(path, "corrupt: NanoVDB grid " + label + " has node tables outside its " +
                       std::to_string(record.nanoGridBytes) + " bytes or off 32-byte alignment");
    // Checksum, then every node pointer against the buffer's extent.
    std::string problem = nanovdb::GridValidator<float>::check(*grid, /*detailed=*/true);
    if (!problem.empty())
        fail(path, "corrupt: NanoVDB grid " + label + ": " + boundedMessage(problem));
    // From here on the buffer is a handle of its own: grid 0 of 1, with the checksum (which
    // covers those fields) brought up to date.
    if (grid->gridIndex() != 0 || grid->gridCount() != 1) {
        grid->data()->mGridIndex = 0;
        grid->data()->mGridCount = 1;
        nanovdb::updateChecksum(*grid, nanovdb::ChecksumMode::Partial);
    }
    return handle;
}

GridInfo openVdbGridInfo(const std::string& path, const FileLayout& layout, int index) {
    const GridRecord& record = layout.grids[size_t(index)];
    const std::string label = vdbformat::gridLabel(layout, index);
    openvdb::GridBase::Ptr grid = readOpenVdbGrid(path, layout, index, ReadMode::Metadata);

    GridInfo info;
    info.name = record.name;
    info.valueType = grid->valueType();
    auto halfMeta =
        grid->getMetadata<openvdb::BoolMetadata>(openvdb::GridBase::META_SAVE_HALF_FLOAT);
    if (info.valueType == "float" &&
        (record.savedAsHalf || grid->saveFloatAsHalf() || (halfMeta && halfMeta->value())))
        info.valueType = "half";
    info.gridClass = openvdb::GridBase::gridClassToString(grid->getGridClass());
    const openvdb::Vec3d vs = grid->transform().voxelSize();
    info.voxelSize = Vec3d(vs[0], vs[1], vs[2]);
    info.transform = describeTransform(grid->transform());
    info.compression = compressionName(record.compression, Format::OpenVdb);

    // The statistics OpenVDB stores with each grid; files written without them cost a full
    // read of the grid.
    auto bmin = grid->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
    auto bmax = grid->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
    auto voxels =
        grid->getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_VOXEL_COUNT);
    auto mem = grid->getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
    openvdb::CoordBBox box;
    if (bmin && bmax && voxels) {
        box = openvdb::CoordBBox(openvdb::Coord(bmin->value()), openvdb::Coord(bmax->value()));
        info.activeVoxels = uint64_t(std::max<int64_t>(0, voxels->value()));
        info.memoryBytes = mem ? uint64_t(std::max<int64_t>(0, mem->value())) : 0;
    } else if (vdbformat::treeIsWalkable(layout, index)) {
        openvdb::GridBase::Ptr full = readOpenVdbGrid(path, layout, index, ReadMode::Values);
        box = full->evalActiveVoxelBoundingBox();
        info.activeVoxels = full->activeVoxelCount();
        info.memoryBytes = full->memUsage();
    }
    if (info.activeVoxels > 0 && !box.empty()) {
        for (int a = 0; a < 3; ++a) {
            info.indexMin[a] = box.min()[a];
            info.indexMax[a] = box.max()[a];
        }
        // Voxel centres are at integer index coordinates: the voxels span ±½ around them.
        for (int c = 0; c < 8; ++c) {
            openvdb::Vec3d corner(c & 1 ? box.max()[0] + 0.5 : box.min()[0] - 0.5,
                                  c & 2 ? box.max()[1] + 0.5 : box.min()[1] - 0.5,
                                  c & 4 ? box.max()[2] + 0.5 : box.min()[2] - 0.5);
            openvdb::Vec3d p = grid->transform().indexToWorld(corner);
            info.objectBounds.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
    }
    return info;
}

// NanoVDB's own converter: its failure named, what it leaves unwritten zeroed (its padding).
template <typename GridT>
nanovdb::GridHandle<nanovdb::HostBuffer> nanoVdbOf(const std::string& path,
                                                   const std::string& label, const GridT& grid) {
    try {
        auto handle =
            nanovdb::openToNanoVDB(grid, nanovdb::StatsMode::All, nanovdb::ChecksumMode::Partial);
        zeroNamePadding(handle);
        return handle;
    } catch (const std::exception& e) {
        fail(path, "could not convert grid " + label + " to NanoVDB: " + boundedMessage(e.what()));
    }
}

// The NanoVDB grid of a fog volume from readFogVolume, under the voxel rule (what it changed in
// *sanitized), at `streamed` where openvdb_to_nano.h encodes it, else float: its leaves read from
// the file (`fileBytes` of it: the bar's length) as they are converted. With `releaseLeaves` the
// OpenVDB grid keeps only its topology afterwards, so that a big grid's values are never held
// twice; *leafMaximum is the largest value its leaves store. Grids that converter does not take (a
// staggered class, a long name) go through NanoVDB's own, at float, *leafMaximum is nullopt.
// `leaves`: where the walk found the leaves' data.
nanovdb::GridHandle<nanovdb::HostBuffer> toNanoVdb(
    const std::string& path, const std::string& label, openvdb::FloatGrid& grid, uint64_t fileBytes,
    bool releaseLeaves, GridPrecision streamed, SanitizeCounts* sanitized,
    std::optional<float>* leafMaximum, const vdbformat::LeafDataIndex* leaves = nullptr) {
    if (convertsDirectly(grid)) {
        float maximum = 0.f;
        auto handle =
            convertFloatGrid(grid, streamsPrecision(streamed) ? streamed : GridPrecision::Float,
                             fileBytes, path, label, releaseLeaves, sanitized, &maximum, leaves);
        *leafMaximum = maximum;
        return handle;
    }
    *leafMaximum = std::nullopt;
    readLeavesInParallel(grid, fileBytes, path, label);
    auto handle = nanoVdbOf(path, label, grid);
    *sanitized = sanitizeScalarVoxels(handle);
    return handle;
}

// The voxel rule's warning for a converted grid (`label` names the grid in it), and the name
// the grid goes by: its own, or "#N".
FloatGrid finishGrid(const std::string& path, const FileLayout& layout, int index,
                     nanovdb::GridHandle<nanovdb::HostBuffer> handle, const std::string& label,
                     const SanitizeCounts& sanitized, std::optional<float> leafMaximum) {
    if (sanitized.total() > 0) warnSanitizedOnce(path, label, sanitized);
    std::string name = gridName(layout.grids[size_t(index)].name, size_t(index));
    return FloatGrid(std::move(handle), std::move(name), sanitized.total(), leafMaximum);
}

}  // namespace

void validateVdbFile(const std::string& path) { vdbformat::scanFile(path); }

uint64_t gridReadCount() { return gGridReads; }

GridTopology readGridTopology(const std::string& path, const std::string& gridName) {
    const FileLayout layout = vdbformat::scanFile(path);
    const int index = requireGrid(path, layout, gridName);
    const vdbformat::TreeCounts n = vdbformat::countOpenVdbTree(path, layout, index);
    return {n.leaves, openvdbtonano::NanoOffsets<>(n.rootEntries, n.upper, n.lower, n.leaves).end};
}

VdbFileInfo inspectVdbFile(const std::string& path) {
    const FileLayout layout = vdbformat::scanFile(path);
    VdbFileInfo info;
    info.path = path;
    if (layout.format == Format::NanoVdb) {
        info.format = "NanoVDB";
        info.fileVersion = info.libraryVersion = vdbformat::nanoVersionString(layout.fileVersion);
        for (const GridRecord& record : layout.grids) info.grids.push_back(nanoVdbGridInfo(record));
        return info;
    }
    info.format = "OpenVDB";
    info.fileVersion = std::to_string(layout.fileVersion);
    info.libraryVersion =
        std::to_string(layout.libraryMajor) + "." + std::to_string(layout.libraryMinor);
    for (size_t i = 0; i < layout.grids.size(); ++i)
        info.grids.push_back(openVdbGridInfo(path, layout, int(i)));
    return info;
}

FloatGrid loadFloatGrid(const std::string& path, const std::string& gridName,
                        GridPrecision streamed) {
    const FileLayout layout = vdbformat::scanFile(path);
    const int index = requireGrid(path, layout, gridName);
    const GridRecord& record = layout.grids[size_t(index)];
    const std::string label = vdbformat::gridLabel(layout, index);

    nanovdb::GridHandle<nanovdb::HostBuffer> handle;
    SanitizeCounts sanitized;
    std::optional<float> leafMaximum;
    if (layout.format == Format::NanoVdb) {
        const std::string valueType = vdbformat::valueTypeOf(record);
        if (valueType != "float")
            fail(path, "NanoVDB grid " + label + " holds " + describeValueType(valueType) +
                           " values, expected a scalar float fog volume (density)");
        checkFogClass(path, label, nanoClassName(record.nanoGridClass));
        handle = readNanoVdbGrid(path, record, label);
        float background = handle.grid<float>()->tree().background();
        if (background != 0.f)
            fail(path, "grid " + label + " has background value " + fmt(background) +
                           ", expected 0 for a fog volume (is it a level set?)");
        sanitized = sanitizeScalarVoxels(handle);
    } else {
        vdbformat::LeafDataIndex leaves;
        handle = toNanoVdb(path, label, *readFogVolume(path, layout, index, &leaves),
                           record.endPos - record.gridPos, /*releaseLeaves=*/true, streamed,
                           &sanitized, &leafMaximum, &leaves);
    }
    return finishGrid(path, layout, index, std::move(handle), label, sanitized, leafMaximum);
}

std::vector<FloatGrid> loadFloatGrids(const std::string& path,
                                      const std::vector<std::string>& gridNames,
                                      const std::vector<GridExpression>& expressions,
                                      std::vector<double>* expressionSeconds,
                                      GridPrecision streamed) {
    if (expressionSeconds) expressionSeconds->clear();
    std::vector<FloatGrid> out;
    if (expressions.empty()) {
        for (const std::string& name : gridNames)
            out.push_back(loadFloatGrid(path, name, streamed));
        return out;
    }
    const FileLayout layout = vdbformat::scanFile(path);
    if (layout.format == Format::NanoVdb)
        throw MirageError(expressions[0].where,
                          expressions[0].label + ": expressions run on OpenVDB grids, but " + path +
                              " is a NanoVDB file; give the OpenVDB (.vdb) cache");

    // Each grid is read once, by index, and carries the name AX will look it up by: its name
    // in the file, or "#N" when it has none.
    auto canonicalName = [&](int index) {
        return gridName(layout.grids[size_t(index)].name, size_t(index));
    };
    std::map<int, openvdb::FloatGrid::Ptr> grids;
    auto read = [&](int index) {
        openvdb::FloatGrid::Ptr& grid = grids[index];
        if (!grid) {
            const GridRecord& record = layout.grids[size_t(index)];
            grid = readFogVolume(path, layout, index);
            readLeavesInParallel(*grid, record.endPos - record.gridPos, path,
                                 vdbformat::gridLabel(layout, index));
            grid->setName(canonicalName(index));
        }
        return grid;
    };
    std::vector<int> wanted;
    for (const std::string& name : gridNames) {
        wanted.push_back(requireGrid(path, layout, name));
        read(wanted.back());
    }

    std::set<int> written;
    for (const GridExpression& e : expressions) {
        const ExpressionAccess access = expressionAccess(e);
        std::vector<std::string> names = access.reads;
        names.insert(names.end(), access.writes.begin(), access.writes.end());
        openvdb::GridPtrVec inputs;
        std::set<int> seen;
        for (const std::string& name : names) {
            const int index = vdbformat::findGrid(layout, name);
            if (index < 0)
                throw MirageError(
                    e.where, e.label + ": the expression names grid '" + boundedMessage(name, 60) +
                                 "', but " + path +
                                 " has no such grid (grids: " + vdbformat::gridList(layout) + ")");
            if (seen.insert(index).second) inputs.push_back(read(index));
        }
        for (const std::string& name : access.writes)
            written.insert(vdbformat::findGrid(layout, name));
        GridExpression bound = e;
        for (auto& binding : bound.bindings) {
            const int index = vdbformat::findGrid(layout, binding.second);
            if (index >= 0) binding.second = canonicalName(index);
        }
        const double seconds = runGridExpression(bound, inputs, path);
        if (expressionSeconds) expressionSeconds->push_back(seconds);
    }

    for (const int index : wanted) {
        std::string label = vdbformat::gridLabel(layout, index);
        // Read already (for the expressions): no second bar; a grid named twice is converted
        // twice, so its leaves stay.
        SanitizeCounts sanitized;
        std::optional<float> leafMaximum;
        auto handle = toNanoVdb(path, label, *grids[index], 0, /*releaseLeaves=*/false, streamed,
                                &sanitized, &leafMaximum);
        if (written.count(index)) label += " (after its expression)";
        out.push_back(
            finishGrid(path, layout, index, std::move(handle), label, sanitized, leafMaximum));
    }
    return out;
}

static VectorGrid finishVectorGrid(const std::string& path, const std::string& label,
                                   const openvdb::Vec3SGrid& grid, bool staggered,
                                   const std::string& name);

VectorGrid loadVectorGrid(const std::string& path, const std::string& gridName) {
    const FileLayout layout = vdbformat::scanFile(path);
    const int index = requireGrid(path, layout, gridName);
    const GridRecord& record = layout.grids[size_t(index)];
    const std::string label = vdbformat::gridLabel(layout, index);
    const std::string valueType = vdbformat::valueTypeOf(record);
    if (layout.format == Format::NanoVdb)
        fail(path, "grid " + label + ": vector grids are read from OpenVDB (.vdb) files only; " +
                       "give the OpenVDB cache");
    if (valueType != "vec3s" && valueType != "vec3d")
        fail(path, "grid " + label + " holds " + describeValueType(valueType) +
                       " values, expected a 3-vector grid (vec3s or vec3d) of velocities");
    openvdb::GridBase::Ptr base = readOpenVdbGrid(path, layout, index, ReadMode::Lazy);
    if (!base->transform().baseMap()->isLinear())
        fail(path, "grid " + label + " has a " + base->transform().mapType() +
                       " transform; only affine index → object maps are supported");
    const bool staggered = base->getGridClass() == openvdb::GRID_STAGGERED;
    openvdb::Vec3SGrid::Ptr grid = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base);
    if (grid) readLeavesInParallel(*grid, record.endPos - record.gridPos, path, label);
    if (!grid) {
        auto dgrid = openvdb::gridPtrCast<openvdb::Vec3DGrid>(base);
        if (!dgrid) fail(path, "grid " + label + " has an unexpected tree type " + record.type);
        grid = openvdb::Vec3SGrid::create(std::make_shared<openvdb::Vec3STree>(dgrid->tree()));
        grid->setTransform(dgrid->transform().copy());
    }
    return finishVectorGrid(path, label, *grid, staggered,
                            mirage::gridName(record.name, size_t(index)));
}

// The common end of both vector loaders: background check, NanoVDB conversion, voxel rule.
static VectorGrid finishVectorGrid(const std::string& path, const std::string& label,
                                   const openvdb::Vec3SGrid& grid, bool staggered,
                                   const std::string& name) {
    // Outside its active voxels a velocity field is still: a non-zero background moves all space.
    if (grid.background() != openvdb::Vec3s(0.f))
        fail(path, "grid " + label + " has a non-zero background vector, expected (0, 0, 0)");
    auto handle = nanoVdbOf(path, label, grid);
    uint64_t zeroed = 0;
    const uint64_t changed = sanitizeVectorVoxels(handle, kMaxVoxelValue, &zeroed);
    if (changed > 0) {
        SanitizeCounts counts;
        counts.zeroed = zeroed;
        counts.clamped = changed - zeroed;
        warnSanitizedOnce(path, label, counts, /*vectors=*/true);
    }
    return VectorGrid(std::move(handle), name, staggered, changed);
}

VectorGrid loadVectorGridFromScalars(const std::string& path, const std::string& stem) {
    const FileLayout layout = vdbformat::scanFile(path);
    if (layout.format == Format::NanoVdb)
        fail(path, "velocity '" + stem +
                       "': vector grids are read from OpenVDB (.vdb) files "
                       "only; give the OpenVDB cache");
    // Each component is a signed scalar grid: read as stored (the fog-volume rule, which
    // zeroes negative values, would stop every particle moving towards −x).
    openvdb::FloatGrid::Ptr parts[3];
    for (int a = 0; a < 3; ++a) {
        const std::string name = stem + "." + "xyz"[a];
        const int index = requireGrid(path, layout, name);
        const std::string label = vdbformat::gridLabel(layout, index);
        if (vdbformat::valueTypeOf(layout.grids[size_t(index)]) != "float")
            fail(path, "grid " + label + " holds " +
                           describeValueType(vdbformat::valueTypeOf(layout.grids[size_t(index)])) +
                           " values, expected a float grid (one velocity component)");
        parts[a] = openvdb::gridPtrCast<openvdb::FloatGrid>(
            readOpenVdbGrid(path, layout, index, ReadMode::Values));
        if (!parts[a]) fail(path, "grid " + label + " is not a float grid");
        if (!parts[a]->transform().baseMap()->isLinear() ||
            parts[a]->transform() != parts[0]->transform())
            fail(path, "grid " + label +
                           ": the three velocity components must share one "
                           "affine transform");
        if (parts[a]->background() != 0.f)
            fail(path, "grid " + label + " has a non-zero background, expected 0");
    }
    // The vector grid covers the union of the components' active voxels.
    openvdb::Vec3SGrid::Ptr grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    grid->setTransform(parts[0]->transform().copy());
    for (int a = 0; a < 3; ++a) grid->tree().topologyUnion(parts[a]->tree());
    openvdb::FloatGrid::ConstAccessor acc[3] = {
        parts[0]->getConstAccessor(), parts[1]->getConstAccessor(), parts[2]->getConstAccessor()};
    for (auto it = grid->beginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        it.setValue(openvdb::Vec3s(acc[0].getValue(c), acc[1].getValue(c), acc[2].getValue(c)));
    }
    return finishVectorGrid(path, "'" + stem + ".x/.y/.z'", *grid, false, stem);
}

}  // namespace mirage
