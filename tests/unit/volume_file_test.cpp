// Reading OpenVDB/NanoVDB files: the reference caches in ../shared/data/vdb (facts from its
// README), agreement with OpenVDB's own lookups, and every kind of bad file we can make.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/IO.h>

#include "core/error.h"
#include "core/rng.h"
#include "test_grids.h"
#include "test_support.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Runs f and expects a MirageError whose message names the file, stays readable (under 400
// characters) and contains `needle`. Any other exception fails the test.
template <typename F>
void expectFileError(F&& f, const std::string& path, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no error for " << path;
    } catch (const MirageError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_LT(msg.size(), 400u) << msg;
        EXPECT_NE(msg.find(needle), std::string::npos) << "expected '" << needle << "': " << msg;
    }
}

// All three entry points must reject a bad file the same way.
void expectBadFile(const std::string& path, const std::string& needle) {
    expectFileError([&] { validateVdbFile(path); }, path, needle);
    expectFileError([&] { inspectVdbFile(path); }, path, needle);
    expectFileError([&] { loadFloatGrid(path, "density"); }, path, needle);
}

float nanoValue(const FloatGrid& g, int i, int j, int k) {
    return g.grid()->tree().getValue(nanovdb::Coord(i, j, k));
}

// ---- Reference data ----------------------------------------------------------------------

TEST(VolumeFile, ReadsEveryGridOfEveryReferenceFile) {
    MIRAGE_REQUIRE_SHARED(dir, "vdb");
    int files = 0, grids = 0, vectors = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        validateVdbFile(path);
        VdbFileInfo info = inspectVdbFile(path);
        ASSERT_FALSE(info.grids.empty());
        for (size_t i = 0; i < info.grids.size(); ++i) {
            const GridInfo& gi = info.grids[i];
            const std::string name = gi.name.empty() ? "#" + std::to_string(i) : gi.name;
            if (gi.valueType.compare(0, 4, "vec3") == 0) {
                // Velocity (Mantaflow writes it staggered).
                VectorGrid v = loadVectorGrid(path, name);
                ASSERT_TRUE(v.valid());
                EXPECT_EQ(v.activeVoxels(), gi.activeVoxels) << name;
                EXPECT_EQ(v.staggered(), gi.gridClass == "staggered") << name;
                EXPECT_EQ(v.sanitizedVoxels(), 0u);
                EXPECT_GT(v.maxMagnitude(), 0.f);
                EXPECT_GE(v.magnitudeBound(), v.maxMagnitude());
                EXPECT_FALSE(v.objectBounds().empty());
                for (int a = 0; a < 3; ++a) {
                    EXPECT_EQ(v.indexBounds().min()[a], gi.indexMin[a]);
                    EXPECT_EQ(v.indexBounds().max()[a], gi.indexMax[a]);
                }
                ++vectors;
                ++grids;
                continue;
            }
            FloatGrid g = loadFloatGrid(path, name);
            ASSERT_TRUE(g.valid());
            EXPECT_EQ(g.activeVoxels(), gi.activeVoxels) << name;
            EXPECT_EQ(g.sanitizedVoxels(), 0u);
            EXPECT_GT(g.maxValue(), 0.f);
            EXPECT_FALSE(g.objectBounds().empty());
            for (int a = 0; a < 3; ++a) {
                EXPECT_EQ(g.indexBounds().min()[a], gi.indexMin[a]);
                EXPECT_EQ(g.indexBounds().max()[a], gi.indexMax[a]);
            }
            ++grids;
        }
        ++files;
    }
    EXPECT_GE(files, 5);
    EXPECT_GE(grids, 6);
    EXPECT_GE(vectors, 3);  // the three Mantaflow frames' velocity
}

TEST(VolumeFile, Smoke1MetadataMatchesReadme) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/smoke1.vdb");
    VdbFileInfo info = inspectVdbFile(path);
    EXPECT_EQ(info.format, "OpenVDB");
    ASSERT_EQ(info.grids.size(), 1u);
    const GridInfo& g = info.grids[0];
    EXPECT_EQ(g.name, "density");
    EXPECT_EQ(g.valueType, "half");
    EXPECT_EQ(g.gridClass, "fog volume");
    EXPECT_EQ(g.activeVoxels, 1049275u);
    const int64_t lo[3] = {1, 2, 1}, hi[3] = {111, 223, 112};
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(g.indexMin[a], lo[a]);
        EXPECT_EQ(g.indexMax[a], hi[a]);
        EXPECT_NEAR(g.voxelSize[a], 0.476, 1e-3);
    }
    EXPECT_GT(g.memoryBytes, 1000000u);
    // The bounds span the voxels ±½ around the extreme centres.
    EXPECT_NEAR(g.objectBounds.hi.y - g.objectBounds.lo.y, 222 * g.voxelSize.y, 1e-3);

    FloatGrid grid = loadFloatGrid(path, "density");
    EXPECT_EQ(grid.name(), "density");
    EXPECT_EQ(grid.activeVoxels(), 1049275u);
    EXPECT_NEAR(grid.maxValue(), 5.71484f, 1e-3f);  // vdb_print's "Max value"
}

TEST(VolumeFile, DensityAndHeatMetadataMatchesReadme) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/density_and_heat.vdb");
    VdbFileInfo info = inspectVdbFile(path);
    ASSERT_EQ(info.grids.size(), 2u);
    for (const GridInfo& g : info.grids) {
        EXPECT_EQ(g.valueType, "float");
        EXPECT_EQ(g.compression, "blosc");
        if (g.name == "density") {
            EXPECT_EQ(g.activeVoxels, 6124u);
        } else if (g.name == "heat") {
            EXPECT_EQ(g.activeVoxels, 5224u);
        } else {
            ADD_FAILURE() << "unexpected grid " << g.name;
        }
    }
    EXPECT_EQ(loadFloatGrid(path, "heat").activeVoxels(), 5224u);
    EXPECT_EQ(loadFloatGrid(path, "density").activeVoxels(), 6124u);
}

TEST(VolumeFile, NanoVdbBloscFileMatchesTheOpenVdbOriginal) {
    MIRAGE_REQUIRE_SHARED(nvdb, "vdb/smoke1_blosc.nvdb");
    MIRAGE_REQUIRE_SHARED(vdb, "vdb/smoke1.vdb");
    VdbFileInfo info = inspectVdbFile(nvdb);
    EXPECT_EQ(info.format, "NanoVDB");
    ASSERT_EQ(info.grids.size(), 1u);
    EXPECT_EQ(info.grids[0].name, "");
    EXPECT_EQ(info.grids[0].compression, "blosc");
    EXPECT_EQ(info.grids[0].activeVoxels, 1049275u);

    FloatGrid nano = loadFloatGrid(nvdb, "#0");
    FloatGrid open = loadFloatGrid(vdb, "density");
    EXPECT_EQ(nano.name(), "#0");
    EXPECT_EQ(nano.activeVoxels(), open.activeVoxels());
    // The same index-space values (the .nvdb was converted with unit voxels).
    Sampler rng(11, 0, 0);
    for (int n = 0; n < 20000; ++n) {
        int i = int(rng.get1D() * 113), j = int(rng.get1D() * 226), k = int(rng.get1D() * 114);
        ASSERT_EQ(nanoValue(nano, i, j, k), nanoValue(open, i, j, k)) << i << "," << j << "," << k;
    }
    expectFileError([&] { loadFloatGrid(nvdb, "#1"); }, nvdb, "no grid '#1'");
}

TEST(VolumeFile, NanoVdbGridsWrittenFromOneHandleLoadEach) {
    // nanovdb::io writes the grids of one handle with their indices among it (0 and 1 here);
    // GridHandle::grid(0) on the second alone would step past its buffer looking for index 0.
    const std::string dir = test::tempDir();
    TestGridSpec a, b;
    a.voxels = {{0, 0, 0, 1.0}, {9, 1, 2, 2.0}};
    b.voxels = {{3, 3, 3, 5.0}};
    writeTestGrid(dir + "/a.vdb", a);
    writeTestGrid(dir + "/b.vdb", b);
    const FloatGrid ga = loadFloatGrid(dir + "/a.vdb", "density");
    const FloatGrid gb = loadFloatGrid(dir + "/b.vdb", "density");
    // Each grid alone as NanoVDB 32.4 writes it (a 16-byte segment header, 176 bytes of
    // metadata and the name, then the grid), marked as grid 0 and 1 of 2; then spliced into
    // one segment of two grids: header, both metadata records, both grids.
    std::string parts[2][3];
    const FloatGrid* grids[2] = {&ga, &gb};
    for (int n = 0; n < 2; ++n) {
        const uint64_t size = grids[n]->grid()->gridSize();
        nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(size);
        std::memcpy(buffer.data(), grids[n]->grid(), size);
        nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
        const std::string one = dir + "/one" + std::to_string(n) + ".nvdb";
        nanovdb::io::writeGrid(one, handle, nanovdb::io::Codec::NONE);
        // NanoVDB 32.4's own writer loops on a grid whose index is not 0, so the index and
        // count are set in the written bytes, and the checksum that covers them recomputed.
        auto* g = reinterpret_cast<nanovdb::FloatGrid*>(handle.data());
        g->data()->mGridIndex = uint32_t(n);
        g->data()->mGridCount = 2;
        nanovdb::updateChecksum(*g, nanovdb::ChecksumMode::Partial);
        const std::string bytes = readBytes(one);
        const size_t metaEnd = bytes.size() - size;
        parts[n][0] = bytes.substr(0, 16);
        parts[n][1] = bytes.substr(16, metaEnd - 16);
        parts[n][2] = std::string(reinterpret_cast<const char*>(handle.data()), size);
    }
    std::string header = parts[0][0];
    header[12] = 2;  // uint16 grid count
    const std::string nvdb = dir + "/pair.nvdb";
    writeBytes(nvdb, header + parts[0][1] + parts[1][1] + parts[0][2] + parts[1][2]);
    ASSERT_EQ(inspectVdbFile(nvdb).grids.size(), 2u);
    const FloatGrid first = loadFloatGrid(nvdb, "#0"), second = loadFloatGrid(nvdb, "#1");
    EXPECT_EQ(first.activeVoxels(), 2u);
    EXPECT_EQ(nanoValue(first, 9, 1, 2), 2.f);
    EXPECT_EQ(second.activeVoxels(), 1u);
    EXPECT_EQ(nanoValue(second, 3, 3, 3), 5.f);
    EXPECT_EQ(second.grid()->gridIndex(), 0u) << "a loaded grid is grid 0 of its own handle";
    EXPECT_EQ(second.grid()->gridCount(), 1u);
}

TEST(VolumeFile, NanoVdbNodeOffsetOffAlignmentIsCorrupt) {
    // The tree's node offsets (four uint64 at the start of TreeData, after the grid's fixed
    // part) are multiples of 32 in any file NanoVDB writes. The root's 8 bytes early still reads
    // a plausible tile count (the bounding box's max y, 1) and fits the buffer: it is refused
    // before a node is read through it, not left to the checksum.
    const std::string dir = test::tempDir();
    TestGridSpec spec;
    spec.voxels = {{0, 0, 0, 1.0}, {9, 1, 2, 2.0}};
    writeTestGrid(dir + "/a.vdb", spec);
    const FloatGrid grid = loadFloatGrid(dir + "/a.vdb", "density");
    const uint64_t size = grid.grid()->gridSize();
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(size);
    std::memcpy(buffer.data(), grid.grid(), size);
    const std::string good = dir + "/good.nvdb";
    nanovdb::io::writeGrid(good, nanovdb::GridHandle<nanovdb::HostBuffer>(std::move(buffer)),
                           nanovdb::io::Codec::NONE);
    std::string bytes = readBytes(good);
    const size_t rootOffsetAt = bytes.size() - size + sizeof(nanovdb::GridData) + 3 * 8;
    uint64_t rootOffset = 0;
    std::memcpy(&rootOffset, &bytes[rootOffsetAt], 8);
    ASSERT_EQ(rootOffset % 32, 0u);
    rootOffset -= 8;
    std::memcpy(&bytes[rootOffsetAt], &rootOffset, 8);
    const std::string bad = dir + "/offset.nvdb";
    writeBytes(bad, bytes);
    EXPECT_EQ(loadFloatGrid(good, "#0").activeVoxels(), 2u);
    expectFileError([&] { loadFloatGrid(bad, "#0"); }, bad, "off 32-byte alignment");
}

TEST(VolumeFile, NanoVdbSizeBeyondAnyCompressionRatioIsRefused) {
    // The metadata's uncompressed size (first field after the 16-byte segment header) is what
    // Mirage allocates before decompressing; no codec reaches 1032:1.
    MIRAGE_REQUIRE_SHARED(nvdb, "vdb/smoke1_blosc.nvdb");
    std::string bytes = readBytes(nvdb);
    const uint64_t claimed = uint64_t(bytes.size()) * 2000;
    std::memcpy(&bytes[16], &claimed, 8);
    const std::string path = test::tempDir() + "/ratio.nvdb";
    writeBytes(path, bytes);
    expectFileError([&] { loadFloatGrid(path, "#0"); }, path, "compressed bytes");
}

TEST(VolumeFile, NanoVdbLookupsAgreeWithOpenVdb) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/smoke1.vdb");
    FloatGrid grid = loadFloatGrid(path, "density");
    const nanovdb::FloatGrid* g = grid.grid();
    auto acc = grid.accessor();
    auto trilinear = nanovdb::createSampler<1, NanoAccessor<float>, false>(acc.as<float>());

    Sampler rng(5, 0, 0);
    std::vector<Vec3d> centres, points, world;
    for (int n = 0; n < 4000; ++n) {
        // Voxel centres and fractional points over the active bbox and one voxel beyond.
        centres.emplace_back(std::floor(rng.get1Dd() * 113), std::floor(rng.get1Dd() * 226),
                             std::floor(rng.get1Dd() * 114));
        points.emplace_back(rng.get1Dd() * 113, rng.get1Dd() * 226, rng.get1Dd() * 114);
        nanovdb::Vec3d w =
            g->indexToWorld(nanovdb::Vec3d(points.back().x, points.back().y, points.back().z));
        world.emplace_back(w[0], w[1], w[2]);
    }
    std::vector<double> refCentres = openvdbSampleForTest(path, "density", centres, true);
    std::vector<double> refPoints = openvdbSampleForTest(path, "density", points, true);
    std::vector<double> refWorld = openvdbSampleForTest(path, "density", world, false);
    double maxErrIndex = 0, maxErrWorld = 0, maxErrFloatMap = 0;
    for (size_t n = 0; n < centres.size(); ++n) {
        const Vec3d& c = centres[n];
        ASSERT_EQ(double(trilinear(nanovdb::Vec3f(float(c.x), float(c.y), float(c.z)))),
                  refCentres[n]);
        const Vec3d& p = points[n];
        maxErrIndex = std::max(maxErrIndex,
                               std::abs(trilinear(nanovdb::Vec3d(p.x, p.y, p.z)) - refPoints[n]));
        nanovdb::Vec3d pi = g->worldToIndex(nanovdb::Vec3d(world[n].x, world[n].y, world[n].z));
        maxErrWorld = std::max(maxErrWorld, std::abs(trilinear(pi) - refWorld[n]));
        maxErrFloatMap =
            std::max(maxErrFloatMap, std::abs(grid.sample(acc, Vec3(world[n])) - refWorld[n]));
    }
    EXPECT_LT(maxErrIndex, 1e-5);
    EXPECT_LT(maxErrWorld, 1e-5);
    // FloatGrid::sample maps world → index in float: ~1e-6 relative position error times the
    // value gradient (up to ~5 per voxel here).
    EXPECT_LT(maxErrFloatMap, 1e-3);
}

// ---- Bad files ---------------------------------------------------------------------------

TEST(VolumeFile, TruncatedCopiesGiveClearErrors) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/smoke1.vdb");
    const std::string bytes = readBytes(path);
    const std::string dir = test::tempDir();
    const size_t lengths[] = {4, 10, 60, 1000, bytes.size() / 2, bytes.size() - 100};
    for (size_t n : lengths) {
        const std::string copy = dir + "/smoke1_" + std::to_string(n) + ".vdb";
        writeBytes(copy, bytes.substr(0, n));
        SCOPED_TRACE(copy);
        expectBadFile(copy, "truncated");
    }
    // The message docs/hostile-input.md promises, with both byte counts.
    const std::string half = dir + "/smoke1_" + std::to_string(bytes.size() / 2) + ".vdb";
    expectFileError([&] { validateVdbFile(half); }, half,
                    "grid 'density' ends at byte " + std::to_string(bytes.size()) +
                        " but the file has " + std::to_string(bytes.size() / 2) + " bytes");
}

TEST(VolumeFile, TruncatedNanoVdbGivesClearErrors) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/smoke1_blosc.nvdb");
    const std::string bytes = readBytes(path);
    const std::string dir = test::tempDir();
    for (size_t n : {size_t(6), size_t(100), bytes.size() / 2, bytes.size() - 1}) {
        const std::string copy = dir + "/smoke_" + std::to_string(n) + ".nvdb";
        writeBytes(copy, bytes.substr(0, n));
        SCOPED_TRACE(copy);
        expectFileError([&] { loadFloatGrid(copy, "#0"); }, copy, "truncated");
    }
}

TEST(VolumeFile, NonVdbFilesGiveClearErrors) {
    const std::string dir = test::tempDir();
    const std::string empty = dir + "/empty.vdb", text = dir + "/notes.vdb",
                      png = dir + "/image.vdb", missing = dir + "/missing.vdb";
    writeBytes(empty, "");
    writeBytes(text, "this is a text file renamed .vdb\n");
    writeBytes(png, std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    expectBadFile(empty, "empty");
    expectBadFile(text, "not an OpenVDB file (bad magic number)");
    expectBadFile(png, "not an OpenVDB file (bad magic number)");
    expectFileError([&] { validateVdbFile(png); }, png, "PNG");
    expectBadFile(missing, "not found");
    expectBadFile(dir, "directory");
}

TEST(VolumeFile, CorruptHeaderFieldsGiveClearErrors) {
    const std::string dir = test::tempDir();
    const std::string good = dir + "/good.vdb";
    TestGridSpec spec;
    spec.voxels = {{0, 0, 0, 1.0}, {1, 2, 3, 0.5}};
    writeTestGrid(good, spec);
    const std::string bytes = readBytes(good);
    ASSERT_EQ(loadFloatGrid(good, "density").activeVoxels(), 2u);

    // Header: magic (8), version (4) at 8, library version (8), offsets flag (1), uuid (36),
    // file metadata count at 57.
    auto patch = [&](const std::string& name, size_t at, uint32_t value) {
        std::string b = bytes;
        std::memcpy(&b[at], &value, 4);
        writeBytes(dir + "/" + name, b);
        return dir + "/" + name;
    };
    expectBadFile(patch("version.vdb", 8, 999999), "unsupported OpenVDB file format version");
    expectBadFile(patch("future.vdb", 8, 300), "unsupported OpenVDB file format version");
    expectBadFile(patch("metacount.vdb", 57, 0x7fffffff), "truncated");
    // The first metadata name length: garbage lengths are "corrupt", never allocated.
    expectBadFile(patch("namelength.vdb", 61, 0xfffffff0u), "corrupt");
}

TEST(VolumeFile, CorruptPayloadNeverCrashes) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/density_and_heat.vdb");
    const std::string bytes = readBytes(path);
    const std::string dir = test::tempDir();
    // Overwrite stretches of the grid data with noise: OpenVDB may still decode something or
    // fail, but every failure must be a bounded MirageError.
    Sampler rng(3, 0, 0);
    for (int trial = 0; trial < 8; ++trial) {
        std::string b = bytes;
        size_t at = 2000 + size_t(rng.get1D() * float(b.size() - 3000));
        for (size_t i = 0; i < 64; ++i) b[at + i] = char((unsigned char)(rng.get1D() * 256));
        const std::string copy = dir + "/noise" + std::to_string(trial) + ".vdb";
        writeBytes(copy, b);
        for (const char* name : {"density", "heat"}) {
            try {
                loadFloatGrid(copy, name);
            } catch (const MirageError& e) {
                EXPECT_LT(std::string(e.what()).size(), 400u) << e.what();
            }
        }
    }
}

// ---- Wrong kinds of grid -----------------------------------------------------------------

TEST(VolumeFile, WrongGridKindsAreRejectedByName) {
    const std::string dir = test::tempDir();
    auto write = [&](const std::string& file, TestGridSpec spec) {
        spec.voxels = {{0, 0, 0, 1.0, Vec3d(1, 0, 0)}, {3, 1, 2, 0.5, Vec3d(0, 1, 0)}};
        writeTestGrid(dir + "/" + file, spec);
        return dir + "/" + file;
    };
    TestGridSpec vec;
    vec.name = "vel";
    vec.valueType = "vec3s";
    vec.gridClass = "staggered";
    std::string p = write("vector.vdb", vec);
    expectFileError([&] { loadFloatGrid(p, "vel"); }, p, "grid 'vel' holds 3-vector (vec3s)");

    TestGridSpec mask;
    mask.name = "mask";
    mask.valueType = "bool";
    p = write("bool.vdb", mask);
    expectFileError([&] { loadFloatGrid(p, "mask"); }, p, "boolean");

    TestGridSpec sdf;
    sdf.name = "surface";
    sdf.gridClass = "level set";
    sdf.background = 0.3;
    p = write("levelset.vdb", sdf);
    expectFileError([&] { loadFloatGrid(p, "surface"); }, p, "grid 'surface' is a level set");
    EXPECT_EQ(inspectVdbFile(p).grids.at(0).gridClass, "level set");

    TestGridSpec offset;
    offset.gridClass = "unknown";
    offset.background = 1.0;
    p = write("background.vdb", offset);
    expectFileError([&] { loadFloatGrid(p, "density"); }, p, "background value 1");

    p = write("plain.vdb", TestGridSpec());
    expectFileError([&] { loadFloatGrid(p, "nope"); }, p, "no grid 'nope' (grids: density)");
}

// ---- Vector grids (velocity) ------------------------------------------------------------

// A field linear in x, v = (2x + 1, −y, 3) in index units, stored at the positions each class
// says (centres, or the faces of a staggered grid), is reproduced exactly by trilinear lookups
// anywhere inside the block: the staggered half-voxel shift is exact, not approximate. The block
// spans 3³ leaves, so lookups whose stencil lies in one leaf (read from its array) and those
// that straddle leaves (read through the accessor) are both checked.
TEST(VolumeFile, VectorGridsSampleCollocatedAndStaggeredLayouts) {
    const std::string dir = test::tempDir();
    auto field = [](double x, double y) { return Vec3d(2 * x + 1, -y, 3); };
    for (const bool staggered : {false, true}) {
        SCOPED_TRACE(staggered ? "staggered" : "collocated");
        TestGridSpec spec;
        spec.name = "vel";
        spec.valueType = "vec3s";
        spec.gridClass = staggered ? "staggered" : "fog volume";
        spec.voxelSize = 1.0;
        for (int i = 0; i < 20; ++i)
            for (int j = 0; j < 20; ++j)
                for (int k = 0; k < 20; ++k) {
                    // Component a of a staggered voxel lives at index − ½ along a.
                    const double sx = staggered ? 0.5 : 0.0;
                    Vec3d v(field(i - sx, j).x, field(i, j - sx).y, 3);
                    spec.voxels.push_back({i, j, k, 0.0, v});
                }
        const std::string path = dir + (staggered ? "/stag.vdb" : "/centre.vdb");
        writeTestGrid(path, spec);
        VectorGrid g = loadVectorGrid(path, "vel");
        ASSERT_EQ(g.staggered(), staggered);
        auto acc = g.accessor();
        // Object space = index space (unit voxels at the origin).
        for (const Vec3 p : {Vec3(2.3f, 3.7f, 4.1f), Vec3(5.5f, 2.25f, 3.f), Vec3(4.f, 4.f, 4.f),
                             Vec3(7.6f, 8.4f, 15.5f), Vec3(15.2f, 7.5f, 8.f),
                             Vec3(8.f, 16.7f, 7.2f), Vec3(6.7f, 6.6f, 6.9f)}) {
            const Vec3 v = g.sample(acc, p);
            const Vec3d want = field(p.x, p.y);
            EXPECT_NEAR(v.x, want.x, 1e-4) << p.x << " " << p.y;
            EXPECT_NEAR(v.y, want.y, 1e-4);
            EXPECT_NEAR(v.z, 3.0, 1e-5);
            EXPECT_LE(length(v), g.magnitudeBound() * (1 + 1e-6f));
        }
        EXPECT_EQ(g.sample(acc, Vec3(50.f, 50.f, 50.f)).x, 0.f);
    }
}

TEST(VolumeFile, VectorVoxelRuleZeroesNonFiniteAndShortensHuge) {
    const std::string dir = test::tempDir();
    const double inf = std::numeric_limits<double>::infinity();
    TestGridSpec spec;
    spec.name = "vel";
    spec.valueType = "vec3s";
    spec.voxelSize = 1.0;
    spec.voxels = {{0, 0, 0, 0.0, Vec3d(1, 0, 0)},
                   {1, 0, 0, 0.0, Vec3d(std::nan(""), 0, 0)},
                   {2, 0, 0, 0.0, Vec3d(0, inf, 0)},
                   {3, 0, 0, 0.0, Vec3d(0, 0, 1e30)}};
    const std::string path = dir + "/bad_vel.vdb";
    writeTestGrid(path, spec);
    VectorGrid g = loadVectorGrid(path, "vel");
    EXPECT_EQ(g.sanitizedVoxels(), 3u);
    EXPECT_FLOAT_EQ(g.maxMagnitude(), kMaxVoxelValue);
    auto acc = g.accessor();
    EXPECT_EQ(g.sample(acc, Vec3(0.f, 0.f, 0.f)).x, 1.f);
    EXPECT_EQ(g.sample(acc, Vec3(1.f, 0.f, 0.f)).x, 0.f);  // the NaN became 0
    EXPECT_FLOAT_EQ(g.sample(acc, Vec3(0.5f, 0.f, 0.f)).x, 0.5f);
    EXPECT_EQ(g.sample(acc, Vec3(2.f, 0.f, 0.f)).y, 0.f);  // so did the infinity
    EXPECT_FLOAT_EQ(g.sample(acc, Vec3(3.f, 0.f, 0.f)).z, kMaxVoxelValue);
    // Scalar loaders still refuse vectors, and the vector loader refuses scalars, by name.
    expectFileError([&] { loadFloatGrid(path, "vel"); }, path, "grid 'vel' holds 3-vector");
    TestGridSpec density;
    const std::string scalar = dir + "/density.vdb";
    writeTestGrid(scalar, density);
    expectFileError([&] { loadVectorGrid(scalar, "density"); }, scalar,
                    "expected a 3-vector grid");
}

TEST(VolumeFile, VoxelRuleZeroesNanAndNegativeClampsHugeWithOneWarning) {
    const std::string dir = test::tempDir();
    const float inf = std::numeric_limits<float>::infinity();
    TestGridSpec spec;
    spec.voxels = {{0, 0, 0, std::nan("")}, {1, 0, 0, inf},  {2, 0, 0, -inf},
                   {3, 0, 0, -1.0},         {4, 0, 0, 1e30}, {5, 0, 0, 0.5}};
    const std::string path = dir + "/bad_values.vdb";
    writeTestGrid(path, spec);

    testing::internal::CaptureStderr();
    FloatGrid g = loadFloatGrid(path, "density");
    FloatGrid again = loadFloatGrid(path, "density");
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(g.sanitizedVoxels(), 5u);
    EXPECT_EQ(again.sanitizedVoxels(), 5u);
    const std::string warning = "warning: " + path +
                                ": grid 'density': 3 voxels were negative or NaN and were set to "
                                "0; 2 voxels were +inf or above 1e+10 and were clamped to it\n";
    EXPECT_EQ(err, warning);  // once, although loaded twice
    for (int i : {0, 2, 3}) EXPECT_EQ(nanoValue(g, i, 0, 0), 0.f) << i;
    EXPECT_EQ(nanoValue(g, 1, 0, 0), kMaxVoxelValue);  // +inf
    EXPECT_EQ(nanoValue(g, 4, 0, 0), kMaxVoxelValue);  // 1e30
    EXPECT_EQ(nanoValue(g, 5, 0, 0), 0.5f);
    EXPECT_EQ(g.maxValue(), kMaxVoxelValue);

    // Stored as half, 1e30 overflows to +inf on disk and is clamped the same way.
    spec.saveAsHalf = true;
    const std::string halfPath = dir + "/bad_values_half.vdb";
    writeTestGrid(halfPath, spec);
    EXPECT_EQ(inspectVdbFile(halfPath).grids.at(0).valueType, "half");
    testing::internal::CaptureStderr();
    FloatGrid h = loadFloatGrid(halfPath, "density");
    testing::internal::GetCapturedStderr();
    EXPECT_EQ(h.sanitizedVoxels(), 5u);
    EXPECT_EQ(nanoValue(h, 5, 0, 0), 0.5f);
}

// ---- Names, types, compression, tiles ----------------------------------------------------

TEST(VolumeFile, UnnamedAndDuplicateGridsAreAddressable) {
    const std::string path = test::tempDir() + "/several.vdb";
    TestGridSpec a, b, c, d;
    a.name = "";
    a.voxels = {{0, 0, 0, 1.0}};
    b.name = "heat";
    b.voxels = {{0, 0, 0, 2.0}};
    c.name = "density";
    c.voxels = {{0, 0, 0, 3.0}};
    d.name = "density";
    d.voxels = {{0, 0, 0, 4.0}};
    writeTestGrids(path, {a, b, c, d});
    VdbFileInfo info = inspectVdbFile(path);
    ASSERT_EQ(info.grids.size(), 4u);
    EXPECT_EQ(info.grids[0].name, "");
    EXPECT_EQ(info.grids[1].name, "heat");
    auto value = [&](const std::string& name) {
        return nanoValue(loadFloatGrid(path, name), 0, 0, 0);
    };
    EXPECT_EQ(value("#0"), 1.f);
    EXPECT_EQ(value("#1"), 2.f);
    EXPECT_EQ(value("heat"), 2.f);
    EXPECT_EQ(value("density"), 3.f);
    EXPECT_EQ(value("#3"), 4.f);
    EXPECT_EQ(value("density[1]"), 4.f);
    EXPECT_EQ(loadFloatGrid(path, "#0").name(), "#0");
    expectFileError([&] { loadFloatGrid(path, "#4"); }, path,
                    "#0 (unnamed), heat, density[0], density[1]");
}

TEST(VolumeFile, DoubleZipAndUncompressedGridsLoad) {
    const std::string dir = test::tempDir();
    TestGridSpec spec;
    spec.valueType = "double";
    spec.gridClass = "unknown";  // OpenVDB never zips fog volumes
    for (int i = 0; i < 40; ++i) spec.voxels.push_back({i, i % 7, 2 * i, 0.25 + i});
    for (const char* compression : {"zip", "none", "blosc"}) {
        const std::string path = dir + "/double_" + compression + ".vdb";
        writeTestGrid(path, spec, compression);
        VdbFileInfo info = inspectVdbFile(path);
        EXPECT_EQ(info.grids.at(0).valueType, "double");
        EXPECT_EQ(info.grids.at(0).compression,
                  std::string(compression) == "none" ? "none" : compression);
        FloatGrid g = loadFloatGrid(path, "density");
        EXPECT_EQ(g.activeVoxels(), 40u);
        for (const auto& v : spec.voxels) EXPECT_EQ(nanoValue(g, v.i, v.j, v.k), float(v.value));
    }
}

TEST(VolumeFile, TilesCountInBoundsAndMaximum) {
    const std::string path = test::tempDir() + "/tiles.vdb";
    TestGridSpec spec;
    spec.voxelSize = 0.5;
    spec.origin = Vec3d(10, 0, 0);
    spec.voxels = {{0, 0, 0, 1.0}};
    spec.tiles = {{16, 0, 0, 1, 2.5}};  // the 8³ block at index (16..23, 0..7, 0..7)
    writeTestGrid(path, spec);
    FloatGrid g = loadFloatGrid(path, "density");
    EXPECT_EQ(g.activeVoxels(), 1u + 512u);
    EXPECT_EQ(g.maxValue(), 2.5f);
    EXPECT_EQ(nanoValue(g, 20, 3, 3), 2.5f);
    // Active index bbox (0,0,0)–(23,7,7) dilated by one voxel, at 0.5 m per voxel from x = 10.
    Bounds3 b = g.objectBounds();
    EXPECT_FLOAT_EQ(b.lo.x, 9.5f);
    EXPECT_FLOAT_EQ(b.hi.x, 22.f);
    EXPECT_FLOAT_EQ(b.lo.y, -0.5f);
    EXPECT_FLOAT_EQ(b.hi.z, 4.f);
    auto acc = g.accessor();
    EXPECT_FLOAT_EQ(g.sample(acc, Vec3(20.f, 2.f, 2.f)), 2.5f);  // index (20, 4, 4)
}

}  // namespace
}  // namespace mirage
