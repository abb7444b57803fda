// The tree walk that runs before OpenVDB reads a grid (src/volume/vdb_tree.h): every tree
// OpenVDB writes passes it — each registered value type, zip / Blosc / no compression, half
// floats, every map type, instances, the reference caches — and each corruption that used to
// reach OpenVDB's reader (a loop over a failed stream, a terabyte allocation, a raw block larger
// than its node) is refused at the byte that is wrong, naming the grid.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "test_grids.h"
#include "test_support.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"
#include "volume/vdb_format.h"
#include "volume/vdb_reader.h"
#include "volume/vdb_tree.h"

namespace mirage {
namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

template <typename T>
void patch(std::string& bytes, uint64_t at, T value) {
    ASSERT_LE(at + sizeof(T), bytes.size());
    std::memcpy(&bytes[size_t(at)], &value, sizeof(T));
}

template <typename T>
T peek(const std::string& bytes, uint64_t at) {
    T v{};
    std::memcpy(&v, &bytes[size_t(at)], sizeof(T));
    return v;
}

// Checks every grid's tree of `path`.
void walkAll(const std::string& path) {
    const vdbformat::FileLayout layout = vdbformat::scanFile(path);
    for (size_t i = 0; i < layout.grids.size(); ++i) {
        EXPECT_TRUE(vdbformat::treeIsWalkable(layout, int(i))) << path << " #" << i;
        vdbformat::checkOpenVdbTree(path, layout, int(i));
    }
}

// Runs the walk on grid 0 and expects a MirageError naming the file and containing `needle`;
// loading the grid must give the same error (the walk runs before OpenVDB reads the tree).
void expectCorrupt(const std::string& path, const std::string& needle) {
    for (int pass = 0; pass < 2; ++pass) {
        try {
            if (pass == 0)
                vdbformat::checkOpenVdbTree(path, vdbformat::scanFile(path), 0);
            else
                loadFloatGrid(path, "#0");
            ADD_FAILURE() << "no error for " << path << (pass ? " (load)" : " (walk)");
        } catch (const MirageError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(path), std::string::npos) << msg;
            EXPECT_NE(msg.find(needle), std::string::npos) << "expected '" << needle << "': " << msg;
            EXPECT_LT(msg.size(), 400u) << msg;
        }
    }
}

// A grid with partly filled leaves (so mask compression stores only active values), a leaf tile
// (level 1), an internal tile (level 2) and two root children far apart.
TestGridSpec sampleSpec(const std::string& type) {
    TestGridSpec s;
    s.valueType = type;
    s.gridClass = "unknown";  // OpenVDB never zips fog volumes
    for (int i = 0; i < 60; ++i)
        s.voxels.push_back({i, (3 * i) % 11, (7 * i) % 13, 1.0 + i, Vec3d(i, -i, 2 * i)});
    s.voxels.push_back({5000, 7, 9, 3.0, Vec3d(1, 2, 3)});  // a second root child
    s.tiles = {{200, 0, 0, 1, 2.0}, {1024, 1024, 0, 2, 4.0}};
    return s;
}

TEST(VdbTree, EveryRegisteredTypeAndCompressionWalksAndLoads) {
    const std::string dir = test::tempDir();
    for (const char* type :
         {"float", "double", "int32", "int64", "vec3s", "vec3d", "vec3i", "bool", "mask"}) {
        const bool real = std::string(type) == "float" || std::string(type) == "double" ||
                          std::string(type) == "vec3s" || std::string(type) == "vec3d";
        for (const char* compression : {"blosc", "zip", "none"})
            for (bool half : {false, true}) {
                if (half && !real) continue;
                TestGridSpec spec = sampleSpec(type);
                spec.saveAsHalf = half;
                const std::string path = dir + "/" + type + "_" + compression +
                                         (half ? "_half" : "") + ".vdb";
                writeTestGrid(path, spec, compression);
                SCOPED_TRACE(path);
                EXPECT_NO_THROW(walkAll(path));
                const VdbFileInfo info = inspectVdbFile(path);
                // 61 voxels, 512 in the leaf tile, 128³ in the internal one.
                EXPECT_EQ(info.grids.at(0).activeVoxels, 61u + 512u + 128u * 128u * 128u);
                if (std::string(type) == "float" || std::string(type) == "double") {
                    FloatGrid g = loadFloatGrid(path, "#0");
                    EXPECT_EQ(g.activeVoxels(), 61u + 512u + 128u * 128u * 128u);
                    EXPECT_EQ(g.grid()->tree().getValue(nanovdb::Coord(5000, 7, 9)), 3.f);
                }
            }
    }
}

TEST(VdbTree, EveryMapTypeAndInstancesWalk) {
    const std::string dir = test::tempDir();
    for (const char* map : {"uniform", "scale", "affine", "frustum"}) {
        TestGridSpec spec = sampleSpec("float");
        spec.map = map;
        const std::string path = dir + "/" + map + ".vdb";
        writeTestGrid(path, spec);
        SCOPED_TRACE(path);
        EXPECT_NO_THROW(walkAll(path));
        if (std::string(map) == "frustum") {
            // The walk passes; then Mirage refuses the map itself, by name.
            try {
                loadFloatGrid(path, "#0");
                ADD_FAILURE() << "a frustum grid loaded";
            } catch (const MirageError& e) {
                EXPECT_NE(std::string(e.what()).find("NonlinearFrustumMap"), std::string::npos)
                    << e.what();
            }
        } else {
            EXPECT_EQ(loadFloatGrid(path, "#0").activeVoxels(), 61u + 512u + 128u * 128u * 128u);
        }
    }
    // Two grids sharing one tree: OpenVDB writes the second as an instance of the first.
    TestGridSpec a = sampleSpec("float"), b = a;
    a.name = "density";
    b.name = "copy";
    b.shareTreeWithPrevious = true;
    const std::string path = dir + "/instance.vdb";
    writeTestGrids(path, {a, b});
    const vdbformat::FileLayout layout = vdbformat::scanFile(path);
    ASSERT_EQ(layout.grids.size(), 2u);
    EXPECT_EQ(layout.grids[1].instanceParent, layout.grids[0].uniqueName);
    EXPECT_NO_THROW(walkAll(path));
    EXPECT_EQ(loadFloatGrid(path, "copy").activeVoxels(), loadFloatGrid(path, "density").activeVoxels());
}

TEST(VdbTree, ReferenceCachesWalk) {
    MIRAGE_REQUIRE_SHARED(smoke1, "vdb/smoke1.vdb");  // file version 222, half, mask compressed
    walkAll(smoke1);
    for (const char* name : {"vdb/density_and_heat.vdb", "vdb/smoke_seq.0002.vdb",
                             "vdb/smoke_seq.0003.vdb"}) {
        const std::string path = test::sharedFile(name);
        if (!path.empty()) {
            EXPECT_NO_THROW(walkAll(path)) << path;
        }
    }
}

// ---- Corruptions, each at a byte computed from the file's own layout ----------------------

struct Sample {
    std::string path, bytes;
    vdbformat::GridRecord grid;
};

// A float grid with Blosc compression: topology at grid.topologyPos = int32 buffer count,
// float background, uint32 tile count, uint32 child count, 0 tiles here, then the children.
Sample bloscSample(const std::string& dir, bool withTiles = false) {
    TestGridSpec spec = sampleSpec("float");
    if (!withTiles) spec.tiles.clear();
    Sample s;
    s.path = dir + "/sample.vdb";
    writeTestGrid(s.path, spec, "blosc");
    s.bytes = readBytes(s.path);
    s.grid = vdbformat::scanFile(s.path).grids.at(0);
    return s;
}

TEST(VdbTree, HugeRootTileCountIsRefusedBeforeOpenVdbLoopsOverIt) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    const uint64_t tileCount = s.grid.topologyPos + 4 + 4;
    ASSERT_EQ(peek<uint32_t>(s.bytes, tileCount), 0u);
    ASSERT_EQ(peek<uint32_t>(s.bytes, tileCount + 4), 2u) << "two root children";
    patch<uint32_t>(s.bytes, tileCount, 0x7fffffffu);
    expectCorrupt(writeBytes(dir + "/tiles.vdb", s.bytes), "root tiles at byte");
    // The slow input the fuzzer found (43 s in OpenVDB's reader) now stops at once.
    const std::string slow =
        test::sourceDir() + "/tests/fuzz/known/slow_root_topology.vdb";
    expectCorrupt(slow, "root tiles at byte");
}

TEST(VdbTree, RootChildrenOutOfOrderAreRefused) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    const uint64_t firstChild = s.grid.topologyPos + 16;
    ASSERT_EQ(peek<int32_t>(s.bytes, firstChild), 0);
    patch<int32_t>(s.bytes, firstChild, 8192);  // now after the second child at x = 4096
    expectCorrupt(writeBytes(dir + "/order.vdb", s.bytes), "out of order");
}

TEST(VdbTree, OversizedAndInconsistentBlocksAreRefusedBeforeAllocation) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    // The first leaf's data: 64-byte mask, 1-byte flag, then the int64 block size and a
    // Blosc frame whose header states the uncompressed (byte 4) and frame (byte 12) sizes.
    const uint64_t size = s.grid.blockPos + 64 + 1;
    const int64_t stored = peek<int64_t>(s.bytes, size);
    ASSERT_GT(stored, 16);
    ASSERT_EQ(peek<uint32_t>(s.bytes, size + 8 + 12), uint32_t(stored));

    std::string huge = s.bytes;
    patch<int64_t>(huge, size, int64_t(3) << 40);  // 3 TiB: what blosc_size_3tb.vdb claimed
    expectCorrupt(writeBytes(dir + "/huge.vdb", huge), "but the grid ends at byte");

    std::string raw = s.bytes;
    patch<int64_t>(raw, size, -(int64_t(1) << 20));  // "1 MiB raw" into a 2 KiB leaf
    expectCorrupt(writeBytes(dir + "/raw.vdb", raw), "an uncompressed block at byte");

    std::string header = s.bytes;
    patch<uint32_t>(header, size + 8 + 4, 1u << 30);  // Blosc would write 1 GiB
    expectCorrupt(writeBytes(dir + "/header.vdb", header), "the Blosc block at byte");

    std::string mask = s.bytes;
    mask[size_t(s.grid.blockPos)] = char(~mask[size_t(s.grid.blockPos)]);
    expectCorrupt(writeBytes(dir + "/mask.vdb", mask), "differs from its topology");
}

TEST(VdbTree, TopologyAndDataMustFillTheGridsIndexedExtent) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    // One root child fewer: the walk ends early, short of where the index puts the data.
    std::string fewer = s.bytes;
    patch<uint32_t>(fewer, s.grid.topologyPos + 12, 1u);
    expectCorrupt(writeBytes(dir + "/fewer.vdb", fewer), "but the file's index puts its data");
}

TEST(VdbTree, CorruptMetadataSizesAreRefusedByTheScan) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    // OpenVDB writes "__delayedload" metadata with each grid; its leaf count sizes an array.
    const size_t at = s.bytes.find("__delayedload");
    ASSERT_NE(at, std::string::npos);
    std::string big = s.bytes;
    patch<uint32_t>(big, at + 13 + 4, 0xfffffff0u);  // after the type name and item size
    const std::string path = writeBytes(dir + "/delayed.vdb", big);
    try {
        vdbformat::scanFile(path);
        ADD_FAILURE() << "no error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("claims 4294967280 leaves"), std::string::npos)
            << e.what();
    }
    // A float metadata item whose stated size is not 4 bytes.
    const size_t cls = s.bytes.find("file_voxel_count");
    ASSERT_NE(cls, std::string::npos);
    std::string odd = s.bytes;
    // name, then type "int64" (4 + 5 bytes), then the uint32 size.
    ASSERT_EQ(peek<uint32_t>(odd, cls + 16 + 4 + 5), 8u);
    patch<uint32_t>(odd, cls + 16 + 4 + 5, 9u);
    try {
        vdbformat::scanFile(writeBytes(dir + "/odd.vdb", odd));
        ADD_FAILURE() << "no error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("has 9 bytes, expected 8"), std::string::npos)
            << e.what();
    }
}

TEST(VdbTree, FilesBefore222AreRefusedWithWhatToDo) {
    const std::string dir = test::tempDir();
    Sample s = bloscSample(dir);
    const vdbformat::FileLayout layout = vdbformat::scanFile(s.path);
    vdbformat::FileLayout old = layout;
    old.fileVersion = 221;
    old.grids[0].topologyPos = 0;
    EXPECT_FALSE(vdbformat::treeIsWalkable(old, 0));
    try {
        vdbformat::checkOpenVdbTree(s.path, old, 0);
        ADD_FAILURE() << "no error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("predates 222"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("vdb_tool"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace mirage

namespace mirage {
namespace {

// The reader's window (src/volume/vdb_reader.h): every read returns the file's bytes at its
// position, whichever way the reads go — forward in small skips, across the window's end, far
// ahead, back to the start, one larger than the window — and a read past the end is refused.
TEST(VdbReader, EveryReadReturnsTheFilesBytesWhereverTheWindowIs) {
    std::string bytes(size_t(9) << 20, '\0');
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char((i * 2654435761u) >> 13);
    const std::string path = writeBytes(test::tempDir() + "/reader.bin", bytes);
    std::ifstream in(path, std::ios::binary);
    vdbformat::Reader r(path, in, bytes.size());
    auto expectAt = [&](uint64_t pos, uint64_t n) {
        r.seek(pos);
        std::string got(size_t(n), '\0');
        r.read(got.data(), n, "bytes");
        ASSERT_EQ(got, bytes.substr(size_t(pos), size_t(n))) << n << " bytes at " << pos;
        ASSERT_EQ(r.pos(), pos + n);
    };
    for (uint64_t pos = 0; pos < (uint64_t(5) << 20); pos += 1000) expectAt(pos, 70);
    expectAt((uint64_t(64) << 10) - 3, 10);
    expectAt(uint64_t(8) << 20, 4096);
    expectAt(0, 8);
    expectAt(12345, uint64_t(5) << 20);
    expectAt(bytes.size() - 1, 1);
    r.seek(bytes.size() - 4);
    char four[8];
    EXPECT_THROW(r.read(four, 8, "past the end"), MirageError);
}

}  // namespace
}  // namespace mirage
