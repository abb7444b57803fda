// An OpenVDB float grid → a NanoVDB grid at float, Fp16, Fp8 or Fp4, each leaf's values read
// from the file, encoded and freed in one step, so that a big cache never holds both trees'
// values at once (the OpenVDB tree of a 10⁹-voxel cache and its NanoVDB copy are ~4 GB each),
// and a quantised grid is never held as floats.
//
// A float buffer is byte for byte what NanoVDB 32.4's converter makes with
// nanovdb::openToNanoVDB(grid, StatsMode::All, ChecksumMode::Partial) followed by the voxel
// rule (sanitizeScalarVoxels, which redoes the statistics when it changes a value); a quantised
// one is what that float grid becomes through volume/grid_quantise.h (back to OpenVDB, then
// openToNanoVDB at Fp16, Fp8 or Fp4): the same breadth-first layout
// (nanovdb/util/OpenToNanoVDB.h: grid, tree, root and its tiles, upper, lower and leaf nodes in
// depth-first order), the same fields, NanoVDB's leaf encoding (volume/leaf_codec.h), and the
// node statistics of nanovdb/util/GridStats.h — each leaf's statistics by the same running mean
// and variance over its active voxels as decoded, in mask order, each node's merged from its
// active tiles then its children in order. Only the order of the work differs: the voxel rule
// is applied as the values are copied, and the leaves and their statistics are done a lower
// node at a time, lower nodes in parallel (NanoVDB's statistics pass is serial), which gives the
// same numbers since every node's merge order is kept.
//
// Includes OpenVDB: only vdb_file.cpp includes it.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridStats.h>
#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "volume/grid_precision.h"
#include "volume/leaf_codec.h"
#include "volume/mapped_file_pages.h"
#include "volume/openvdb_read.h"
#include "volume/voxel_rule.h"

namespace mirage {

namespace openvdbtonano {

using OpenTree = openvdb::FloatTree;
using OpenRoot = OpenTree::RootNodeType;
using OpenUpper = OpenRoot::ChildNodeType;
using OpenLower = OpenUpper::ChildNodeType;
using OpenLeaf = OpenLower::ChildNodeType;
using Stats = nanovdb::Stats<float>;

// What GridStats keeps of a node while it merges: the statistics of its active values and
// their index bbox (empty until a value is added).
struct NodeStats {
    Stats stats;
    nanovdb::CoordBBox bbox;
    void add(const NodeStats& other) {
        stats.add(other.stats);
        bbox[0].minComponent(other.bbox[0]);
        bbox[1].maxComponent(other.bbox[1]);
    }
    // An active tile of a node whose children are `ChildT`, at `origin`.
    template <typename ChildT>
    void addTile(const nanovdb::Coord& origin, float value) {
        stats.add(value, ChildT::NUM_VALUES);
        bbox[0].minComponent(origin);
        bbox[1].maxComponent(origin + nanovdb::Coord(int32_t(ChildT::DIM) - 1));
    }
};

// nanovdb::Stats<float>::add(float) on one value after another: the same operations, so the
// same bits, kept as a Stats for the nodes' merges.
class RunningStats : public Stats {
public:
    void add(float v) {
        if (v < mMin) mMin = v;
        if (v > mMax) mMax = v;
        mSize += 1;
        const double delta = double(v) - mAvg;
        mAvg += delta / double(mSize);
        mAux += delta * (double(v) - mAvg);
    }
};

template <typename Data, typename = void>
struct IsQuantised : std::false_type {};
template <typename Data>
struct IsQuantised<Data, std::void_t<decltype(Data::mQuantum)>> : std::true_type {};

// A quantised leaf's statistics are codes relative to its range: on a leaf of one value the
// quantum is 0 and NanoVDB's setters would convert 0/0 to an integer (undefined behaviour). Its
// four codes are 0 then, the bytes x86 gives that conversion, so the grid stays NanoVDB's own.
template <typename Data>
void setStats(Data* data, const Stats& s) {
    if constexpr (IsQuantised<Data>::value) {
        if (data->mQuantum == 0.0f) {
            data->mMin = data->mMax = data->mAvg = data->mDev = 0;
            return;
        }
    }
    data->setMin(s.min());
    data->setMax(s.max());
    data->setAvg(s.avg());
    data->setDev(s.std());
}

// An internal node's bbox, flags and statistics from its merged total (GridStats: fog
// volumes have no level-set band, so the "skip this node" bit is always cleared).
template <typename Data>
void finishInternal(Data* data, const NodeStats& total) {
    data->mBBox = total.bbox;
    if (total.bbox.empty()) {
        data->mFlags |= uint64_t(1);
        data->mFlags &= ~uint64_t(2);
    } else {
        data->mFlags |= uint64_t(2);
        setStats(data, total.stats);
        data->mFlags &= ~uint64_t(1);
    }
}

// The bytes of a NanoVDB grid at BuildT (float, Fp16, Fp8, Fp4) whose root has `rootEntries`
// tiles and children, over `upper`, `lower` and `leaves` nodes: where each level starts, and its
// end.
template <typename BuildT = float>
struct NanoOffsets {
    uint64_t tree = 0, root = 0, upper = 0, lower = 0, leaf = 0, end = 0;
    NanoOffsets(uint64_t rootEntries, uint64_t uppers, uint64_t lowers, uint64_t leaves) {
        tree = nanovdb::NanoGrid<BuildT>::memUsage();
        root = tree + nanovdb::NanoTree<BuildT>::memUsage();
        upper = root + nanovdb::NanoRoot<BuildT>::memUsage(uint32_t(rootEntries));
        lower = upper + nanovdb::NanoUpper<BuildT>::memUsage() * uppers;
        leaf = lower + nanovdb::NanoLower<BuildT>::memUsage() * lowers;
        end = leaf + sizeof(nanovdb::NanoLeaf<BuildT>) * leaves;
    }
};

// The OpenVDB nodes in the order of their NanoVDB copies at BuildT, and where each level starts.
template <typename BuildT>
struct Layout {
    std::vector<OpenUpper*> uppers;
    std::vector<OpenLower*> lowers;
    std::vector<OpenLeaf*> leaves;   // released leaves are deleted once copied: count only then
    std::vector<size_t> firstLeaf;   // of each lower node, then the leaf count
    std::vector<size_t> firstLower;  // of each upper node, then the lower count
    uint32_t rootTiles = 0;
    uint64_t grid = 0, tree = 0, root = 0, upper = 0, lower = 0, leaf = 0, end = 0;

    explicit Layout(OpenTree& openTree) {
        OpenRoot& openRoot = openTree.root();
        for (auto u = openRoot.beginChildOn(); u; ++u) {
            uppers.push_back(&*u);
            firstLower.push_back(lowers.size());
            for (auto l = u->beginChildOn(); l; ++l) {
                lowers.push_back(&*l);
                firstLeaf.push_back(leaves.size());
                for (auto f = l->beginChildOn(); f; ++f) leaves.push_back(&*f);
            }
        }
        firstLower.push_back(lowers.size());
        firstLeaf.push_back(leaves.size());
        rootTiles = uint32_t(openRoot.getTableSize());
        const NanoOffsets<BuildT> at(rootTiles, uppers.size(), lowers.size(), leaves.size());
        tree = at.tree;
        root = at.root;
        upper = at.upper;
        lower = at.lower;
        leaf = at.leaf;
        end = at.end;
    }
};

// Writes one NanoVDB tree at BuildT into a buffer laid out by Layout.
template <typename BuildT>
class Converter {
    using NanoGrid = nanovdb::NanoGrid<BuildT>;
    using NanoTree = nanovdb::NanoTree<BuildT>;
    using NanoRoot = nanovdb::NanoRoot<BuildT>;
    using NanoUpper = nanovdb::NanoUpper<BuildT>;
    using NanoLower = nanovdb::NanoLower<BuildT>;
    using NanoLeaf = nanovdb::NanoLeaf<BuildT>;
    using Codec = LeafCodec<BuildT>;

public:
    Converter(openvdb::FloatGrid& open, LeafReads<OpenLeaf>& reads, bool releaseLeaves)
        : mOpen(open), mLayout(open.tree()), mReads(reads), mRelease(releaseLeaves) {}

    uint64_t bytes() const { return mLayout.end; }

    // Fills `buffer` (bytes() long) and returns what the voxel rule changed.
    SanitizeCounts run(uint8_t* buffer) {
        mBuffer = buffer;
        std::vector<NodeStats> lowerStats(mLayout.lowers.size());
        std::vector<float> lowerMaxima(mLayout.lowers.size(), 0.f);
        std::atomic<uint64_t> zeroed{0}, clamped{0};
        tbb::parallel_for(tbb::blocked_range<size_t>(0, mLayout.lowers.size(), 1),
                          [&](const tbb::blocked_range<size_t>& r) {
                              SanitizeCounts count;
                              for (size_t i = r.begin(); i != r.end(); ++i)
                                  lowerStats[i] = lowerNode(i, count, &lowerMaxima[i]);
                              zeroed += count.zeroed;
                              clamped += count.clamped;
                          });
        mReads.finish();
        for (const float m : lowerMaxima) mLeafMaximum = std::max(mLeafMaximum, m);
        SanitizeCounts count;
        std::vector<NodeStats> upperStats(mLayout.uppers.size());
        for (size_t i = 0; i < mLayout.uppers.size(); ++i)
            upperStats[i] = upperNode(i, lowerStats, count);
        rootNode(upperStats, count);
        treeData();
        gridData();
        nanovdb::updateChecksum(*grid(), nanovdb::ChecksumMode::Partial);
        count.zeroed += zeroed;
        count.clamped += clamped;
        return count;
    }

    // After run(): the largest value the leaves store, inactive voxels too, under the voxel
    // rule and as decoded (0 without leaves): what FloatGrid's maximum would read them all
    // again for.
    float leafMaximum() const { return mLeafMaximum; }

private:
    template <typename T>
    T* at(uint64_t offset) const {
        return reinterpret_cast<T*>(mBuffer + offset);
    }
    NanoGrid* grid() const { return at<NanoGrid>(0); }
    NanoRoot* root() const { return at<NanoRoot>(mLayout.root); }
    NanoUpper* upper(size_t i) const { return at<NanoUpper>(mLayout.upper) + i; }
    NanoLower* lower(size_t i) const { return at<NanoLower>(mLayout.lower) + i; }
    NanoLeaf* leaf(size_t i) const { return at<NanoLeaf>(mLayout.leaf) + i; }

    // Leaf i, a child of `lowerOf`: its values read and encoded under the voxel rule (then,
    // when asked, the leaf deleted from the OpenVDB tree, a tile in its place), their decoded
    // maximum kept in *maximum. False when the leaf could not be read.
    bool fillLeaf(size_t i, OpenLower& lowerOf, SanitizeCounts& count, float* maximum) {
        OpenLeaf& open = *mLayout.leaves[i];
        auto* data = leaf(i)->data();
        data->mFlags = data->mBBoxDif[2] = data->mBBoxDif[1] = data->mBBoxDif[0] = 0u;
        Codec::clearStats(*data);
        data->setOrigin(open.origin());
        data->mValueMask = open.valueMask();
        float decoded[OpenLeaf::SIZE];
        const float* src = mReads.values(i, open, decoded);
        if (!src) return false;
        // Nearly every leaf keeps the rule already: a test of all its values at once, with
        // their range; the rule value by value, on a copy, only where one breaks it.
        uint32_t broken = 0;
        float lo = src[0], hi = src[0];
        for (uint32_t n = 0; n < OpenLeaf::SIZE; ++n) {
            broken |= uint32_t(!(src[n] >= 0.f && src[n] <= kMaxVoxelValue));
            lo = src[n] < lo ? src[n] : lo;
            hi = src[n] > hi ? src[n] : hi;
        }
        float fixed[OpenLeaf::SIZE];
        if (broken) {
            std::memcpy(fixed, src, sizeof(fixed));
            for (float& v : fixed) applyScalarVoxelRule(v, 1, count);
            lo = *std::min_element(fixed, fixed + OpenLeaf::SIZE);
            hi = *std::max_element(fixed, fixed + OpenLeaf::SIZE);
            src = fixed;
        }
        *maximum = std::max(*maximum, Codec::encode(*data, src, lo, hi));
        // The leaf goes as soon as it is copied, on this thread: freeing two million leaves
        // with the tree afterwards took half a second on one core.
        if (mRelease) delete lowerOf.template stealNode<OpenLeaf>(open.origin(), 0.f, false);
        return true;
    }

    // The active bbox and statistics of leaves [first, first + n), n ≤ kLeafGroup, filled.
    // Each leaf's mean and variance are a chain of dependent divisions over its active voxels
    // (RunningStats); the group's chains advance side by side so that the core overlaps them.
    static constexpr size_t kLeafGroup = 4;  // leafStats writes the four chains out
    void leafStats(size_t first, size_t n, NodeStats* out) {
        float active[kLeafGroup][OpenLeaf::SIZE];
        uint32_t count[kLeafGroup];
        uint32_t common = OpenLeaf::SIZE;
        for (size_t k = 0; k < n; ++k) {
            count[k] = Codec::activeValues(*leaf(first + k)->data(), active[k]);
            common = std::min(common, count[k]);
        }
        RunningStats running[kLeafGroup];
        if (n == kLeafGroup) {
            // Written out, so that the four means stay in registers.
            for (uint32_t v = 0; v < common; ++v) {
                running[0].add(active[0][v]);
                running[1].add(active[1][v]);
                running[2].add(active[2][v]);
                running[3].add(active[3][v]);
            }
        } else {
            common = 0;
        }
        for (size_t k = 0; k < n; ++k) {
            for (uint32_t v = common; v < count[k]; ++v) running[k].add(active[k][v]);
            out[k] = finishLeaf(first + k, running[k]);
        }
    }

    // GridStats on a leaf: its bbox of active voxels, its statistics and flags.
    NodeStats finishLeaf(size_t i, const RunningStats& running) {
        NodeStats local;
        auto* data = leaf(i)->data();
        if (running.size() == 0) {
            data->mFlags &= ~uint8_t(2);
            return local;
        }
        leaf(i)->updateBBox();
        local.bbox[0] = local.bbox[1] = data->mBBoxMin;
        local.bbox[1] += nanovdb::Coord(data->mBBoxDif[0], data->mBBoxDif[1], data->mBBoxDif[2]);
        local.stats = running;
        setStats(data, local.stats);
        data->mFlags &= ~uint8_t(1);
        return local;
    }

    // An internal node's masks and table: its children's offsets (`child(k)`: the k-th child in
    // mask order) and its tiles under the voxel rule (each covering `tileVoxels` voxels); then
    // its active tiles' statistics, to which the caller adds its children's.
    template <typename NanoNode, typename OpenNode, typename ChildAt>
    NodeStats internalNode(NanoNode* node, const OpenNode& open, ChildAt&& child,
                           uint64_t tileVoxels, SanitizeCounts& count) {
        auto* data = node->data();
        std::memset(static_cast<void*>(data), 0, NanoNode::memUsage());
        data->setOrigin(open.origin());
        data->mValueMask = open.getValueMask();
        data->mChildMask = open.getChildMask();
        float value = 0.f;
        size_t k = 0;
        for (auto it = open.cbeginChildAll(); it; ++it) {
            if (it.probeChild(value)) {
                data->setChild(it.pos(), child(k++));
            } else {
                applyScalarVoxelRule(value, tileVoxels, count);
                data->setValue(it.pos(), value);
            }
        }
        NodeStats total;
        for (auto it = data->mValueMask.beginOn(); it; ++it)
            total.template addTile<typename NanoNode::ChildNodeType>(node->offsetToGlobalCoord(*it),
                                                                     data->mTable[*it].value);
        return total;
    }

    // Lower node i with its leaves (one thread: the leaves' statistics merge in order); the
    // leaves' largest value in *maximum.
    NodeStats lowerNode(size_t i, SanitizeCounts& count, float* maximum) {
        const size_t first = mLayout.firstLeaf[i], last = mLayout.firstLeaf[i + 1];
        NodeStats total = internalNode(
            lower(i), *mLayout.lowers[i], [&](size_t k) { return leaf(first + k); },
            uint64_t(OpenLeaf::SIZE), count);
        for (size_t l = first; l < last; l += kLeafGroup) {
            const size_t n = std::min(kLeafGroup, last - l);
            bool filled = true;
            for (size_t k = 0; k < n; ++k)
                filled = fillLeaf(l + k, *mLayout.lowers[i], count, maximum) && filled;
            if (!filled) break;  // mReads reports it
            NodeStats leaves[kLeafGroup];
            leafStats(l, n, leaves);
            for (size_t k = 0; k < n; ++k) total.add(leaves[k]);
        }
        finishInternal(lower(i)->data(), total);
        mReads.advance(last - first);
        return total;
    }

    NodeStats upperNode(size_t i, const std::vector<NodeStats>& lowerStats, SanitizeCounts& count) {
        const size_t first = mLayout.firstLower[i], last = mLayout.firstLower[i + 1];
        NodeStats total = internalNode(
            upper(i), *mLayout.uppers[i], [&](size_t k) { return lower(first + k); },
            uint64_t(OpenLower::NUM_VOXELS), count);
        for (size_t l = first; l < last; ++l) total.add(lowerStats[l]);
        finishInternal(upper(i)->data(), total);
        return total;
    }

    void rootNode(const std::vector<NodeStats>& upperStats, SanitizeCounts& count) {
        const OpenRoot& open = mOpen.tree().root();
        auto* data = root()->data();
        std::memset(static_cast<void*>(data), 0, NanoRoot::memUsage(mLayout.rootTiles));
        data->mBackground = open.background();
        data->mMinimum = data->mMaximum = data->mBackground;
        data->mBBox = nanovdb::CoordBBox();
        if (mLayout.rootTiles == 0) return;
        float value = 0.f;
        size_t u = 0;
        NodeStats total;
        for (auto it = open.cbeginChildAll(); it; ++it) {
            auto* tile = data->tile(data->mTableSize++);
            const openvdb::Coord ijk = it.getCoord();
            if (it.probeChild(value)) {
                total.add(upperStats[u]);
                tile->setChild(ijk, upper(u++), data);
                continue;
            }
            applyScalarVoxelRule(value, uint64_t(OpenUpper::NUM_VOXELS), count);
            tile->setValue(ijk, it.isValueOn(), value);
            if (it.isValueOn())
                total.addTile<NanoUpper>(nanovdb::Coord(ijk[0], ijk[1], ijk[2]), value);
        }
        setStats(data, total.stats);
        data->mBBox = total.bbox;
    }

    void treeData() {
        auto* data = at<NanoTree>(mLayout.tree)->data();
        std::memset(static_cast<void*>(data), 0, NanoTree::memUsage());
        data->setRoot(root());
        data->setFirstNode(mLayout.uppers.empty() ? nullptr : upper(0));
        data->setFirstNode(mLayout.lowers.empty() ? nullptr : lower(0));
        data->setFirstNode(mLayout.leaves.empty() ? nullptr : leaf(0));
        data->mNodeCount[0] = uint32_t(mLayout.leaves.size());
        data->mNodeCount[1] = uint32_t(mLayout.lowers.size());
        data->mNodeCount[2] = uint32_t(mLayout.uppers.size());
        uint32_t tiles[3] = {0, 0, 0};
        for (const OpenLower* l : mLayout.lowers) tiles[0] += l->getValueMask().countOn();
        for (const OpenUpper* u : mLayout.uppers) tiles[1] += u->getValueMask().countOn();
        for (auto it = mOpen.tree().root().cbeginValueOn(); it; ++it) ++tiles[2];
        uint64_t voxels = 0;
        for (size_t i = 0; i < mLayout.leaves.size(); ++i)
            voxels += leaf(i)->data()->mValueMask.countOn();
        // NanoVDB counts a tile of a lower or upper node as its child's table size, not its
        // voxels (OpenToNanoVDB::processTree); kept, so that the grids match.
        voxels += tiles[0] * NanoLeaf::NUM_VALUES;
        voxels += tiles[1] * NanoLower::NUM_VALUES;
        voxels += tiles[2] * NanoUpper::NUM_VALUES;
        for (int a = 0; a < 3; ++a) data->mTileCount[a] = tiles[a];
        data->mVoxelCount = voxels;
    }

    void gridData() {
        auto* data = grid()->data();
        std::memset(static_cast<void*>(data), 0, NanoGrid::memUsage());
        data->mMagic = NANOVDB_MAGIC_NUMBER;
        data->mVersion = nanovdb::Version();
        data->mFlags = uint32_t(nanovdb::GridFlags::IsBreadthFirst);
        data->mGridCount = 1;
        data->mGridSize = mLayout.end;
        std::strncpy(data->mGridName, mOpen.getName().c_str(), nanovdb::GridData::MaxNameSize - 1);
        data->mGridClass = mOpen.getGridClass() == openvdb::GRID_FOG_VOLUME
                               ? nanovdb::GridClass::FogVolume
                               : nanovdb::GridClass::Unknown;
        data->mGridType = nanovdb::mapToGridType<BuildT>();
        const auto affine = mOpen.transform().baseMap()->getAffineMap();
        const openvdb::Vec3d voxel = affine->voxelSize();
        data->mVoxelSize = mOpen.hasUniformVoxels() ? nanovdb::Vec3d(voxel[0])
                                                    : nanovdb::Vec3d(voxel[0], voxel[1], voxel[2]);
        const openvdb::Mat4d mat = affine->getMat4();
        data->mMap.set(mat, mat.inverse(), 1.0);
        worldBBox(data);
    }

    // GridStats: the active index bbox's corners through the map ([min, max + 1]: the voxels'
    // extent), and the flags of what the nodes carry.
    void worldBBox(nanovdb::GridData* data) {
        const nanovdb::CoordBBox box = root()->bbox();
        data->mWorldBBox = nanovdb::BBox<nanovdb::Vec3R>();
        data->setBBoxOn(!box.empty());
        if (!box.empty()) {
            const nanovdb::Coord lo = box[0], hi = box[1] + nanovdb::Coord(1);
            const nanovdb::Map& map = data->mMap;
            auto& w = data->mWorldBBox;
            w[0] = w[1] = map.applyMap(nanovdb::Vec3d(lo[0], lo[1], lo[2]));
            w.expand(map.applyMap(nanovdb::Vec3d(lo[0], lo[1], hi[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(lo[0], hi[1], lo[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(hi[0], lo[1], lo[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(hi[0], hi[1], lo[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(hi[0], lo[1], hi[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(lo[0], hi[1], hi[2])));
            w.expand(map.applyMap(nanovdb::Vec3d(hi[0], hi[1], hi[2])));
        }
        data->setMinMaxOn(true);
        data->setAverageOn(true);
        data->setStdDeviationOn(true);
    }

    openvdb::FloatGrid& mOpen;
    Layout<BuildT> mLayout;
    uint8_t* mBuffer = nullptr;
    LeafReads<OpenLeaf>& mReads;
    bool mRelease;
    float mLeafMaximum = 0.f;
};

}  // namespace openvdbtonano

// Whether convertFloatGrid makes what NanoVDB's converter would: a fog volume (or a grid of no
// stated class) with an affine map and a name short enough for the grid's header (a longer
// one goes into blind data, which only NanoVDB's converter writes).
inline bool convertsDirectly(const openvdb::FloatGrid& grid) {
    const auto cls = grid.getGridClass();
    return (cls == openvdb::GRID_FOG_VOLUME || cls == openvdb::GRID_UNKNOWN) &&
           grid.transform().baseMap()->isLinear() &&
           grid.getName().size() < nanovdb::GridData::MaxNameSize;
}

namespace openvdbtonano {

template <typename BuildT>
nanovdb::GridHandle<nanovdb::HostBuffer> convert(openvdb::FloatGrid& grid,
                                                 LeafReads<OpenLeaf>& reads, bool releaseLeaves,
                                                 SanitizeCounts* sanitized, float* leafMaximum) {
    Converter<BuildT> converter(grid, reads, releaseLeaves);
    nanovdb::GridHandle<nanovdb::HostBuffer> handle(nanovdb::HostBuffer::create(converter.bytes()));
    adviseHugePages(handle.data(), handle.size());
    *sanitized = converter.run(handle.data());
    *leafMaximum = converter.leafMaximum();
    return handle;
}

}  // namespace openvdbtonano

// Whether convertFloatGrid encodes precision p itself: float and the fixed-width codecs. FpN
// picks each leaf's width against a tolerance relative to the grid's largest value, unknown
// until every leaf is read (volume/grid_quantise.h does it afterwards).
inline bool streamsPrecision(GridPrecision p) { return p != GridPrecision::FpN; }

// The NanoVDB grid of `grid` (convertsDirectly) at `precision` (streamsPrecision), under the
// voxel rule, whose changes are returned in *sanitized, and the largest value a lookup decodes
// from its leaves in *leafMaximum. Leaves still in the file (delayed loading) are read in
// parallel, on a bar when the grid's `fileBytes` in file `path` call for one; with
// `releaseLeaves`, each leaf's values are freed once encoded (the OpenVDB grid keeps its
// topology only). No float copy of a quantised grid is made: its leaves are encoded as they are
// read. Where the tree walk indexed the leaves' data (`leafIndex`, one offset per leaf), they
// are decoded from the file by vdb_leaf_values.h, else read by OpenVDB. Throws MirageError
// naming the file and `label` when a leaf cannot be read.
inline nanovdb::GridHandle<nanovdb::HostBuffer> convertFloatGrid(
    openvdb::FloatGrid& grid, GridPrecision precision, uint64_t fileBytes, const std::string& path,
    const std::string& label, bool releaseLeaves, SanitizeCounts* sanitized, float* leafMaximum,
    const vdbformat::LeafDataIndex* leafIndex = nullptr) {
    using namespace openvdbtonano;
    MIRAGE_CHECK(convertsDirectly(grid) && streamsPrecision(precision));
    std::optional<LeafValueReader> decoder;
    if (leafIndex && leafIndex->offsets.size() == grid.tree().leafCount())
        decoder.emplace(path, *leafIndex);
    LeafReads<OpenLeaf> reads(fileBytes, grid.tree().leafCount(), path, label,
                              decoder ? &*decoder : nullptr);
    switch (precision) {
        case GridPrecision::Half:
            return convert<nanovdb::Fp16>(grid, reads, releaseLeaves, sanitized, leafMaximum);
        case GridPrecision::Fp8:
            return convert<nanovdb::Fp8>(grid, reads, releaseLeaves, sanitized, leafMaximum);
        case GridPrecision::Fp4:
            return convert<nanovdb::Fp4>(grid, reads, releaseLeaves, sanitized, leafMaximum);
        default:
            return convert<float>(grid, reads, releaseLeaves, sanitized, leafMaximum);
    }
}

}  // namespace mirage
