// Procedural assets → OpenVDB files, and the one OpenVDB file writer (tools/vdb_writer.h) that
// the test grids share. The tools' only translation unit that includes OpenVDB.
#include "tools/asset_writer.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/text.h"
#include "tools/dense_vdb.h"
#include "tools/vdb_writer.h"
#include "volume/vdb_format.h"

namespace mirage {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

}  // namespace

// ---- Writing -----------------------------------------------------------------------------

void initOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

uint32_t vdbCompressionFlags(const std::string& name, const std::string& path) {
    if (name == "blosc")
        // Without Blosc, zip: but OpenVDB never zips fog volumes (Archive::setGridCompression),
        // so those are then stored with the active-mask encoding only.
        return (openvdb::io::Archive::hasBloscCompression() ? openvdb::io::COMPRESS_BLOSC
                                                            : openvdb::io::COMPRESS_ZIP) |
               openvdb::io::COMPRESS_ACTIVE_MASK;
    if (name == "zip") return openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK;
    if (name == "none") return openvdb::io::COMPRESS_NONE;
    fail(path, "unknown compression '" + name + "' (valid: blosc, zip, none)");
}

void writeVdbFile(const std::string& path, const openvdb::GridPtrVec& grids,
                  const openvdb::MetaMap& meta, const std::string& compressionName) {
    const uint32_t compression = vdbCompressionFlags(compressionName, path);
    namespace fs = std::filesystem;
    const fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path() && !fs::is_directory(target.parent_path(), ec))
        fail(path, "cannot write: folder " + target.parent_path().string() + " does not exist");
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            try {
                openvdb::io::File file(tmp);
                file.setCompression(compression);
                file.write(grids, meta);
                file.close();
                vdbformat::scanFile(tmp);
            } catch (const std::exception& e) {
                fail(path, "cannot write: " + boundedMessage(e.what()));
            }
        },
        "cannot write");
}

openvdb::math::Transform::Ptr linearVdbTransform(double voxelSize, const Vec3d& origin) {
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
    return xform;
}

namespace {

constexpr size_t kMaxAssetGrids = 8;  // values one voxel of a field holds, at most

// The voxels of an asset: n[a] along each axis, voxel centres at first + index · h.
struct VoxelDomain {
    int n[3];
    Vec3 first;
    float h;
    int blocks(int a) const { return (n[a] + 7) / 8; }
    uint64_t blockCount() const { return uint64_t(blocks(0)) * blocks(1) * blocks(2); }
    openvdb::Coord blockOrigin(uint64_t b) const {
        const uint64_t bx = uint64_t(blocks(0)), by = uint64_t(blocks(1));
        return openvdb::Coord(int(b % bx) * 8, int(b / bx % by) * 8, int(b / (bx * by)) * 8);
    }
    Vec3 centre(const openvdb::Coord& c) const {
        return first + Vec3(float(c.x()), float(c.y()), float(c.z())) * h;
    }
};

// Fills `trees` block by block: the domain's 8³ blocks are evaluated in parallel, each into
// leaf nodes of its own (`eval(ijk, values, active)` gives every tree's value and state at one
// voxel), then added to the trees in block order. A voxel's value depends on its position
// only, so the trees are the same for any thread count. `skip(origin)` answers whether a block
// is empty without evaluating it. Blocks are taken in batches so that at most one batch of
// leaves waits outside the trees.
template <typename TreeT, typename Eval, typename Skip>
void fillTrees(const VoxelDomain& d, const std::vector<TreeT*>& trees, const Eval& eval,
               const Skip& skip, Progress* progress) {
    using Leaf = typename TreeT::LeafNodeType;
    using Value = typename TreeT::ValueType;
    const size_t numTrees = trees.size();
    constexpr uint64_t kBatch = 16384;
    std::vector<Leaf*> leaves;
    for (uint64_t b0 = 0; b0 < d.blockCount(); b0 += kBatch) {
        const uint64_t b1 = std::min(d.blockCount(), b0 + kBatch);
        leaves.assign((b1 - b0) * numTrees, nullptr);
        tbb::parallel_for(tbb::blocked_range<uint64_t>(b0, b1, 16), [&](const auto& r) {
            std::vector<Value> values(numTrees);
            std::unique_ptr<bool[]> active(new bool[numTrees]);
            for (uint64_t b = r.begin(); b != r.end(); ++b) {
                const openvdb::Coord origin = d.blockOrigin(b);
                if (skip(origin)) continue;
                Leaf** out = &leaves[(b - b0) * numTrees];
                for (int k = origin.z(); k < std::min(origin.z() + 8, d.n[2]); ++k)
                    for (int j = origin.y(); j < std::min(origin.y() + 8, d.n[1]); ++j)
                        for (int i = origin.x(); i < std::min(origin.x() + 8, d.n[0]); ++i) {
                            const openvdb::Coord ijk(i, j, k);
                            eval(ijk, values.data(), active.get());
                            for (size_t t = 0; t < numTrees; ++t) {
                                if (!active[t]) continue;
                                if (!out[t]) out[t] = new Leaf(origin, openvdb::zeroVal<Value>());
                                out[t]->setValueOn(ijk, values[t]);
                            }
                        }
            }
            if (progress) progress->advance(r.size());
        });
        for (size_t i = 0; i < leaves.size(); ++i)
            if (leaves[i]) trees[i % numTrees]->addLeaf(leaves[i]);
    }
}

// Whether the field can be non-zero anywhere in the block of `size` voxels of size `h` at
// `origin` (voxel centres from d.centre(origin)).
bool blockMayCover(const AssetField& field, const VoxelDomain& d, const openvdb::Coord& origin,
                   int size, float h) {
    if (!field.mayCover) return true;
    const Vec3 lo = d.centre(origin) - Vec3(0.5f * h);
    return field.mayCover(lo, lo + Vec3(float(size) * h));
}

openvdb::FloatGrid::Ptr emptyFogGrid(const std::string& name, const std::string& units,
                                     const openvdb::math::Transform& xform, bool half) {
    auto grid = openvdb::FloatGrid::create(0.f);
    grid->setName(name);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(xform.copy());
    grid->insertMeta("units", openvdb::StringMetadata(units));
    if (half) grid->setSaveFloatAsHalf(true);
    return grid;
}

// The scalar grids of the field over the domain.
std::vector<openvdb::FloatGrid::Ptr> scalarGrids(const AssetField& field, const VoxelDomain& d,
                                                 const openvdb::math::Transform& xform,
                                                 Progress* progress) {
    const size_t numGrids = field.grids.size();
    std::vector<openvdb::FloatGrid::Ptr> grids;
    std::vector<openvdb::FloatTree*> trees;
    for (size_t g = 0; g < numGrids; ++g) {
        grids.push_back(emptyFogGrid(field.grids[g], field.units[g], xform, field.half));
        trees.push_back(&grids.back()->tree());
    }
    fillTrees(
        d, trees,
        [&](const openvdb::Coord& ijk, float* v, bool* active) {
            field.eval(d.centre(ijk), v);
            for (size_t g = 0; g < numGrids; ++g) active[g] = v[g] > 0.f;
        },
        [&](const openvdb::Coord& o) { return !blockMayCover(field, d, o, 8, d.h); }, progress);
    return grids;
}

// The flow as the vec3s grid `vel`. At velocityScale 1, over the density's voxels (a copy of
// its topology, leaf by leaf in parallel: the flow needs no noise); at 2, over the voxels of
// twice the size whose centre has a non-zero first grid, evaluated like the scalar grids.
openvdb::Vec3SGrid::Ptr velocityGrid(const AssetField& field, const VoxelDomain& d,
                                     const openvdb::FloatTree& density, Progress* progress) {
    auto vel = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    vel->setName("vel");
    vel->setGridClass(openvdb::GRID_UNKNOWN);
    vel->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    vel->insertMeta("units", openvdb::StringMetadata("m/s"));
    if (field.half) vel->setSaveFloatAsHalf(true);
    const int s = field.velocityScale;
    // Voxel (I, J, K) of `vel` covers the voxels s·I … s·I + s − 1 of the others: its centre
    // is half a voxel of theirs from the first one's at s = 2.
    const VoxelDomain coarse{{(d.n[0] + s - 1) / s, (d.n[1] + s - 1) / s, (d.n[2] + s - 1) / s},
                             d.first + Vec3(0.5f * float(s - 1) * d.h),
                             d.h * float(s)};
    vel->setTransform(linearVdbTransform(coarse.h, Vec3d(coarse.first)));
    auto flow = [&](const openvdb::Coord& ijk) {
        const Vec3 u = field.velocity(coarse.centre(ijk));
        return openvdb::Vec3s(u.x, u.y, u.z);
    };
    std::vector<openvdb::Vec3STree*> trees{&vel->tree()};
    if (s == 1) {
        std::vector<const openvdb::FloatTree::LeafNodeType*> leaves;
        density.getNodes(leaves);
        std::vector<openvdb::Vec3STree::LeafNodeType*> out(leaves.size());
        tbb::parallel_for(size_t(0), leaves.size(), [&](size_t i) {
            out[i] = new openvdb::Vec3STree::LeafNodeType(leaves[i]->origin(), openvdb::Vec3s(0.f));
            for (auto it = leaves[i]->cbeginValueOn(); it; ++it)
                out[i]->setValueOn(it.pos(), flow(it.getCoord()));
        });
        for (auto* leaf : out) vel->tree().addLeaf(leaf);
        return vel;
    }
    fillTrees(
        coarse, trees,
        [&](const openvdb::Coord& ijk, openvdb::Vec3s* v, bool* active) {
            float values[kMaxAssetGrids];
            field.eval(coarse.centre(ijk), values);
            active[0] = values[0] > 0.f;
            if (active[0]) v[0] = flow(ijk);
        },
        [&](const openvdb::Coord& o) { return !blockMayCover(field, coarse, o, 8, coarse.h); },
        progress);
    return vel;
}

VoxelDomain assetDomain(const AssetField& field, int resolution) {
    // Voxel centres at lo + (i + ½) h: the voxels tile the domain exactly along y.
    VoxelDomain d;
    d.h = 2.f / float(resolution);
    for (int a = 0; a < 3; ++a)
        d.n[a] = std::max(1, int(std::lround((field.hi[a] - field.lo[a]) / d.h)));
    d.first = field.lo + Vec3(0.5f * d.h);
    return d;
}

uint64_t progressBlocks(const AssetField& field, const VoxelDomain& d) {
    uint64_t blocks = d.blockCount();
    const int s = field.velocityScale;
    if (field.velocity && s > 1)
        blocks += uint64_t((d.blocks(0) + s - 1) / s) * ((d.blocks(1) + s - 1) / s) *
                  ((d.blocks(2) + s - 1) / s);
    return blocks;
}

}  // namespace

int assetResolutionForVoxels(const std::string& kind, uint64_t seed, double voxels) {
    // The fields are defined in metres, so their active voxel count grows as resolution³: one
    // count at a small resolution fixes the constant.
    constexpr int kPilot = 96;
    const AssetField field = proceduralField(kind, seed);
    initOpenVdb();
    const VoxelDomain d = assetDomain(field, kPilot);
    const auto grids = scalarGrids(field, d, *linearVdbTransform(d.h, Vec3d(d.first)), nullptr);
    const double count = double(grids[0]->activeVoxelCount());
    if (!(voxels > 0.0) || count <= 0.0)
        throw MirageError("asset '" + kind + "': cannot aim at " + std::to_string(voxels) +
                          " active voxels");
    const double r = double(kPilot) * std::cbrt(voxels / count);
    return int(
        std::lround(std::clamp(r, double(kMinAssetResolution), double(kMaxAssetResolution))));
}

void writeProceduralAsset(const std::string& kind, const std::string& path, int resolution,
                          uint64_t seed, bool report) {
    const AssetField field = proceduralField(kind, seed);
    if (resolution < kMinAssetResolution || resolution > kMaxAssetResolution)
        throw MirageError("asset resolution " + std::to_string(resolution) + " is out of range (" +
                          std::to_string(kMinAssetResolution) + " to " +
                          std::to_string(kMaxAssetResolution) + " voxels along the 2 m height)");
    initOpenVdb();
    const VoxelDomain d = assetDomain(field, resolution);
    auto xform = linearVdbTransform(d.h, Vec3d(d.first));
    std::optional<Progress> progress;
    if (report) progress.emplace("make-asset " + kind, progressBlocks(field, d), "blocks");
    Progress* p = progress ? &*progress : nullptr;
    std::vector<openvdb::FloatGrid::Ptr> grids = scalarGrids(field, d, *xform, p);
    openvdb::Vec3SGrid::Ptr vel;
    if (field.velocity) vel = velocityGrid(field, d, grids[0]->tree(), p);
    if (progress) progress->finish();

    // Blocks whose voxels are all equal (the fog sphere's core) become single tiles.
    for (auto& g : grids) openvdb::tools::prune(g->tree());

    openvdb::MetaMap meta;
    meta.insertMeta("creator", openvdb::StringMetadata("Mirage " MIRAGE_VERSION " make-asset"));
    meta.insertMeta("mirage_asset_kind", openvdb::StringMetadata(kind));
    meta.insertMeta("mirage_asset_seed", openvdb::StringMetadata(std::to_string(seed)));
    meta.insertMeta("mirage_asset_resolution", openvdb::Int32Metadata(resolution));
    openvdb::GridPtrVec out(grids.begin(), grids.end());
    if (vel) out.push_back(vel);
    if (report) {
        uint64_t voxels = 0;
        for (const auto& g : out) voxels += g->activeVoxelCount();
        std::fprintf(stderr, "make-asset: writing %zu grids, %llu active voxels\n", out.size(),
                     (unsigned long long)voxels);
    }
    writeVdbFile(path, out, meta, "blosc");
}

// ---- Dense arrays (dense_vdb.h) ------------------------------------------------------------

namespace {

std::string numberText(double v) {
    std::ostringstream text;
    text << v;
    return text.str();
}

// The grid's shape and values, checked before OpenVDB sees them: the message names the grid.
void checkDenseGrid(const DenseGrid& g, const std::string& path) {
    const std::string what = "grid '" + g.name + "'";
    if (g.name.empty()) fail(path, "a dense grid has no name");
    if (!(g.voxelSize > 0.0) || !std::isfinite(g.voxelSize))
        fail(path, what + ": voxel size " + numberText(g.voxelSize) +
                       " is not a positive finite number of metres");
    if (g.components != 1 && g.components != 3)
        fail(path, what + ": " + std::to_string(g.components) +
                       " values per voxel; a grid holds 1 (a scalar) or 3 (a vector)");
    for (int a = 0; a < 3; ++a)
        if (g.dims[size_t(a)] < 1 ||
            int64_t(g.offset[size_t(a)]) + g.dims[size_t(a)] - 1 > int64_t(INT32_MAX))
            fail(path, what + ": its voxels along axis " + std::to_string(a) + " (" +
                           std::to_string(g.dims[size_t(a)]) + " from index " +
                           std::to_string(g.offset[size_t(a)]) +
                           ") are empty or leave OpenVDB's 32-bit index range");
    const int64_t n = g.dims[0] * g.dims[1] * g.dims[2] * g.components;
    for (int64_t i = 0; i < n; ++i)
        if (!std::isfinite(g.values[i])) {
            const int64_t voxel = i / g.components, z = voxel % g.dims[2],
                          y = voxel / g.dims[2] % g.dims[1], x = voxel / g.dims[2] / g.dims[1];
            fail(path, what + ": value " + numberText(double(g.values[i])) + " at [" +
                           std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
                           "] of the array is not finite");
        }
}

// The OpenVDB grid of one dense array: Dense's default layout (LayoutZYX) is z fastest, the
// array's C order; copyFromDense activates only the voxels that differ from the background 0.
template <typename GridT>
typename GridT::Ptr gridFromDense(const DenseGrid& g) {
    using Value = typename GridT::ValueType;
    const openvdb::Coord lo(g.offset[0], g.offset[1], g.offset[2]);
    const openvdb::Coord hi =
        lo + openvdb::Coord(int32_t(g.dims[0] - 1), int32_t(g.dims[1] - 1), int32_t(g.dims[2] - 1));
    // Dense reads through a non-const pointer but copyFromDense only reads.
    openvdb::tools::Dense<Value> dense(openvdb::CoordBBox(lo, hi),
                                       reinterpret_cast<Value*>(const_cast<float*>(g.values)));
    auto grid = GridT::create(openvdb::zeroVal<Value>());
    openvdb::tools::copyFromDense(dense, *grid, openvdb::zeroVal<Value>());
    grid->setName(g.name);
    grid->setTransform(linearVdbTransform(g.voxelSize, g.origin));
    if (g.components == 1)
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    else
        grid->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    return grid;
}

}  // namespace

void writeDenseVdbFile(const std::string& path, const std::vector<DenseGrid>& grids) {
    initOpenVdb();
    openvdb::GridPtrVec out;
    for (const DenseGrid& g : grids) {
        checkDenseGrid(g, path);
        if (g.components == 1)
            out.push_back(gridFromDense<openvdb::FloatGrid>(g));
        else
            out.push_back(gridFromDense<openvdb::Vec3SGrid>(g));
    }
    writeVdbFile(path, out, openvdb::MetaMap(), "blosc");
}

}  // namespace mirage
