// The bad-input matrix (docs/hostile-input.md): every broken file, wrong grid and absurd
// scene value must give one MirageError that names the file (and line, for scenes), the key or
// grid, and what was expected, in a single bounded line; none may crash. Through the library
// (loadScene, loadFloatGrid) for speed; a few cases through the `mirage` binary for the exit
// code and the single `mirage: error:` line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "film/color.h"
#include "medium/medium.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"
#include "volume/vdb_file.h"

using namespace mirage;

namespace {

constexpr size_t kMaxMessage = 400;  // characters besides the test's temporary folder
std::string gTempDir;                // that folder, not counted: users' paths are their own

std::string writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// One clear message: every needle present, a single line, bounded length.
void expectClearMessage(const std::string& msg, const std::vector<std::string>& needles,
                        const std::string& what) {
    EXPECT_FALSE(msg.empty()) << what << ": no error";
    for (const std::string& n : needles)
        EXPECT_NE(msg.find(n), std::string::npos) << what << ": '" << n << "' missing in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << what << ": several lines: " << msg;
    std::string counted = msg;
    for (size_t at; !gTempDir.empty() && (at = counted.find(gTempDir)) != std::string::npos;)
        counted.erase(at, gTempDir.size());
    EXPECT_LE(counted.size(), kMaxMessage) << what << ": " << msg;
}

std::string sceneError(const std::string& path) {
    static ColorPipeline color;
    try {
        loadScene(path, LoadOptions{}, color);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

std::string gridError(const std::string& path, const std::string& grid = "density") {
    try {
        loadFloatGrid(path, grid);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

// A good fog volume: 6³ voxels of density 1.
TestGridSpec goodSpec() {
    TestGridSpec s;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k) s.voxels.push_back({i, j, k, 1.0});
    return s;
}

std::string sceneFor(const std::string& vdbFile, const std::string& extra = "",
                     const std::string& shader = "smoke") {
    return "[film]\nresolution = [8, 8]\nspp = 1\n\n[[volume]]\nfile = \"" + vdbFile +
           "\"\nshader = \"" + shader + "\"\n" + extra +
           "\n[[light]]\ntype = \"distant\"\ndirection = [0, -1, 0]\nirradiance = 100.0\n";
}

class BadInput : public testing::Test {
protected:
    void SetUp() override {
        dir = test::tempDir();
        gTempDir = dir;
        good = dir + "/good.vdb";
        writeTestGrid(good, goodSpec());
    }
    std::string scene(const std::string& name, const std::string& text) {
        return writeFile(dir + "/" + name, text);
    }
    std::string dir, good;
};

}  // namespace

// ---- Files: missing, empty, truncated, corrupt, not a VDB --------------------------------

TEST_F(BadInput, MissingEmptyAndNonVdbFilesNameTheFile) {
    struct Case {
        std::string name, bytes, expect;
    };
    const std::vector<Case> cases = {
        {"empty.vdb", "", "empty"},
        {"text.vdb", "density = 1\nthis is not a volume\n", ""},
        {"png.vdb", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), ""},
        {"zeros.vdb", std::string(4096, '\0'), ""},
        {"scene.vdb", sceneFor("good.vdb"), ""},
    };
    for (const Case& c : cases) {
        std::string path = writeFile(dir + "/" + c.name, c.bytes);
        std::vector<std::string> needles{path};
        if (!c.expect.empty()) needles.push_back(c.expect);
        expectClearMessage(gridError(path), needles, c.name);
        // Through a scene: the scene's line of `file` and the file itself.
        std::string s = scene("uses_" + c.name + ".toml", sceneFor(c.name));
        expectClearMessage(sceneError(s), {c.name}, "scene using " + c.name);
    }
    std::string absent = dir + "/absent.vdb";
    expectClearMessage(gridError(absent), {absent}, "missing file");
    std::string s = scene("missing.toml", sceneFor("absent.vdb"));
    expectClearMessage(sceneError(s), {s + ":6:8", "not found", "absent.vdb"}, "missing in scene");
    expectClearMessage(sceneError(dir + "/absent.toml"), {"absent.toml", "cannot open"},
                       "missing scene");
}

TEST_F(BadInput, TruncatedFilesNeverLoadAndNeverCrash) {
    const std::string bytes = readBytes(good);
    ASSERT_GT(bytes.size(), 64u);
    for (size_t keep : {size_t(1), size_t(4), size_t(8), size_t(20), size_t(64),
                        bytes.size() / 2, bytes.size() - 16, bytes.size() - 1}) {
        std::string path =
            writeFile(dir + "/cut" + std::to_string(keep) + ".vdb", bytes.substr(0, keep));
        expectClearMessage(gridError(path), {path}, "truncated to " + std::to_string(keep));
    }
}

TEST_F(BadInput, CorruptBytesEitherLoadSanitisedOrFailClearly) {
    // Flipping bytes anywhere: the header checks, OpenVDB's reader and the voxel rule between
    // them must give a clean grid or one clear error, whatever is hit. It runs under ASan too:
    // the tree walk (vdb_tree.h) refuses a flipped block size before OpenVDB allocates it.
    const std::string bytes = readBytes(good);
    int loaded = 0, refused = 0;
    for (size_t at = 0; at < bytes.size(); at += std::max<size_t>(1, bytes.size() / 97)) {
        std::string broken = bytes;
        broken[at] = char(~broken[at]);
        std::string path = writeFile(dir + "/flip.vdb", broken);
        testing::internal::CaptureStderr();
        try {
            FloatGrid g = loadFloatGrid(path, "density");
            EXPECT_TRUE(std::isfinite(g.maxValue()) && g.maxValue() >= 0.f) << "byte " << at;
            EXPECT_LE(g.maxValue(), kMaxVoxelValue) << "byte " << at;
            ++loaded;
        } catch (const MirageError& e) {
            expectClearMessage(e.what(), {path}, "flipped byte " + std::to_string(at));
            ++refused;
        }
        testing::internal::GetCapturedStderr();
    }
    EXPECT_GT(loaded + refused, 90);
}

// ---- Wrong grid types --------------------------------------------------------------------

TEST_F(BadInput, WrongGridTypesNameTheGridAndWhatWasExpected) {
    struct Case {
        std::string name;
        TestGridSpec spec;
        std::string expect;
    };
    TestGridSpec vec = goodSpec(), flags = goodSpec(), sdf = goodSpec(), stag = goodSpec();
    vec.valueType = "vec3s";
    for (auto& v : vec.voxels) v.vector = Vec3d(1.0, 0.0, 0.0);
    flags.valueType = "bool";
    sdf.gridClass = "level set";
    sdf.background = 0.3;
    stag.gridClass = "staggered";
    const std::vector<Case> cases = {{"vector", vec, "vec3s"},
                                     {"bool", flags, "bool"},
                                     {"levelset", sdf, "level set"},
                                     {"staggered", stag, "staggered"}};
    for (const Case& c : cases) {
        std::string path = dir + "/" + c.name + ".vdb";
        writeTestGrid(path, c.spec);
        expectClearMessage(gridError(path), {path, "'density'", c.expect, "expected"}, c.name);
        std::string s = scene(c.name + ".toml", sceneFor(c.name + ".vdb"));
        expectClearMessage(sceneError(s), {c.name + ".vdb", "'density'", c.expect},
                           "scene with " + c.name);
    }
    // A grid that is not in the file: the error lists the grids that are.
    std::string s = scene("nogrid.toml", sceneFor("good.vdb", "bind = { density = \"smoke\" }\n"));
    expectClearMessage(sceneError(s), {"'smoke'", "density"}, "absent grid");
}

// ---- Scene files: unknown keys, wrong types, absurd values -------------------------------

TEST_F(BadInput, UnknownKeysAnywhereAreNamedWithLineAndColumn) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"[film]\nresolutoin = [8, 8]\n", "resolutoin"},
        {"[render]\nintegator = \"volpath\"\n", "integator"},
        {"[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_deg = 30\n", "fov_deg"},
        {"[output]\npth = \"x.exr\"\n", "pth"},
        {"[films]\nspp = 4\n", "films"},
        {"[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\npowr = 5.0\n", "powr"},
        {sceneFor("good.vdb", "densty_scale = 2.0\n"), "densty_scale"},
        {sceneFor("good.vdb", "transform = { scael = 2.0 }\n"), "scael"},
    };
    int i = 0;
    for (const auto& [text, key] : cases) {
        std::string s = scene("unknown" + std::to_string(i++) + ".toml", text);
        expectClearMessage(sceneError(s), {s + ":", "unknown key '" + key + "'"}, key);
    }
}

TEST_F(BadInput, WrongTypesNameTheKeyAndTheExpectedType) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"[film]\nresolution = \"big\"\n", "resolution"},
        {"[film]\nspp = 1.5\n", "spp"},
        {"[film]\nspp = \"many\"\n", "spp"},
        {"[render]\nmax_depth = [1, 2]\n", "max_depth"},
        {"[output]\nhalf = 3\n", "half"},
        {"[[light]]\ntype = \"distant\"\ndirection = \"down\"\n", "direction"},
        {"[[light]]\ntype = 7\n", "type"},
        {sceneFor("good.vdb", "density_scale = \"thick\"\n"), "density_scale"},
        {"film = 3\n", "film"},
    };
    int i = 0;
    for (const auto& [text, key] : cases) {
        std::string s = scene("type" + std::to_string(i++) + ".toml", text);
        expectClearMessage(sceneError(s), {s + ":", key, "expected"}, key);
    }
}

TEST_F(BadInput, AbsurdValuesAreRefusedOrBounded) {
    const std::vector<std::pair<std::string, std::string>> refused = {
        {"[film]\nresolution = [-4, 10]\n", "resolution"},
        {"[film]\nresolution = [0, 0]\n", "resolution"},
        {"[film]\nresolution = [1e9, 1e9]\n", "resolution"},
        {"[film]\nspp = 0\n", "spp"},
        {"[film]\nspp = -3\n", "spp"},
        {"[film]\ntile_size = 0\n", "tile_size"},
        {"[render]\nmax_depth = 0\n", "max_depth"},
        {"[render]\nmajorant_resolution = 1000000000\n", "majorant_resolution"},
        {"[render]\nphotons = -1\n", "photons"},
        {"[render]\nk = -5\n", "k"},
        {"[render]\nintegrator = \"magic\"\n", "integrator"},
        {"[render]\nsampler = \"halton\"\n", "sampler"},
        {"[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 5]\n", "look_at"},
        {"[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 0\n", "fov"},
        {"[camera]\nposition = [0, 0, nan]\nlook_at = [0, 0, 0]\n", "position"},
        {"[[light]]\ntype = \"distant\"\ndirection = [0, -1, 0]\nirradiance = -5.0\n",
         "irradiance"},
        {"[[light]]\ntype = \"distant\"\ndirection = [0, -1, 0]\nirradiance = inf\n",
         "irradiance"},
        {"[[light]]\ntype = \"distant\"\ndirection = [0, 0, 0]\n", "direction"},
        {"[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\ntemperature = -100\n",
         "temperature"},
        {"[[light]]\ntype = \"laser\"\n", "type"},
        {"[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\nradius = -0.1\n", "radius"},
        {"[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n"
         "radius = nan\n",
         "radius"},
        {"[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\nies = \"absent.ies\"\n", "absent.ies"},
        {"[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n",
         "direction"},
        {sceneFor("good.vdb", "density_scale = -1.0\n"), "density_scale"},
        {sceneFor("good.vdb", "density_scale = 1e300\n"), "density_scale"},
        {sceneFor("good.vdb", "transform = { scale = 0.0 }\n"), "scale"},
        {sceneFor("good.vdb", "transform = { scale = 1e-300 }\n"), "scale"},
        {sceneFor("good.vdb", "transform = { scale = [1, 1e300, 1] }\n"), "scale"},
        {sceneFor("good.vdb", "transform = { rotate = [30, 0, 0, 0] }\n"), "rotate"},
        {sceneFor("good.vdb", "transform = { translate = [1e300, 0, 0] }\n"), "translate"},
        {sceneFor("good.vdb", "", "no_such_shader"), "no_such_shader"},
    };
    int i = 0;
    for (const auto& [text, key] : refused) {
        std::string s = scene("absurd" + std::to_string(i++) + ".toml", text);
        expectClearMessage(sceneError(s), {s + ":", key}, text);
    }
    // 1e9 photons loads (the count is legal; whether it fits in memory is the memory budget's
    // question, not the parser's) and is kept exactly, not wrapped or truncated.
    std::string s = scene("photons.toml", "[render]\nintegrator = \"photon\"\nphotons = 1e9\n");
    std::string msg = sceneError(s);
    if (!msg.empty()) expectClearMessage(msg, {s + ":", "photons"}, "1e9 photons");
    s = scene("photons_int.toml",
              "[render]\nintegrator = \"photon\"\nphotons = 1000000000\n" + sceneFor("good.vdb"));
    ColorPipeline color;
    Scene loaded = loadScene(s, LoadOptions{}, color);
    EXPECT_EQ(loaded.photon.photons, 1000000000u);
}

TEST_F(BadInput, MalformedIesFileIsNamedWithItsLineAndTheKey) {
    scene("bad.ies",
          "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n"
          "1 oops 1\n");
    const std::string s = scene("ies.toml",
                                "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\n"
                                "direction = [0, -1, 0]\nies = \"bad.ies\"\n");
    expectClearMessage(sceneError(s), {s + ":", "ies", "bad.ies:7", "candela", "'oops'"},
                       "malformed IES file");
}

TEST_F(BadInput, OverflowingCoefficientProductIsRefusedNamingTheGrid) {
    // A voxel at the ceiling (1e30 clamped to 1e10 by the voxel rule) × density_scale 1e12 ×
    // a cross-section of 1e10 m²-per-unit: σt = 1e32 1/m, above the 1e30 limit. Every factor
    // is legal alone; the product is not.
    TestGridSpec spec = goodSpec();
    spec.voxels[0].value = 1e30;
    writeTestGrid(dir + "/huge.vdb", spec);
    scene("dense.toml", "name = \"dense\"\n[[component]]\nname = \"soot\"\ngrid = \"density\"\n"
                        "sigma_a = 1e10\nsigma_s = 0.0\n");
    std::string s = scene("overflow.toml", sceneFor("huge.vdb", "density_scale = 1e12\n", "dense"));
    testing::internal::CaptureStderr();
    std::string msg = sceneError(s);
    std::string warning = testing::internal::GetCapturedStderr();
    expectClearMessage(msg, {s + ":6:8", "huge.vdb", "shader 'dense'", "grid 'density'", "1e+30"},
                       "σ overflow");
    EXPECT_NE(warning.find("clamped"), std::string::npos) << warning;
}

// ---- The command itself: exit codes and one line ---------------------------------------

TEST_F(BadInput, CommandExitsNonZeroWithOneBoundedLine) {
    struct Case {
        std::string args, needle;
        int code;
    };
    std::string bad = writeFile(dir + "/junk.vdb", std::string(100, '\x7f'));
    std::string spp = scene("spp.toml", "[film]\nspp = 0\n");
    std::string ok = scene("ok.toml", sceneFor("good.vdb"));
    const std::vector<Case> cases = {
        {"render '" + bad + "' -o '" + dir + "/a.exr' --quiet", "junk.vdb", 1},
        {"render '" + spp + "' -o '" + dir + "/b.exr' --quiet", "spp", 1},
        {"render '" + dir + "/absent.toml' -o '" + dir + "/c.exr' --quiet", "absent.toml", 1},
        {"render '" + ok + "' --resolution -3x5 -o '" + dir + "/d.exr' --quiet", "resolution",
         1},
    };
    for (const Case& c : cases) {
        std::string log;
        int code = test::runMirage(c.args, &log);
        EXPECT_EQ(code, c.code) << c.args << "\n" << log;
        EXPECT_EQ(log.rfind("mirage: error:", 0), 0u) << log;
        expectClearMessage(log.substr(0, log.size() - (log.back() == '\n')), {c.needle}, c.args);
    }
    for (const char* out : {"a", "b", "c", "d"})
        EXPECT_FALSE(std::filesystem::exists(dir + "/" + out + ".exr")) << out;
    // Command-line syntax: exit 2, and a range that fits on a line (a negative seed used to
    // print the 309-digit maximum of a double).
    std::string log;
    EXPECT_EQ(test::runMirage("render '" + ok + "' --seed -5 -o '" + dir + "/e.exr'", &log), 2);
    EXPECT_NE(log.find("--seed"), std::string::npos) << log;
    EXPECT_LT(log.size(), 200u) << log;
}

// A bare VDB has no scene file: --set reaches [film], [render] and [output] and nothing else.
// (It used to be ignored altogether: `render smoke.vdb --set film.spp=0` rendered at 16 spp.)
TEST_F(BadInput, SetOnABareVolumeIsAppliedOrRefused) {
    ColorPipeline color;
    Scene s = loadScene(good, LoadOptions{1, {"film.spp=3", "render.integrator=volpath"}}, color);
    EXPECT_EQ(s.settings.spp, 3);
    EXPECT_EQ(s.integrator, "volpath");
    EXPECT_EQ(s.output.path, "good.exr");
    auto error = [&](const std::string& o) {
        try {
            loadScene(good, LoadOptions{1, {o}}, color);
        } catch (const MirageError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    expectClearMessage(error("film.spp=0"), {"--set", "good.vdb", "spp", "1 to"}, "spp 0");
    expectClearMessage(error("nope.key=1"), {"--set", "unknown key 'nope'", "film, render, output"},
                       "unknown key");
    expectClearMessage(error("light.0.color=[1,0,0]"), {"unknown key 'light'"}, "light");
}

// Emission: a temperature grid clamped at the voxel ceiling (1e10 K), intensity 1e12 and a
// dense medium multiply σa·Le past 1e30: refused naming the temperature grid, instead of every
// emitting sample overflowing to ∞ and being dropped.
TEST(BadInputLibrary, OverflowingEmissionIsRefusedNamingTheTemperatureGrid) {
    ShaderDesc s;
    s.name = "furnace";
    MediumComponent c;
    c.name = "soot";
    c.grid = "density";
    c.sigmaA = Spectrum(1.f);
    s.components.push_back(c);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    e.intensity = 1e12f;
    s.emission = e;
    auto dense = [](int, int, int) { return 1e6f; };
    auto hot = [](int, int, int) { return kMaxVoxelValue; };
    std::vector<FloatGrid> grids{test::makeGrid(dense, 0, 3, 0.1, Vec3d(0.0), "density"),
                                 test::makeGrid(hot, 0, 3, 0.1, Vec3d(0.0), "temperature")};
    try {
        Medium m(s, grids, Transform(), 1.f, 4);
        ADD_FAILURE() << "σa·Le beyond float range was accepted";
    } catch (const MirageError& err) {
        expectClearMessage(err.what(), {"shader 'furnace'", "emission", "grid 'temperature'"},
                           "emission overflow");
    }
    // The same medium at 1e5 K is legal.
    grids[1] = test::makeGrid([](int, int, int) { return 1e5f; }, 0, 3, 0.1, Vec3d(0.0),
                              "temperature");
    EXPECT_NO_THROW(Medium(s, grids, Transform(), 1.f, 4));
}

// Defects the matrix found in the scene loader: a directory parsed as an empty scene and
// rendered black; "#N" bindings past the file's grids failed later without the scene line; a
// shader file next to a scene given relative to the working directory was not found.
TEST_F(BadInput, DirectoriesOutOfRangeIndicesAndShadersNextToARelativeScene) {
    std::filesystem::create_directories(dir + "/folder");
    expectClearMessage(sceneError(dir + "/folder"), {dir + "/folder", "is a directory"},
                       "directory as scene");
    for (const std::string index : {"#1", "#-1", "#99999999999999999999"}) {
        std::string s = scene("index.toml",
                              sceneFor("good.vdb", "bind = { density = \"" + index + "\" }\n"));
        expectClearMessage(sceneError(s), {s + ":6:8", "no grid '" + index + "'", "'density'"},
                           index);
    }
    scene("grey.toml", "name = \"grey\"\n[[component]]\nname = \"soot\"\ngrid = \"density\"\n"
                       "sigma_a = 0.5\nsigma_s = 0.5\n");
    scene("grey_scene.toml", sceneFor("good.vdb", "", "grey"));
    std::string log;
    EXPECT_EQ(test::runCommand("cd '" + dir + "' && '" + test::mirageBinary() + "' info grey_scene.toml",
                               &log),
              0)
        << log;
    EXPECT_NE(log.find("shader 'grey'"), std::string::npos) << log;
}
