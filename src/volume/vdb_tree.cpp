#include "volume/vdb_tree.h"

#include <array>
#include <cstring>
#include <fstream>
#include <vector>

#include "volume/load_progress.h"
#include "volume/vdb_reader.h"

namespace mirage::vdbformat {

namespace {

std::string num(uint64_t v) { return std::to_string(v); }

enum class LeafKind { Values, Bool, Mask };

struct TreeLayout {
    uint32_t valueBytes = 0;  // sizeof(ValueType)
    uint32_t halfBytes = 0;   // its half-float form (grids saved as half); 0: not a real type
    LeafKind leaf = LeafKind::Values;
};

// The registered 5-4-3 trees of OpenVDB 10 (openvdb::initialize()), by tree type name.
bool layoutOf(const std::string& treeType, TreeLayout* out) {
    static const struct {
        const char* value;
        TreeLayout layout;
    } kTrees[] = {{"float", {4, 2, LeafKind::Values}},  {"double", {8, 2, LeafKind::Values}},
                  {"int32", {4, 0, LeafKind::Values}},  {"int64", {8, 0, LeafKind::Values}},
                  {"vec3s", {12, 6, LeafKind::Values}}, {"vec3d", {24, 6, LeafKind::Values}},
                  {"vec3i", {12, 0, LeafKind::Values}}, {"bool", {1, 0, LeafKind::Bool}},
                  {"mask", {1, 0, LeafKind::Mask}}};
    for (const auto& t : kTrees)
        if (treeType == std::string("Tree_") + t.value + "_5_4_3") {
            *out = t.layout;
            return true;
        }
    return false;
}

// The grid whose tree `index` uses: itself, or its instance parent (-1 if there is none).
int treeOwner(const FileLayout& layout, int index) {
    const GridRecord& g = layout.grids[size_t(index)];
    if (g.instanceParent.empty()) return index;
    for (size_t i = 0; i < layout.grids.size(); ++i)
        if (layout.grids[i].uniqueName == g.instanceParent &&
            layout.grids[i].instanceParent.empty())
            return int(i);
    return -1;
}

constexpr uint32_t kLeafValues = 512;  // 8³
constexpr uint64_t kLeafMaskBytes = kLeafValues / 8;
constexpr uint64_t kCoordBytes = 12;  // int32 × 3

// What the data pass needs of a leaf seen in the topology: its active count and a hash of its
// mask (maskHash), to check that the data repeat the same mask.
struct LeafRecord {
    uint64_t hash;
    uint32_t active;
};

template <typename Words>
uint32_t popcount(const Words& words) {
    uint32_t n = 0;
    for (uint64_t w : words) n += uint32_t(__builtin_popcountll(w));
    return n;
}

// FNV-1a's step on whole 64-bit words rather than bytes: a leaf's 8 words in 8 dependent
// multiplications instead of 64 (the walk hashes two million masks twice at 10⁹ voxels). Each
// step is a bijection of the hash, so a mask that differs in one word always changes it.
template <typename Words>
uint64_t maskHash(const Words& words) {
    uint64_t h = 1469598103934665603ull;
    for (uint64_t w : words) h = (h ^ w) * 1099511628211ull;
    return h ^ (h >> 29);
}

class TreeWalker {
public:
    TreeWalker(Reader& r, const GridRecord& g, const TreeLayout& t, const std::string& label,
               Progress* progress = nullptr, LeafDataIndex* index = nullptr)
        : mR(r), mGrid(g), mTree(t), mLabel(label), mProgress(progress), mIndex(index) {}

    // The topology alone: the node counts, without the leaves' values.
    TreeCounts topology() {
        mR.seek(mGrid.topologyPos);
        skip(4, "buffer count");
        root();
        mCounts.leaves = mLeaves.size();
        return mCounts;
    }

    void walk() {
        topology();
        if (mR.pos() != mGrid.blockPos)
            corrupt("its topology ends at byte " + num(mR.pos()) +
                    " but the file's index puts its data at byte " + num(mGrid.blockPos));
        buffers();
        if (mR.pos() != mGrid.endPos)
            corrupt("its data end at byte " + num(mR.pos()) +
                    " but the file's index puts its end at byte " + num(mGrid.endPos));
    }

private:
    [[noreturn]] void corrupt(const std::string& why) const {
        mR.fail("corrupt: grid " + mLabel + ": " + why);
    }
    // Every read stays within the grid's bytes [.., endPos), not merely the file's.
    void need(uint64_t n, const char* what) const {
        const uint64_t pos = mR.pos();
        if (pos > mGrid.endPos || n > mGrid.endPos - pos)
            corrupt(std::string(what) + " at byte " + num(pos) + " needs " + num(n) +
                    " bytes but the grid ends at byte " + num(mGrid.endPos));
    }
    void skip(uint64_t n, const char* what) {
        need(n, what);
        mR.skip(n, what);
    }
    template <typename T>
    T pod(const char* what) {
        need(sizeof(T), what);
        return mR.pod<T>(what);
    }
    std::vector<uint64_t> mask(uint64_t bits, const char* what) {
        std::vector<uint64_t> words(size_t(bits / 64));
        need(bits / 8, what);
        mR.read(words.data(), bits / 8, what);
        return words;
    }

    void root() {
        if (mIndex) {
            mIndex->background = pod<float>("root background value");
            mIndex->savedAsHalf = mGrid.savedAsHalf;
            mIndex->compression = mGrid.compression;
        } else {
            skip(mTree.valueBytes, "root background value");
        }
        const uint32_t tiles = pod<uint32_t>("root tile count");
        const uint32_t children = pod<uint32_t>("root child count");
        mCounts.rootEntries = uint64_t(tiles) + children;
        // One multiplication bounds the tile loop OpenVDB runs (2^32 × 37 bytes cannot wrap).
        skip(uint64_t(tiles) * (kCoordBytes + mTree.valueBytes + 1), "root tiles");
        std::array<int32_t, 3> previous{};
        for (uint32_t n = 0; n < children; ++n) {
            std::array<int32_t, 3> origin{};
            need(kCoordBytes, "root child origin");
            mR.read(origin.data(), kCoordBytes, "root child origin");
            // OpenVDB files its root children by origin in a std::map and reads their data in
            // that order; a file listing them otherwise (or twice) would have its data read
            // for the wrong nodes.
            if (n > 0 && !(previous < origin))
                corrupt("root child " + num(n) + " at byte " + num(mR.pos() - kCoordBytes) +
                        " is out of order (origins must ascend)");
            previous = origin;
            internal(5);
        }
    }

    // An internal node of 2^(3·log2Dim) entries; its children are internal(4) or leaves.
    void internal(int log2Dim) {
        const uint64_t entries = uint64_t(1) << (3 * log2Dim);
        const std::vector<uint64_t> childMask = mask(entries, "internal node child mask");
        const std::vector<uint64_t> valueMask = mask(entries, "internal node value mask");
        values(entries, popcount(valueMask), "internal node values");
        ++(log2Dim == 5 ? mCounts.upper : mCounts.lower);
        for (size_t w = 0; w < childMask.size(); ++w)
            for (uint64_t bits = childMask[w]; bits != 0; bits &= bits - 1) {
                if (log2Dim == 5)
                    internal(4);
                else
                    leafTopology();
            }
    }

    // A leaf's mask, in place (a vector per leaf would be two million allocations).
    std::array<uint64_t, kLeafValues / 64> leafMask(const char* what) {
        std::array<uint64_t, kLeafValues / 64> words;
        need(kLeafMaskBytes, what);
        mR.read(words.data(), kLeafMaskBytes, what);
        return words;
    }

    void leafTopology() {
        // A mask leaf's topology is its value bits; the others' is their active mask.
        const auto m = leafMask("leaf mask");
        mLeaves.push_back({maskHash(m), popcount(m)});
    }

    // The leaves' data, on a bar when `progress` is given (in MB of the file).
    void buffers() {
        const uint64_t start = mR.pos();
        uint64_t shown = 0;
        auto show = [&] {
            const uint64_t megabytes = (mR.pos() - start) / 1000000;
            if (mProgress) mProgress->advance(megabytes - shown);
            shown = megabytes;
        };
        for (size_t i = 0; i < mLeaves.size(); ++i) {
            if (i % 4096 == 0) show();
            switch (mTree.leaf) {
                case LeafKind::Bool:  // value mask, origin, value bits
                    skip(kLeafMaskBytes + kCoordBytes + kLeafMaskBytes, "bool leaf data");
                    break;
                case LeafKind::Mask:  // value bits, origin
                    skip(kLeafMaskBytes + kCoordBytes, "mask leaf data");
                    break;
                case LeafKind::Values: {
                    if (mIndex) mIndex->offsets.push_back(mR.pos());
                    const auto m = leafMask("leaf data mask");
                    if (maskHash(m) != mLeaves[i].hash || popcount(m) != mLeaves[i].active)
                        corrupt("leaf " + num(i) + "'s mask at byte " +
                                num(mR.pos() - kLeafMaskBytes) + " differs from its topology");
                    values(kLeafValues, mLeaves[i].active, "leaf values");
                    break;
                }
            }
        }
        show();
    }

    // io::readCompressedValues: `entries` values of which `active` are on in the node's mask.
    void values(uint64_t entries, uint32_t active, const char* what) {
        const int8_t flag = pod<int8_t>("mask-compression flag");
        // Flags 2, 4, 5 store one or two inactive values; 3, 4, 5 a selection mask; 6 (or a
        // grid without mask compression) all values, any other only the active ones.
        if (flag == 2 || flag == 4 || flag == 5)
            skip(uint64_t(mTree.valueBytes) * (flag == 5 ? 2 : 1), "inactive values");
        if (flag == 3 || flag == 4 || flag == 5) skip(entries / 8, "selection mask");
        const bool maskCompressed = (mGrid.compression & kCompressActiveMask) != 0;
        const uint64_t count = maskCompressed && flag != 6 ? active : entries;
        uint64_t elementBytes = mTree.valueBytes;
        if (mGrid.savedAsHalf && mTree.halfBytes != 0) {
            if (count == 0) return;  // io::HalfReader reads nothing for no values
            elementBytes = mTree.halfBytes;
        }
        const uint64_t bytes = elementBytes * count;
        if (mGrid.compression & kCompressBlosc)
            block(bytes, true, what);
        else if (mGrid.compression & kCompressZip)
            block(bytes, false, what);
        else
            skip(bytes, what);
    }

    // io::bloscFromStream / unzipFromStream: int64 size, then the block; a size ≤ 0 means
    // -size raw bytes, which must be exactly the node's (OpenVDB reads them into its buffer).
    void block(uint64_t rawBytes, bool blosc, const char* what) {
        const int64_t stored = pod<int64_t>("compressed block size");
        const uint64_t start = mR.pos() - 8;
        if (stored <= 0) {
            const uint64_t bytes = uint64_t(0) - uint64_t(stored);
            if (bytes != rawBytes)
                corrupt(std::string(what) + ": an uncompressed block at byte " + num(start) +
                        " holds " + num(bytes) + " bytes, expected " + num(rawBytes));
            skip(bytes, what);
            return;
        }
        const uint64_t bytes = uint64_t(stored);
        need(bytes, what);
        if (blosc) {
            // A Blosc frame's header (blosc.h): uint32 uncompressed size at byte 4, uint32
            // frame size at byte 12. Blosc trusts it, so it must agree with the block.
            unsigned char header[16];
            if (bytes < sizeof(header))
                corrupt(std::string(what) + ": a Blosc block at byte " + num(start) + " of " +
                        num(bytes) + " bytes is shorter than its header");
            mR.read(header, sizeof(header), what);
            uint32_t nbytes, cbytes;
            std::memcpy(&nbytes, header + 4, 4);
            std::memcpy(&cbytes, header + 12, 4);
            if (nbytes != rawBytes || cbytes != bytes)
                corrupt(std::string(what) + ": the Blosc block at byte " + num(start) + " claims " +
                        num(cbytes) + " of " + num(bytes) + " bytes, holding " + num(nbytes) +
                        " of the " + num(rawBytes) + " expected");
            skip(bytes - sizeof(header), what);
        } else {
            skip(bytes, what);
        }
    }

    Reader& mR;
    const GridRecord& mGrid;
    const TreeLayout mTree;
    const std::string mLabel;
    std::vector<LeafRecord> mLeaves;
    TreeCounts mCounts;
    Progress* mProgress;
    LeafDataIndex* mIndex;  // null, or filled for a float tree
};

}  // namespace

bool treeIsWalkable(const FileLayout& layout, int index) {
    if (layout.format != Format::OpenVdb) return false;
    const int owner = treeOwner(layout, index);
    if (owner < 0) return false;
    const GridRecord& g = layout.grids[size_t(owner)];
    TreeLayout t;
    return g.topologyPos != 0 && layoutOf(g.type, &t);
}

void checkOpenVdbTree(const std::string& path, const FileLayout& layout, int index,
                      LeafDataIndex* leaves) {
    const std::string label = gridLabel(layout, index);
    auto fail = [&](const std::string& msg) { throw MirageError(FileLoc{path}, msg); };
    if (layout.format != Format::OpenVdb) fail("not an OpenVDB file");
    const int owner = treeOwner(layout, index);
    if (owner < 0)
        fail("grid " + label +
             " is an instance of a grid the file does not hold (or of "
             "another instance)");
    const GridRecord& g = layout.grids[size_t(owner)];
    if (layout.fileVersion < 222)
        fail("grid " + label + ": OpenVDB file format version " + num(layout.fileVersion) +
             " predates 222 (OpenVDB 3.0, 2014); Mirage checks a tree's layout before "
             "reading it and knows it from 222 on: re-save the file with a current OpenVDB "
             "(vdb_tool -read in.vdb -write out.vdb)");
    TreeLayout tree;
    if (!layoutOf(g.type, &tree) || g.topologyPos == 0)
        fail("grid " + label + " has tree type '" + boundedMessage(g.type, 60) +
             "', which Mirage does not read (expected a 5-4-3 tree of scalar, vector, bool or "
             "mask values)");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(std::string("cannot be opened: ") + std::strerror(errno));
    Reader r(path, in, layout.fileSize);
    LoadStage progress("checking", path, gridLabel(layout, index), g.endPos - g.gridPos,
                       (g.endPos - g.blockPos) / 1000000, "MB");
    const bool floats = g.type == "Tree_float_5_4_3";
    if (leaves) *leaves = LeafDataIndex();
    TreeWalker(r, g, tree, gridLabel(layout, owner), &progress, floats ? leaves : nullptr).walk();
    progress.finish();
}

TreeCounts countOpenVdbTree(const std::string& path, const FileLayout& layout, int index) {
    const int owner = treeOwner(layout, index);
    TreeLayout tree;
    if (layout.format != Format::OpenVdb || owner < 0 || layout.fileVersion < 222 ||
        !layoutOf(layout.grids[size_t(owner)].type, &tree) ||
        layout.grids[size_t(owner)].topologyPos == 0)
        throw MirageError(FileLoc{path},
                          "grid " + gridLabel(layout, index) +
                              ": its tree cannot be walked (checkOpenVdbTree says why)");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw MirageError(FileLoc{path}, std::string("cannot be opened: ") + std::strerror(errno));
    Reader r(path, in, layout.fileSize);
    return TreeWalker(r, layout.grids[size_t(owner)], tree, gridLabel(layout, owner)).topology();
}

}  // namespace mirage::vdbformat
