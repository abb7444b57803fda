// Scene files: errors name the file, line and column; overrides; frame patterns; and the
// command end to end (a scene and a bare VDB render to finite, non-black EXRs).
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "film/color.h"
#include "film/image_io.h"
#include "frame/frame_settings.h"
#include "scene/toml_reader.h"
#include "test_support.h"

using namespace mirage;

namespace {

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    std::string p = dir + "/" + name;
    std::ofstream(p) << text;
    return p;
}

// A fog sphere made by `mirage make-asset`, shared by the tests of this file.
std::string fogAsset(const std::string& dir) {
    std::string vdb = dir + "/fog.vdb";
    std::string out;
    EXPECT_EQ(0, test::runMirage("make-asset fog-sphere -o '" + vdb + "' --resolution 24", &out))
        << out;
    return vdb;
}

std::string loadError(const std::string& scenePath) {
    ColorPipeline color;
    try {
        loadScene(scenePath, LoadOptions{}, color);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

const char* kGoodScene = R"(
[film]
resolution = [32, 24]
spp = 2

[[volume]]
file = "fog.vdb"
shader = "smoke"
density_scale = 20.0

[[light]]
type = "distant"
direction = [1, -1, -1]
irradiance = 1500.0
)";

}  // namespace

TEST(SceneErrors, UnknownKeyNamesFileLineAndColumn) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string p =
        writeFile(dir, "s.toml",
                  std::string(kGoodScene) +
                      "\n[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfvo = 30\n");
    std::string msg = loadError(p);
    EXPECT_NE(msg.find(p + ":19:1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unknown key 'fvo'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("fov"), std::string::npos) << msg;  // the expected keys are listed
}

TEST(SceneErrors, WrongTypeAndRangeAreReportedWithLocation) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string p = writeFile(dir, "type.toml", "[film]\nspp = \"many\"\n");
    std::string msg = loadError(p);
    EXPECT_NE(msg.find(p + ":2:7"), std::string::npos) << msg;
    EXPECT_NE(msg.find("expected an integer"), std::string::npos) << msg;

    p = writeFile(dir, "range.toml", "[film]\nresolution = [-4, 10]\n");
    msg = loadError(p);
    EXPECT_NE(msg.find(p + ":2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("resolution"), std::string::npos) << msg;
}

TEST(SceneErrors, SyntaxErrorAndMissingFiles) {
    std::string dir = test::tempDir();
    std::string p = writeFile(dir, "syntax.toml", "[film]\nspp = = 3\n");
    std::string msg = loadError(p);
    EXPECT_NE(msg.find(p + ":2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("TOML syntax error"), std::string::npos) << msg;

    p = writeFile(dir, "missing.toml", "[[volume]]\nfile = \"nope.vdb\"\n");
    msg = loadError(p);
    EXPECT_NE(msg.find(p + ":2:8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not found"), std::string::npos) << msg;

    EXPECT_NE(loadError(dir + "/absent.toml").find("cannot open"), std::string::npos);
}

// A path the file system cannot even look up (a name past its 255-byte limit) is one message
// naming the key, like a missing file; std::filesystem::exists would throw past the loader.
TEST(SceneErrors, UnreadablePathsAreOneMessageNamingTheKey) {
    const std::string dir = test::tempDir();
    const std::string longName(300, 'x');
    const std::string volume =
        writeFile(dir, "long_volume.toml", "[[volume]]\nfile = \"" + longName + ".vdb\"\n");
    std::string msg = loadError(volume);
    EXPECT_NE(msg.find(volume + ":2:8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("volume file unreadable (File name too long)"), std::string::npos) << msg;

    fogAsset(dir);
    const std::string shader =
        writeFile(dir, "long_shader.toml",
                  "[[volume]]\nfile = \"fog.vdb\"\nshader = \"" + longName + ".toml\"\n");
    msg = loadError(shader);
    EXPECT_NE(msg.find("shader file unreadable (File name too long)"), std::string::npos) << msg;

    const std::string mesh =
        writeFile(dir, "long_mesh.toml",
                  "[[material]]\nname = \"white\"\ntype = \"diffuse\"\n"
                  "[[shape]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"" +
                      longName + ".obj\"\n");
    msg = loadError(mesh);
    EXPECT_NE(msg.find("mesh file unreadable (File name too long)"), std::string::npos) << msg;
}

TEST(SceneErrors, MissingGridNamesTheSlotAndTheGridsPresent) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string p =
        writeFile(dir, "grid.toml", "[[volume]]\nfile = \"fog.vdb\"\nshader = \"fire\"\n");
    std::string msg = loadError(p);
    EXPECT_NE(msg.find("flame"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'density'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(p + ":2:"), std::string::npos) << msg;
}

TEST(SceneLoad, OverridesAndFramePatterns) {
    EXPECT_EQ(expandFramePattern("smoke.$F4.vdb", 7), "smoke.0007.vdb");
    EXPECT_EQ(expandFramePattern("smoke.$F.vdb", 12), "smoke.12.vdb");
    EXPECT_EQ(expandFramePattern("out.####.exr", 3), "out.0003.exr");
    EXPECT_FALSE(hasFramePattern("plain.exr"));
    // Pads wider than 32 digits are typos, refused before any string is built (the scene
    // fuzzer found `$F888888888`, an int overflow and a gigabyte of zeros).
    EXPECT_EQ(expandFramePattern("f.$F32.vdb", 5).size(), 32u + 6u);
    EXPECT_THROW(expandFramePattern("f.$F33.vdb", 5), MirageError);
    EXPECT_THROW(expandFramePattern("f.$F888888888.vdb", 5), MirageError);
    EXPECT_THROW(expandFramePattern("f." + std::string(33, '#') + ".vdb", 5), MirageError);

    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string wide =
        writeFile(dir, "wide.toml", "[[volume]]\nfile = \"fog.$F99999999999.vdb\"\n");
    std::string wideMsg = loadError(wide);
    EXPECT_NE(wideMsg.find(wide + ":2:"), std::string::npos) << wideMsg;
    EXPECT_NE(wideMsg.find("32 digits"), std::string::npos) << wideMsg;

    std::string p = writeFile(dir, "ok.toml", kGoodScene);
    ColorPipeline color;
    Scene s = loadScene(p, LoadOptions{1, {"film.spp=7", "volume.0.density_scale=3"}}, color);
    EXPECT_EQ(s.settings.spp, 7);
    EXPECT_EQ(s.settings.width, 32);
    EXPECT_FLOAT_EQ(s.volumes[0].densityScale, 3.f);
    ASSERT_EQ(s.render.media.size(), 1u);
    ASSERT_EQ(s.render.lights.size(), 1u);
    EXPECT_THROW(loadScene(p, LoadOptions{1, {"nothing.here.0.x=1"}}, color), MirageError);

    bool emission = true;
    for (const auto& t : s.physics())
        if (t.name == "emission") emission = t.active;
    EXPECT_FALSE(emission);  // smoke does not emit: the term is off and says why
}

// `mirage info` says how volpath's camera rays find a dome: points of their own weighed against
// delta tracking's, forking paths in a plain medium under domes alone
// (render/lamp_sampling.h), and nothing of the kind with lamp_sampling = "distance".
TEST(SceneLoad, InfoSaysHowCameraRaysFindTheDome) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string p = writeFile(dir, "sky.toml",
                              "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\n"
                              "[[light]]\ntype = \"dome\"\ncolor = [1, 1, 1]\n");
    ColorPipeline color;
    auto reason = [&](std::vector<std::string> sets) {
        sets.push_back("render.integrator=volpath");
        const Scene s = loadScene(p, LoadOptions{1, sets}, color);
        for (const auto& t : s.physics())
            if (t.name == "single scattering") return t.why;
        return std::string();
    };
    EXPECT_NE(reason({}).find("starting a path of its own"), std::string::npos)
        << reason({});
    EXPECT_EQ(reason({"render.lamp_sampling=distance"}).find("points"), std::string::npos);
}

// `mirage info` says when volpath's continuations head towards a lamp inside the medium
// (render/light_lobes.h): a point light in the middle of the fog ball, not one far outside it,
// nor with lamp_sampling = "distance".
TEST(SceneLoad, InfoSaysWhenContinuationsHeadTowardsALampInside) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    auto reason = [&](const std::string& position, std::vector<std::string> sets) {
        const std::string p = writeFile(dir, "lamp.toml",
                                        "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\n"
                                        "[[light]]\ntype = \"point\"\nposition = " +
                                            position + "\npower = 100\n");
        sets.push_back("render.integrator=volpath");
        ColorPipeline color;
        const Scene s = loadScene(p, LoadOptions{1, sets}, color);
        for (const auto& t : s.physics())
            if (t.name == "multiple scattering") return t.why;
        return std::string();
    };
    const std::string inside = reason("[0, 1, 0]", {});
    EXPECT_NE(inside.find("drawn towards the 1 lamp(s) inside the media"), std::string::npos)
        << inside;
    EXPECT_EQ(reason("[5, 1, 0]", {}).find("towards"), std::string::npos);
    EXPECT_EQ(reason("[0, 1, 0]", {"render.lamp_sampling=distance"}).find("towards"),
              std::string::npos);
}

// `mirage info` says when volpath's paths are guided by lobe walks (render/light_lobes.h): a
// cloud's forward medium (g = 0.85, albedo 0.99: a walk from a quarter of the vertices) under a
// sun, not the isotropic smoke under it, nor the cloud under a uniform dome (no lobe).
TEST(SceneLoad, InfoSaysWhenPathsAreGuided) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    writeFile(dir, "cloud.toml",
              "name = \"cloud\"\n[[component]]\ngrid = \"density\"\nsigma_a = 0.01\n"
              "sigma_s = 0.99\ng = 0.85\n");
    auto reason = [&](const std::string& shader, const std::string& light) {
        const std::string p = writeFile(
            dir, "guided.toml",
            "[[volume]]\nfile = \"fog.vdb\"\nshader = \"" + shader + "\"\n[[light]]\n" + light);
        ColorPipeline color;
        const Scene s = loadScene(p, LoadOptions{1, {"render.integrator=volpath"}}, color);
        for (const auto& t : s.physics())
            if (t.name == "multiple scattering") return t.why;
        return std::string();
    };
    const std::string sun = "type = \"sun\"\ndirection = [0, -1, 0]\nirradiance = 1\n";
    const std::string cloud = reason("cloud.toml", sun);
    EXPECT_NE(cloud.find("paths guided (a forward phase function): 25 % of medium vertices"),
              std::string::npos)
        << cloud;
    EXPECT_EQ(reason("smoke", sun).find("guided"), std::string::npos);
    EXPECT_EQ(reason("cloud.toml", "type = \"dome\"\ncolor = [1, 1, 1]\n").find("guided"),
              std::string::npos);
    // A sky map with a sun (a pixel of 300 in a sky of 0.2, flat RGBE scanlines): its samples
    // are drawn at a rate from the sun's shade over the media (render/sun_shade.h); not under a
    // distant sun.
    test::writeSunnySky(dir);
    const std::string shaded = "; medium vertices draw the sky's own samples at a rate from the "
                               "sun's optical depth over the media (a 64³ grid: every vertex "
                               "where it is lit, 10 % past depth 3.7)";
    const std::string map = reason("cloud.toml", "type = \"dome\"\nmap = \"sunny.hdr\"\n");
    EXPECT_NE(map.find(shaded), std::string::npos) << map;
    EXPECT_EQ(cloud.find("sun's optical depth"), std::string::npos) << cloud;
}

TEST(EndToEnd, SceneAndBareVdbRenderFiniteNonBlackExr) {
    std::string dir = test::tempDir();
    std::string vdb = fogAsset(dir);
    std::string p = writeFile(dir, "ok.toml", kGoodScene);
    for (const std::string& input : {p, vdb}) {
        std::string out = dir + "/out.exr", log;
        ASSERT_EQ(0, test::runMirage("render '" + input + "' -o '" + out +
                                         "' --resolution 32x24 --spp 2 --quiet",
                                     &log))
            << log;
        std::map<std::string, std::string> meta;
        Image img = readExr(out, &meta);
        ASSERT_EQ(img.width, 32);
        double sum = 0;
        for (float v : img.rgba) {
            ASSERT_TRUE(std::isfinite(v));
            sum += v;
        }
        EXPECT_GT(sum, 0.0) << input;
        EXPECT_EQ(meta["mirage:spp"], "2");
        // The frame's time includes the render's and the integrator's set-up.
        ASSERT_TRUE(meta.count("mirage:frame_seconds") && meta.count("mirage:render_seconds"));
        EXPECT_GE(std::stod(meta["mirage:frame_seconds"]),
                  std::stod(meta["mirage:render_seconds"]));
    }
}

TEST(EndToEnd, BadInputExitsNonZeroWithOneMessage) {
    std::string dir = test::tempDir();
    std::string bad = writeFile(dir, "bad.vdb", "this is not a vdb");
    std::string log;
    EXPECT_EQ(1, test::runMirage("render '" + bad + "' -o '" + dir + "/x.exr' --quiet", &log));
    EXPECT_NE(log.find("mirage: error:"), std::string::npos) << log;
    EXPECT_NE(log.find("bad.vdb"), std::string::npos) << log;
    EXPECT_LT(log.size(), 600u) << log;
    EXPECT_FALSE(std::ifstream(dir + "/x.exr").good());
}

TEST(EndToEnd, TurntableAndFrameRangesNumberTheirOutputs) {
    std::string dir = test::tempDir();
    std::string vdb = fogAsset(dir);
    std::string log;
    ASSERT_EQ(0, test::runMirage("render '" + vdb + "' -o '" + dir +
                                     "/tt.exr' --turntable 2 "
                                     "--resolution 16x16 --spp 1 --quiet",
                                 &log))
        << log;
    Image a = readExr(dir + "/tt.0001.exr"), b = readExr(dir + "/tt.0002.exr");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_NE(a.rgba, b.rgba);  // the camera moved half a turn

    // A frame pattern in the scene's volume path and in the output path.
    std::filesystem::copy_file(vdb, dir + "/fog.0003.vdb");
    std::filesystem::copy_file(vdb, dir + "/fog.0004.vdb");
    std::string scene = std::string(kGoodScene);
    scene.replace(scene.find("fog.vdb"), 7, "fog.$F4.vdb");
    std::string p = writeFile(dir, "seq.toml", scene);
    ASSERT_EQ(0, test::runMirage("render '" + p + "' -o '" + dir +
                                     "/seq.####.exr' --frames 3-4 "
                                     "--quiet",
                                 &log))
        << log;
    EXPECT_TRUE(std::filesystem::exists(dir + "/seq.0003.exr"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/seq.0004.exr"));
    EXPECT_NE(0, test::runMirage("render '" + p + "' -o '" + dir + "/x.exr' --frames 3-5 --quiet",
                                 &log));  // frame 5 has no cache: a clear error, exit 1
    EXPECT_NE(log.find("fog.0005.vdb"), std::string::npos) << log;
}

// [camera] turntable = N: frame f orbits (f − 1)/N of a turn about `up` through look_at.
TEST(SceneLoad, CameraTurntableOrbitsLookAtOncePerNFrames) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    std::string p = writeFile(dir, "turn.toml",
                              std::string(kGoodScene) +
                                  "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\n"
                                  "turntable = 4\n");
    ColorPipeline color;
    auto cameraAt = [&](int frame) {
        return loadScene(p, LoadOptions{frame, {}}, color).render.camera;
    };
    const CameraDesc c1 = cameraAt(1), c2 = cameraAt(2), c3 = cameraAt(3), c5 = cameraAt(5);
    EXPECT_NEAR(c1.position.z, 4.f, 1e-5f);
    // A quarter turn: still 4 m from look_at, at its height, on the x axis.
    EXPECT_NEAR(std::abs(c2.position.x), 4.f, 1e-4f);
    EXPECT_NEAR(c2.position.z, 0.f, 1e-4f);
    EXPECT_NEAR(c2.position.y, 1.f, 1e-5f);
    // Half a turn: opposite; N frames later: where it started.
    EXPECT_NEAR(c3.position.z, -4.f, 1e-4f);
    EXPECT_NEAR(c5.position.x, c1.position.x, 1e-4f);
    EXPECT_NEAR(c5.position.z, c1.position.z, 1e-4f);
    EXPECT_EQ(c2.lookAt.y, 1.f);
    // Zero or fractional frame counts are errors naming the line.
    std::string bad = writeFile(dir, "bad.toml",
                                std::string(kGoodScene) +
                                    "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\n"
                                    "turntable = 0\n");
    EXPECT_NE(loadError(bad).find("turntable"), std::string::npos) << loadError(bad);
}

// [output] color_space: the EXR holds that space's values and chromaticities. ACEScg and
// linear Rec.709 share the D65-ish white and differ by a 3×3 matrix, so the same render in
// both is two images whose greys agree and whose primaries do not; an unknown space is an
// error naming the scene's line.
TEST(EndToEnd, OutputColorSpaceConvertsPixelsAndTagsChromaticities) {
    std::string dir = test::tempDir();
    fogAsset(dir);
    auto sceneIn = [&](const std::string& space) {
        return writeFile(
            dir, "cs.toml",
            std::string(kGoodScene) + "[output]\ncolor_space = \"" + space + "\"\nhalf = false\n");
    };
    std::string log;
    ASSERT_EQ(
        0, test::runMirage(
               "render '" + sceneIn("ACEScg") + "' -o '" + dir + "/cg.exr' --quiet --seed 3", &log))
        << log;
    ASSERT_EQ(0, test::runMirage("render '" + sceneIn("Linear Rec.709 (sRGB)") + "' -o '" + dir +
                                     "/709.exr' --quiet --seed 3",
                                 &log))
        << log;
    std::map<std::string, std::string> metaCg, meta709;
    Image cg = readExr(dir + "/cg.exr", &metaCg), rec = readExr(dir + "/709.exr", &meta709);
    ASSERT_EQ(cg.rgba.size(), rec.rgba.size());
    EXPECT_NE(metaCg["chromaticities"].find("0.713"), std::string::npos)
        << metaCg["chromaticities"];
    EXPECT_NE(meta709["chromaticities"].find("0.64"), std::string::npos)
        << meta709["chromaticities"];
    // Luminance is the same in both (Y row of each space's RGB→XYZ), pixel by pixel.
    double maxRel = 0, maxDiff = 0, sumY = 0;
    for (int y = 0; y < cg.height; ++y)
        for (int x = 0; x < cg.width; ++x) {
            const float* a = cg.pixel(x, y);
            const float* b = rec.pixel(x, y);
            const double yCg = 0.2722287 * a[0] + 0.6740818 * a[1] + 0.0536895 * a[2];
            const double y709 = 0.2126390 * b[0] + 0.7151687 * b[1] + 0.0721923 * b[2];
            sumY += yCg;
            maxRel = std::max(maxRel, std::abs(yCg - y709) / std::max(1e-3, yCg));
            maxDiff = std::max(maxDiff, double(std::abs(a[0] - b[0])));
        }
    ASSERT_GT(sumY, 0.0);
    EXPECT_LT(maxRel, 1e-2);  // Y is kept up to the D60→D65 adaptation of chromatic colours
    EXPECT_GT(maxDiff, 0.0);  // not the same numbers: converted

    const std::string msg = loadError(sceneIn("Rec.2020 linear"));
    EXPECT_NE(msg.find("cs.toml:16:"), std::string::npos) << msg;  // the color_space line
    EXPECT_NE(msg.find("ACEScg"), std::string::npos) << msg;       // lists what the config has
}

TEST(SceneLoad, BareFileNameResolvesShadersAndVolumesFromWorkingDirectory) {
    // `mirage render scene.toml` from the scene's own folder: the scene path has no directory
    // part, and a shader file beside it must still be found (it once fell through to the
    // built-in shaders and failed as "unknown shader").
    std::string dir = test::tempDir();
    fogAsset(dir);
    writeFile(dir, "mist.toml",
              "name = \"mist\"\n[[component]]\nname = \"d\"\ngrid = \"density\"\n"
              "sigma_a = 0.25\nsigma_s = 0.5\n");
    std::string scene = kGoodScene;
    scene.replace(scene.find("\"smoke\""), 7, "\"mist\"");
    writeFile(dir, "here.toml", scene);
    auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(dir);
    ColorPipeline color;
    std::string error;
    Scene s;
    try {
        s = loadScene("here.toml", LoadOptions{}, color);
    } catch (const MirageError& e) {
        error = e.what();
    }
    std::filesystem::current_path(cwd);
    ASSERT_EQ(error, "");
    ASSERT_EQ(s.volumes.size(), 1u);
    EXPECT_EQ(s.volumes[0].shader, "mist");
}

TEST(SceneLoad, SetOnABareVdbAppliesSettingsAndRefusesOtherKeys) {
    std::string dir = test::tempDir();
    std::string vdb = fogAsset(dir);
    ColorPipeline color;
    Scene s = loadScene(vdb, LoadOptions{1, {"film.spp=7"}}, color);
    EXPECT_EQ(s.settings.spp, 7);
    try {
        loadScene(vdb, LoadOptions{1, {"volume.0.density_scale=2"}}, color);
        FAIL() << "--set of a volume key on a bare VDB was ignored";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("volume"), std::string::npos) << e.what();
    }
}

TEST(SceneLoad, BoxVolumeAndComponentConcentrations) {
    // A homogeneous box of a grid-free shader; `concentration` sets a component by name, and
    // --set reaches it as volume.N.concentration.NAME.
    std::string dir = test::tempDir();
    writeFile(dir, "water.toml",
              "[[component]]\nname = \"water\"\nkind = \"water\"\n"
              "[[component]]\nname = \"chlorophyll\"\nkind = \"chlorophyll\"\n"
              "concentration = 0.1\n");
    std::string scene = writeFile(dir, "sea.toml",
                                  "[[volume]]\nbox = { min = [0, 0, 0], max = [2, 1, 3] }\n"
                                  "shader = \"water\"\nconcentration = { chlorophyll = 0.5 }\n");
    ColorPipeline color;
    Scene s = loadScene(scene, LoadOptions{}, color);
    ASSERT_EQ(s.render.media.size(), 1u);
    const Medium& m = *s.render.media[0];
    EXPECT_TRUE(m.homogeneous());
    EXPECT_FLOAT_EQ(m.worldBounds().hi.z, 3.f);
    EXPECT_FLOAT_EQ(m.shader().components[1].concentration, 0.5f);
    Scene t = loadScene(scene, LoadOptions{1, {"volume.0.concentration.chlorophyll=5"}}, color);
    EXPECT_FLOAT_EQ(t.render.media[0]->shader().components[1].concentration, 5.f);

    // An unknown component names the ones there are; a shader with a grid cannot fill a box.
    std::string bad = writeFile(dir, "bad.toml",
                                "[[volume]]\nbox = { min = [0, 0, 0], max = [1, 1, 1] }\n"
                                "shader = \"water\"\nconcentration = { chlorofyll = 1 }\n");
    EXPECT_NE(loadError(bad).find("no component 'chlorofyll'; its components are: water, "
                                  "chlorophyll"),
              std::string::npos)
        << loadError(bad);
    std::string grid = writeFile(dir, "grid.toml",
                                 "[[volume]]\nbox = { min = [0, 0, 0], max = [1, 1, 1] }\n"
                                 "shader = \"ocean\"\n");
    EXPECT_NE(loadError(grid).find("reads grid slot(s) 'chlorophyll'"), std::string::npos)
        << loadError(grid);
    std::string flat = writeFile(dir, "flat.toml",
                                 "[[volume]]\nbox = { min = [0, 0, 0], max = [1, 0, 1] }\n"
                                 "shader = \"water\"\n");
    EXPECT_NE(loadError(flat).find("'max'"), std::string::npos) << loadError(flat);
}

// The quality presets scale what a scene states it needs (film.spp, render.photons: ¼, 1, 4)
// and keep a stated render.k, so that the final preset, the gallery's noise reference, is the
// scene's own estimator with 4× the samples; unstated, k is the preset's; --set still wins.
TEST(SceneLoad, QualityPresetsScaleStatedSamplesAndKeepAStatedK) {
    const std::string dir = test::tempDir();
    fogAsset(dir);
    auto scene = [&](const std::string& name, const std::string& render) {
        ColorPipeline color;
        return loadScene(writeFile(dir, name,
                                   "[film]\nresolution = [8, 8]\nspp = 16\n[render]\n"
                                   "integrator = \"photon\"\nphotons = 2000\n" +
                                       render + "[[volume]]\nfile = \"fog.vdb\"\n"),
                         LoadOptions{}, color);
    };
    for (const QualityPreset& preset : qualityPresets()) {
        Scene stated = scene("k64.toml", "k = 64\n");
        applyQualityPreset(stated, preset, "photon", {});
        EXPECT_EQ(stated.photon.k, 64) << preset.name;
        EXPECT_EQ(stated.settings.spp, int(16 * preset.sceneScale)) << preset.name;
        EXPECT_EQ(stated.photon.photons, uint64_t(2000 * preset.sceneScale)) << preset.name;
        Scene unstated = scene("k0.toml", "");
        applyQualityPreset(unstated, preset, "photon", {});
        EXPECT_EQ(unstated.photon.k, preset.k) << preset.name;
        Scene overridden = scene("k64.toml", "k = 64\n");
        overridden.photon.k = 8;
        applyQualityPreset(overridden, preset, "photon", {"render.k=8"});
        EXPECT_EQ(overridden.photon.k, 8) << preset.name;
    }
}

// A scene in passes (stated here; `auto` makes them on dense smoke) has its passes scaled and
// keeps each map's photons: the preset's photons are a one-map render's (10⁶ or 4·10⁶ in each
// of 16 maps once made the final preset 40 times the scene's own render).
TEST(SceneLoad, QualityPresetsScalePassesAndKeepEachMapsPhotons) {
    const std::string dir = test::tempDir();
    fogAsset(dir);
    for (const QualityPreset& preset : qualityPresets()) {
        ColorPipeline color;
        Scene s = loadScene(writeFile(dir, "passes.toml",
                                      "[film]\nresolution = [8, 8]\n[render]\n"
                                      "integrator = \"photon\"\npasses = 4\n"
                                      "[[volume]]\nfile = \"fog.vdb\"\n"),
                            LoadOptions{}, color);
        const uint64_t photons = s.photon.photons;
        applyQualityPreset(s, preset, "photon", {});
        EXPECT_EQ(s.passes.maxPasses, int(4 * preset.sceneScale)) << preset.name;
        EXPECT_EQ(s.photon.photons, photons) << preset.name;
    }
}
