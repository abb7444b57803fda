// `mirage make-asset`: procedural OpenVDB assets are deterministic for a seed, have the
// documented grids and value ranges, and are written atomically.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "tools/procedural_fields.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

// The file's bytes without its header UUID (bytes 21–56 of a version-224 file), which OpenVDB
// draws at random on every write.
std::string contentWithoutUuid(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (b.size() > 57) b.replace(21, 36, 36, '-');
    return b;
}

struct ValueRange {
    float lo = kInfinity, hi = -kInfinity;
    uint64_t active = 0;
};

// Range of the active voxel values, read straight from the NanoVDB leaves.
ValueRange activeRange(const FloatGrid& g) {
    ValueRange r;
    const auto& tree = g.grid()->tree();
    const auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i)
        for (uint32_t k = 0; k < 512; ++k)
            if (leaf[i].isActive(k)) {
                float v = leaf[i].getValue(k);
                r.lo = std::min(r.lo, v);
                r.hi = std::max(r.hi, v);
                ++r.active;
            }
    return r;
}

TEST(Asset, SameSeedSameFileDifferentSeedDifferentFile) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("smoke", dir + "/a.vdb", 32, 7);
    writeProceduralAsset("smoke", dir + "/b.vdb", 32, 7);
    writeProceduralAsset("smoke", dir + "/c.vdb", 32, 8);
    const std::string a = contentWithoutUuid(dir + "/a.vdb");
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, contentWithoutUuid(dir + "/b.vdb"));
    EXPECT_NE(a, contentWithoutUuid(dir + "/c.vdb"));

    // The voxel values themselves, through the loader.
    FloatGrid ga = loadFloatGrid(dir + "/a.vdb", "density");
    FloatGrid gb = loadFloatGrid(dir + "/b.vdb", "density");
    FloatGrid gc = loadFloatGrid(dir + "/c.vdb", "density");
    EXPECT_EQ(ga.activeVoxels(), gb.activeVoxels());
    int differ = 0;
    const auto& ta = ga.grid()->tree();
    for (int k = 0; k < 20; ++k)
        for (int j = 0; j < 32; ++j)
            for (int i = 0; i < 20; ++i) {
                nanovdb::Coord c(i, j, k);
                ASSERT_EQ(ta.getValue(c), gb.grid()->tree().getValue(c));
                differ += ta.getValue(c) != gc.grid()->tree().getValue(c);
            }
    EXPECT_GT(differ, 100);
}

// The blocks are evaluated in parallel: one thread and every thread write the same file.
TEST(Asset, SameFileForAnyThreadCount) {
    const std::string dir = test::tempDir();
    for (const char* kind : {"smoke", "pyro"}) {
        SCOPED_TRACE(kind);
        const std::string one = dir + "/" + kind + "_1.vdb", all = dir + "/" + kind + "_n.vdb";
        {
            tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
            writeProceduralAsset(kind, one, 40, 3);
        }
        writeProceduralAsset(kind, all, 40, 3);
        const std::string a = contentWithoutUuid(one);
        EXPECT_GT(a.size(), 10000u);
        EXPECT_TRUE(a == contentWithoutUuid(all));
    }
}

// --voxels aims at an active voxel count by the resolution; the pyro's density is within a few
// per cent of it.
TEST(Asset, PyroReachesTheVoxelCountAskedFor) {
    const int res = assetResolutionForVoxels("pyro", 1, 2e5);
    const std::string path = test::tempDir() + "/pyro.vdb";
    writeProceduralAsset("pyro", path, res, 1);
    const VdbFileInfo info = inspectVdbFile(path);
    EXPECT_NEAR(double(info.grids[0].activeVoxels), 2e5, 0.1 * 2e5);
    // The temperature lies in the column's core, a subset of the density's voxels.
    EXPECT_LT(info.grids[1].activeVoxels, info.grids[0].activeVoxels);
    const ValueRange t = activeRange(loadFloatGrid(path, "temperature"));
    EXPECT_GE(t.lo, 299.f);
    EXPECT_LE(t.hi, 1201.f);
}

TEST(Asset, KindsHaveTheDocumentedGridsAndRanges) {
    const std::string dir = test::tempDir();
    const int res = 48;
    struct Expect {
        const char* kind;
        std::vector<std::string> grids;
    };
    const Expect expects[] = {{"smoke", {"density", "temperature", "vel"}},
                              {"smoke-sphere", {"density", "temperature"}},
                              {"fire", {"density", "temperature", "flame", "vel"}},
                              {"plume", {"density", "temperature", "flame", "vel"}},
                              {"fog-sphere", {"density"}}};
    for (const Expect& e : expects) {
        SCOPED_TRACE(e.kind);
        const std::string path = dir + "/" + e.kind + ".vdb";
        writeProceduralAsset(e.kind, path, res, 1);
        VdbFileInfo info = inspectVdbFile(path);
        ASSERT_EQ(info.grids.size(), e.grids.size());
        for (size_t i = 0; i < e.grids.size(); ++i) {
            const GridInfo& gi = info.grids[i];
            EXPECT_EQ(gi.name, e.grids[i]);
            // The plumes' velocity (`vel`, m/s) is a collocated vector grid.
            const bool velocity = e.grids[i] == std::string("vel");
            EXPECT_EQ(gi.valueType, velocity ? "vec3s" : "float");
            EXPECT_EQ(gi.gridClass, velocity ? "unknown" : "fog volume");
            EXPECT_NEAR(gi.voxelSize.x, 2.0 / res, 1e-6);
            // Sparse: far fewer active voxels than the dense domain.
            EXPECT_GT(gi.activeVoxels, 500u);
            EXPECT_LE(gi.indexMax[1] - gi.indexMin[1] + 1, res);
            // Standing on y = 0, at most 2 m tall; the density about 2 m (flames are lower).
            EXPECT_GT(gi.objectBounds.lo.y, -0.01f);
            EXPECT_LT(gi.objectBounds.hi.y, 2.01f);
            if (i == 0) {
                EXPECT_GT(gi.objectBounds.hi.y - gi.objectBounds.lo.y, 1.5f);
            }
        }
        EXPECT_EQ(info.grids[0].compression, "blosc");

        FloatGrid density = loadFloatGrid(path, "density");
        ValueRange d = activeRange(density);
        EXPECT_GT(d.lo, 0.f);
        EXPECT_GT(d.hi, 0.5f);
        EXPECT_LE(d.hi, 1.3f);
        EXPECT_LT(d.active, uint64_t(res) * res * res);
        if (e.grids.size() > 1) {
            ValueRange t = activeRange(loadFloatGrid(path, "temperature"));
            EXPECT_GE(t.lo, 299.f);
            if (std::string(e.kind).rfind("smoke", 0) == 0) {
                EXPECT_LE(t.hi, 900.f);
                EXPECT_GT(t.hi, 750.f);
            } else {
                EXPECT_LE(t.hi, 1800.f);
                EXPECT_GT(t.hi, 1500.f);
                ValueRange f = activeRange(loadFloatGrid(path, "flame"));
                EXPECT_GT(f.lo, 0.f);
                EXPECT_LE(f.hi, 1.f);
                EXPECT_GT(f.hi, 0.8f);
            }
        }
    }
}

// The demo's plume: flames at its foot only, and smoke whose top is the rounded cap (an
// ellipsoid's upper half centred at 1.45 m, 0.3 m high, its edge moved out by at most 0.62 of
// it: below 1.94 m), not the domain's lid at 2 m.
TEST(Asset, PlumeHasFlamesAtItsFootAndARoundedCap) {
    const std::string path = test::tempDir() + "/plume.vdb";
    writeProceduralAsset("plume", path, 64, 7);
    const VdbFileInfo info = inspectVdbFile(path);
    ASSERT_EQ(info.grids.size(), 4u);
    EXPECT_LT(info.grids[2].objectBounds.hi.y, 1.3f);              // flame
    EXPECT_LT(info.grids[0].objectBounds.hi.y, 1.94f + 2.f / 64);  // + a voxel
    EXPECT_GT(info.grids[0].objectBounds.hi.y, 1.45f);
    // Wider at the cap than just above the flames: the column spreads as it rises.
    EXPECT_GT(info.grids[0].objectBounds.hi.x - info.grids[0].objectBounds.lo.x, 0.5f);
}

TEST(Asset, FogSphereIsTheDocumentedSoftSphere) {
    const std::string path = test::tempDir() + "/sphere.vdb";
    writeProceduralAsset("fog-sphere", path, 64, 1);
    FloatGrid g = loadFloatGrid(path, "density");
    auto acc = g.accessor();
    EXPECT_NEAR(g.sample(acc, Vec3(0.f, 1.f, 0.f)), 1.f, 1e-6f);
    EXPECT_NEAR(g.sample(acc, Vec3(0.3f, 1.2f, -0.2f)), 1.f, 1e-6f);
    // Halfway through the falloff (r = 0.8 m) smoothstep gives ½.
    EXPECT_NEAR(g.sample(acc, Vec3(0.8f, 1.f, 0.f)), 0.5f, 0.02f);
    EXPECT_EQ(g.sample(acc, Vec3(0.f, 2.2f, 0.f)), 0.f);
    EXPECT_EQ(g.sample(acc, Vec3(0.9f, 1.f, 0.9f)), 0.f);
}

// `smoke-sphere` is `smoke` deflected about a ball of radius a = 0.1 m at (0, 0.75, 0) by
// potential flow: below the ball's equator each point reads the plume at the lateral offset its
// streamline had upstream, the ρ∞ that keeps Stokes's stream function ψ = ½ U ρ² (1 − a³/r³)
// (Lamb 1932, §96) at its value there; nothing inside the ball; above it the documented wake,
// 1 − 0.85 e^(−h/0.45 m) of the deflected plume on the ball's axis at height h over its centre.
TEST(Asset, SmokeSphereIsThePlumeDeflectedAboutTheBall) {
    const AssetField past = proceduralField("smoke-sphere", 7), plume = proceduralField("smoke", 7);
    const Vec3 c(0.f, 0.75f, 0.f);
    const float a = 0.1f;
    float out[2], ref[2];
    for (const Vec3& p : {c, c + Vec3(0.06f, 0.04f, -0.03f), c + Vec3(0.f, -0.099f, 0.f)}) {
        past.eval(p, out);
        EXPECT_EQ(out[0], 0.f) << "inside the ball";
    }
    int compared = 0;
    for (const Vec3& d :
         {Vec3(0.16f, -0.02f, 0.f), Vec3(0.1f, -0.15f, 0.08f), Vec3(-0.2f, -0.1f, 0.1f),
          Vec3(0.05f, -0.3f, -0.12f), Vec3(0.25f, -0.05f, 0.2f)}) {
        const float r = length(d), rho2 = d.x * d.x + d.z * d.z;
        const float rhoUp2 = rho2 * (1.f - a * a * a / (r * r * r));  // ψ(ρ∞, ∞) = ψ(ρ, r)
        const float s = std::sqrt(rhoUp2 / rho2);
        past.eval(c + d, out);
        plume.eval(Vec3(d.x * s, c.y + d.y, d.z * s), ref);
        EXPECT_NEAR(out[0], ref[0], 1e-5f) << d.x << " " << d.y << " " << d.z;
        compared += ref[0] > 0.f ? 1 : 0;
        // Pulled in towards the ball's axis: the deflected smoke reaches farther out.
        EXPECT_LT(rhoUp2, rho2);
    }
    EXPECT_GE(compared, 3) << "most points read smoke";
    for (const float h : {0.2f, 0.4f, 0.8f}) {
        past.eval(c + Vec3(0.f, h, 0.f), out);
        plume.eval(c + Vec3(0.f, h, 0.f), ref);  // on the axis ρ∞ = ρ = 0
        if (ref[0] > 0.f) {
            EXPECT_NEAR(out[0] / ref[0], 1.f - 0.85f * std::exp(-h / 0.45f), 1e-4f) << h;
        }
    }
    // Every point holding smoke lies in a box the writer evaluates.
    for (float x = -0.6f; x <= 0.6f; x += 0.05f)
        for (float y = 0.3f; y <= 1.2f; y += 0.05f) {
            const Vec3 p(x, y, 0.02f);
            past.eval(p, out);
            if (out[0] > 0.f) {
                EXPECT_TRUE(past.mayCover(p - Vec3(0.01f), p + Vec3(0.01f))) << x << " " << y;
            }
        }
}

TEST(Asset, OceanIsAChlorophyllPlumeInMgPerCubicMetre) {
    const std::string path = test::tempDir() + "/ocean.vdb";
    writeProceduralAsset("ocean", path, 48, 1);
    VdbFileInfo info = inspectVdbFile(path);
    ASSERT_EQ(info.grids.size(), 1u);
    EXPECT_EQ(info.grids[0].name, "chlorophyll");
    EXPECT_EQ(info.grids[0].gridClass, "fog volume");
    EXPECT_GT(info.grids[0].objectBounds.lo.y, -0.01f);
    EXPECT_LT(info.grids[0].objectBounds.hi.y, 2.01f);
    FloatGrid g = loadFloatGrid(path, "chlorophyll");
    ValueRange c = activeRange(g);
    // Bloom core to open-ocean rim: up to 10 mg/m³, nothing below 0.01 stored.
    EXPECT_GE(c.lo, 0.01f);
    EXPECT_GT(c.hi, 5.f);
    EXPECT_LE(c.hi, 10.f);
    EXPECT_GT(c.active, 1000u);
    EXPECT_LT(c.active, uint64_t(48) * 48 * 48 / 2);  // a plume, not a filled box
}

TEST(Asset, BadKindListsTheValidKinds) {
    const std::string path = test::tempDir() + "/x.vdb";
    try {
        writeProceduralAsset("smokey", path, 32, 1);
        ADD_FAILURE() << "no error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "'smokey' (valid kinds: smoke, smoke-sphere, fire, plume, fog-sphere, ocean, pyro)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(writeProceduralAsset("smoke", path, 2, 1), MirageError);
    EXPECT_FALSE(fs::exists(path));
}

TEST(Asset, WritesAtomicallyAndLeavesNoTemporaryFiles) {
    const std::string dir = test::tempDir();
    const std::string path = dir + "/smoke.vdb";
    writeProceduralAsset("smoke", path, 16, 1);
    writeProceduralAsset("smoke", path, 24, 2);  // replaces the first
    EXPECT_EQ(inspectVdbFile(path).grids.at(0).indexMax[1], 23);

    // A destination that cannot be replaced (a folder) or whose folder is missing: an error,
    // and nothing left behind.
    fs::create_directory(dir + "/taken.vdb");
    EXPECT_THROW(writeProceduralAsset("fog-sphere", dir + "/taken.vdb", 16, 1), MirageError);
    EXPECT_THROW(writeProceduralAsset("fog-sphere", dir + "/missing/x.vdb", 16, 1), MirageError);
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
    EXPECT_EQ(files, 2);
}

}  // namespace
}  // namespace mirage
