// Render passes (docs/aovs.md): the light-path passes and the light groups sum to the beauty
// per pixel with every integrator, the EXR layers carry names Nuke splits into layers, a
// partial file carries the passes bit for bit, and a render without AOVs keeps its bits.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "core/error.h"
#include "film/color.h"
#include "film/image_io.h"
#include "film/partial_film.h"
#include "frame/render_frame.h"
#include "scene/scene.h"
#include "test_support.h"
#include "tools/asset_writer.h"

using namespace mirage;

namespace {

// Fire (emission and smoke in one volume), a fog sphere, a diffuse floor, a mirror sphere and
// two light groups: every light-path class occurs.
std::string writeAovScene(const std::string& dir, const std::string& integrator,
                          const std::string& aovs, const std::string& extra = "") {
    if (!std::filesystem::exists(dir + "/fire.vdb")) {
        writeProceduralAsset("fire", dir + "/fire.vdb", 16, 3);
        writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    }
    const std::string path = dir + "/aov_" + integrator + std::to_string(aovs.size()) +
                             std::to_string(extra.size()) + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [12, 10]\nspp = 4\nseed = 3\n"
         "[render]\nintegrator = \""
      << integrator
      << "\"\nphotons = 20000\n"
         "[camera]\nposition = [0.0, 1.0, 3.6]\nlook_at = [0.0, 0.8, 0.0]\nfov = 40.0\n"
         "[[volume]]\nfile = \"fire.vdb\"\nshader = \"fire\"\ndensity_scale = 6.0\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3.0\n"
         "transform = { scale = 0.5, translate = [0.6, 0.5, 0.2] }\n"
         "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 0.7\n"
         "[[material]]\nname = \"chrome\"\ntype = \"mirror\"\n"
         "[[shape]]\ntype = \"quad\"\ncorner = [-2, 0, 2]\nedge_u = [4, 0, 0]\n"
         "edge_v = [0, 0, -4]\nmaterial = \"white\"\n"
         "[[shape]]\ntype = \"sphere\"\ncenter = [-0.7, 0.3, 0.4]\nradius = 0.3\n"
         "material = \"chrome\"\n"
         "[[light]]\ntype = \"point\"\nposition = [1.5, 2.5, 2.0]\npower = 20000\ngroup = \"key\"\n"
         "[[light]]\ntype = \"distant\"\ndirection = [-1, -1, 0.3]\ngroup = \"fill\"\n"
         "[output]\naovs = ["
      << aovs << "]\n"
      << extra;
    return path;
}

const char* const kLightPathAovs =
    "\"emission\", \"volume_direct\", \"volume_indirect\", \"surface_direct\", "
    "\"surface_indirect\", \"caustic\"";
const char* const kGroupAovs = "\"lightgroup_emission\", \"lightgroup_key\", \"lightgroup_fill\"";

const ImageLayer* findLayer(const Image& image, const std::string& name) {
    for (const ImageLayer& l : image.layers)
        if (l.name == name) return &l;
    return nullptr;
}

// Per pixel and channel, Σ of the named layers against the beauty, to float rounding.
void expectSumToBeauty(const Image& image, const std::vector<std::string>& names,
                       const std::string& what) {
    std::vector<const ImageLayer*> layers;
    for (const std::string& n : names) {
        layers.push_back(findLayer(image, n));
        ASSERT_NE(layers.back(), nullptr) << n;
    }
    double nonZeroParts = 0;
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
        for (int c = 0; c < 3; ++c) {
            double sum = 0, magnitude = 0;
            for (const ImageLayer* l : layers) {
                sum += l->pixels[p * 3 + c];
                magnitude += std::abs(l->pixels[p * 3 + c]);
                nonZeroParts += l->pixels[p * 3 + c] != 0.f;
            }
            const double beauty = image.rgba[p * 4 + c];
            EXPECT_NEAR(sum, beauty, 1e-5 * magnitude + 1e-7)
                << what << " pixel " << p << " c " << c;
        }
    EXPECT_GT(nonZeroParts, 0) << what;
}

Image renderAovScene(const std::string& integrator, const std::string& aovs,
                     const std::string& extra = "") {
    ColorPipeline color;
    Scene scene = loadScene(writeAovScene(test::tempDir(), integrator, aovs, extra), {}, color);
    scene.settings.progress = Progress::Mode::Quiet;
    scene.photon.progress = Progress::Mode::Quiet;
    return renderFrame(scene, color).image;
}

}  // namespace

TEST(Aov, LightPathPassesSumToTheBeautyWithEveryIntegrator) {
    for (const char* integrator : {"single", "volpath", "photon"}) {
        const Image image = renderAovScene(integrator, kLightPathAovs);
        std::vector<std::string> names;
        for (int p = 0; p < kLightPathCount; ++p) names.push_back(lightPathName(LightPath(p)));
        expectSumToBeauty(image, names, integrator);
        // Fire is seen directly, and the smoke scatters light once, in every integrator.
        for (const char* pass : {"emission", "volume_direct"}) {
            const ImageLayer* l = findLayer(image, pass);
            double total = 0;
            for (float v : l->pixels) total += v;
            EXPECT_GT(total, 0.0) << integrator << " " << pass;
        }
    }
}

// With photons too: each photon carries the light it left, and the photon estimates split by
// it (photon/photon_groups.h). `auto` picks the photon integrator for this scene's fire.
TEST(Aov, LightGroupsSumToTheBeauty) {
    for (const char* integrator : {"single", "volpath", "photon", "auto"}) {
        const Image image = renderAovScene(integrator, kGroupAovs);
        expectSumToBeauty(image, {"lightgroup_emission", "lightgroup_key", "lightgroup_fill"},
                          integrator);
        for (const char* group : {"lightgroup_emission", "lightgroup_key", "lightgroup_fill"}) {
            double total = 0;
            for (float v : findLayer(image, group)->pixels) total += v;
            EXPECT_GT(total, 0.0) << integrator << " " << group;
        }
    }
}

// Curved camera rays (a refraction gradient) carry their passes chord by chord
// (AovSample::addWeighted): the passes a chord lit must reach the film, whichever chord lit them.
TEST(Aov, PassesSumToTheBeautyAlongCurvedRays) {
    const std::string refraction = "[refraction]\nprofile = \"linear\"\nn0 = 1.0003\nk = 0.02\n";
    for (const char* integrator : {"single", "volpath"}) {
        const Image image =
            renderAovScene(integrator, std::string(kLightPathAovs) + ", " + kGroupAovs, refraction);
        std::vector<std::string> names;
        for (int p = 0; p < kLightPathCount; ++p) names.push_back(lightPathName(LightPath(p)));
        expectSumToBeauty(image, names, integrator);
        expectSumToBeauty(image, {"lightgroup_emission", "lightgroup_key", "lightgroup_fill"},
                          integrator);
    }
}

TEST(Aov, TheBeautyKeepsItsBitsWithAovs) {
    const Image plain = renderAovScene("volpath", "");
    const Image passes = renderAovScene(
        "volpath", std::string(kLightPathAovs) + ", " + kGroupAovs + ", \"depth\", \"albedo\"");
    ASSERT_EQ(plain.rgba.size(), passes.rgba.size());
    EXPECT_TRUE(plain.layers.empty());
    for (size_t i = 0; i < plain.rgba.size(); ++i) ASSERT_EQ(plain.rgba[i], passes.rgba[i]) << i;
}

// Data passes describe the camera ray, not its light: on a grey scene the beauty keeps its
// exact colour per sample (render/achromatic_film.h), so asking for them changes no bit of it.
TEST(Aov, DataPassesKeepTheBeautysExactColourAndBits) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    auto render = [&](const std::string& aovs) {
        const std::string path = dir + "/grey" + std::to_string(aovs.size()) + ".toml";
        std::ofstream(path) << "[film]\nresolution = [12, 10]\nspp = 4\nseed = 3\n"
                               "[render]\nintegrator = \"volpath\"\n"
                               "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\n"
                               "fov = 40.0\n"
                               "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\n"
                               "density_scale = 4.0\n"
                               "[[light]]\ntype = \"sun\"\ndirection = [-1, -1, -0.5]\n"
                               "[output]\naovs = ["
                            << aovs << "]\n";
        ColorPipeline color;
        Scene scene = loadScene(path, {}, color);
        scene.settings.progress = Progress::Mode::Quiet;
        return renderFrame(scene, color).image;
    };
    const Image plain = render("");
    const Image data =
        render("\"alpha\", \"depth\", \"albedo\", \"transmittance\", \"variance\"");
    ASSERT_EQ(plain.rgba.size(), data.rgba.size());
    ASSERT_EQ(data.layers.size(), 5u);
    double lit = 0;
    for (size_t i = 0; i < plain.rgba.size(); ++i) {
        ASSERT_EQ(plain.rgba[i], data.rgba[i]) << i;
        lit += plain.rgba[i];
    }
    EXPECT_GT(lit, 0.0);
}

TEST(Aov, DataPasses) {
    const Image image = renderAovScene("single",
                                       "\"alpha\", \"depth\", \"transmittance\", "
                                       "\"albedo\"");
    const ImageLayer* alpha = findLayer(image, "alpha");
    const ImageLayer* depth = findLayer(image, "depth");
    const ImageLayer* T = findLayer(image, "transmittance");
    ASSERT_TRUE(alpha && depth && T && findLayer(image, "albedo"));
    EXPECT_EQ(depth->channels, std::vector<std::string>{"Z"});
    int sky = 0, floor = 0;
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
        EXPECT_EQ(alpha->pixels[p], image.rgba[p * 4 + 3]);
        // Where nothing is ever 50 % opaque the depth is ∞ (the top rows see the sky).
        if (!std::isfinite(depth->pixels[p])) {
            ++sky;
            EXPECT_GT(T->pixels[p * 3 + 1], 0.4f);
        } else {
            EXPECT_GT(depth->pixels[p], 1.f);
            EXPECT_LT(depth->pixels[p], 20.f);
            floor += image.rgba[p * 4 + 3] == 1.f;
        }
    }
    EXPECT_GT(sky, 0);
    EXPECT_GT(floor, 0);
}

TEST(Aov, ExrLayersFollowNukesLayerRule) {
    const Image image = renderAovScene("single", std::string(kGroupAovs) +
                                                     ", \"volume_direct\", "
                                                     "\"depth\"");
    const std::string dir = test::tempDir();
    for (bool multipart : {false, true}) {
        const std::string path = dir + (multipart ? "/multi.exr" : "/single.exr");
        ExrOptions options;
        options.multipart = multipart;
        writeExr(path, image, options);
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in);
        std::vector<std::string> channels;
        int parts = 0;
        for (; in->seek_subimage(parts, 0); ++parts)
            for (const std::string& c : in->spec().channelnames) channels.push_back(c);
        EXPECT_EQ(parts, multipart ? 6 : 1);  // the beauty and five passes
        const std::regex nuke("([A-Za-z0-9_]+\\.[A-Za-z0-9_]+)|[RGBA]");
        for (const std::string& c : channels) EXPECT_TRUE(std::regex_match(c, nuke)) << c;
        for (const char* c : {"R", "G", "B", "A", "lightgroup_key.R", "lightgroup_fill.G",
                              "lightgroup_emission.B", "volume_direct.R", "depth.Z"})
            EXPECT_NE(std::find(channels.begin(), channels.end(), c), channels.end()) << c;
        // Read back: the same layers.
        const Image back = readExr(path);
        ASSERT_EQ(back.layers.size(), image.layers.size());
        const ImageLayer* key = findLayer(back, "lightgroup_key");
        ASSERT_TRUE(key);
        EXPECT_NEAR(key->pixels[5], findLayer(image, "lightgroup_key")->pixels[5],
                    2e-3 * std::abs(key->pixels[5]) + 1e-6);
    }
}

TEST(Aov, PartialFileCarriesThePassSums) {
    ColorPipeline color;
    Scene scene = loadScene(writeAovScene(test::tempDir(), "single", kGroupAovs), {}, color);
    scene.settings.progress = Progress::Mode::Quiet;
    RenderedFrame frame = renderFrame(scene, color);
    const Film& film = *frame.film;
    const std::string path = test::tempDir() + "/aov.exr.partial";
    const int tiles = tileCount(scene.settings);
    writePartialFilm(path, film, scene.settings.tileSize, std::vector<uint8_t>(size_t(tiles), 1),
                     color.xyzToWorking(), {});
    PartialFilm back = readPartialFilm(path);
    ASSERT_EQ(back.film->aovs().stride(), film.aovs().stride());
    EXPECT_EQ(back.film->aovs().names(), film.aovs().names());
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x)
            for (int i = 0; i < film.aovs().stride(); ++i)
                ASSERT_EQ(back.film->aovSums(x, y)[i], film.aovSums(x, y)[i]);
}

TEST(Aov, BadInputNamesTheLine) {
    ColorPipeline color;
    const std::string dir = test::tempDir();
    auto error = [&](const std::string& integrator, const std::string& aovs,
                     const std::string& extra = "") {
        try {
            Scene s = loadScene(writeAovScene(dir, integrator, aovs, extra), {}, color);
            s.settings.progress = Progress::Mode::Quiet;
            renderFrame(s, color);
        } catch (const MirageError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // An unknown pass, and a light group no light belongs to: the [output] line.
    std::string e = error("single", "\"volume_drect\"");
    const std::regex line("aov_single[0-9]+\\.toml:[0-9]+:");
    EXPECT_TRUE(std::regex_search(e, line)) << e;
    EXPECT_NE(e.find("unknown AOV 'volume_drect'"), std::string::npos) << e;
    e = error("single", "\"lightgroup_rim\"");
    EXPECT_NE(e.find("lightgroup_key"), std::string::npos) << e;
    EXPECT_TRUE(std::regex_search(e, line)) << e;
}

// Two scenes the fire scene above does not cover. Grey fog under one white sun is the scene
// whose beauty the renderer would colour exactly per sample (render/achromatic_film.h): with
// passes it must not, or the passes would no longer sum to the beauty sample by sample. Under a
// dome, the dome seen straight through the fog is light seen at its source: it is counted with
// emission, so the passes and the light groups still sum to the beauty.
TEST(Aov, GreyFogAndADomeKeepThePassesSummingToTheBeauty) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    const std::string common =
        "[film]\nresolution = [12, 10]\nspp = 4\nseed = 3\n"
        "[camera]\nposition = [0.0, 0.5, 3.0]\nlook_at = [0.0, 0.5, 0.0]\nfov = 40.0\n"
        "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3.0\n";
    const std::string sun = "[[light]]\ntype = \"distant\"\ndirection = [-1, -1, 0.3]\n";
    const std::string dome = "[[light]]\ntype = \"dome\"\ncolor = [0.2, 0.4, 0.9]\n";
    std::vector<std::string> names;
    for (int p = 0; p < kLightPathCount; ++p) names.push_back(lightPathName(LightPath(p)));
    for (const std::string& lights : {sun, sun + dome})
        for (const char* integrator : {"single", "volpath"}) {
            const std::string path =
                dir + "/grey_" + std::to_string(lights.size()) + integrator + ".toml";
            std::ofstream(path) << common << "[render]\nintegrator = \"" << integrator << "\"\n"
                                << lights << "[output]\naovs = [" << kLightPathAovs
                                << ", \"lightgroup_emission\", \"lightgroup_default\"]\n";
            ColorPipeline color;
            Scene scene = loadScene(path, {}, color);
            scene.settings.progress = Progress::Mode::Quiet;
            const Image image = renderFrame(scene, color).image;
            const std::string what = std::string(integrator) + (lights == sun ? " sun" : " dome");
            expectSumToBeauty(image, names, what);
            expectSumToBeauty(image, {"lightgroup_emission", "lightgroup_default"}, what);
        }
}

// The variance pass against its definition: a pixel of n samples whose XYZ are known has, per
// working-space channel r = Σ_c M_rc X_c, the variance of its mean s²_r / n, s²_r the unbiased
// sample variance of the samples' r (computed here from the samples themselves).
TEST(Aov, VariancePassIsTheVarianceOfThePixelMean) {
    ColorPipeline color;
    Film film(1, 1, AovLayout({"variance"}, {}));
    const std::vector<Vec3> samples = {Vec3(0.2f, 0.5f, 0.1f), Vec3(1.5f, 0.3f, 0.9f),
                                       Vec3(0.7f, 0.7f, 0.2f), Vec3(0.1f, 2.0f, 0.4f),
                                       Vec3(0.9f, 0.2f, 1.3f)};
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    AovSample aov;
    for (const Vec3& s : samples)
        ASSERT_TRUE(film.addSample(0, 0, SampledSpectrum(0.f), w, 1.f, s, &aov));
    const Image image = film.develop(color);
    const ImageLayer* variance = findLayer(image, "variance");
    ASSERT_TRUE(variance);
    EXPECT_EQ(variance->channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_FALSE(variance->convertColor);
    const Mat3& M = color.xyzToWorking();
    const double n = double(samples.size());
    for (int r = 0; r < 3; ++r) {
        std::vector<double> v;
        for (const Vec3& s : samples) v.push_back(M.apply(Vec3d(s))[r]);
        double mean = 0, s2 = 0;
        for (double x : v) mean += x / n;
        for (double x : v) s2 += (x - mean) * (x - mean) / (n - 1);
        EXPECT_NEAR(variance->pixels[size_t(r)], s2 / n, 1e-6 * s2 / n) << r;
    }
}

// On grey fog the variance of a pixel's mean falls as 1/N in its samples: four times the
// samples, a quarter of the variance (the image mean of the per-pixel estimates; each is a
// sample variance over ≥ 16 samples of heavy-tailed volpath paths, so their mean over 256
// pixels is within ~±15 %: over 64 pixels one long path could halve the ratio).
TEST(Aov, VariancePassFallsAsOneOverSamples) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    auto meanVariance = [&](int spp) {
        const std::string path = dir + "/variance_" + std::to_string(spp) + ".toml";
        std::ofstream(path) << "[film]\nresolution = [16, 16]\nspp = " << spp
                            << "\nseed = 9\n[render]\nintegrator = \"volpath\"\n"
                               "[camera]\nposition = [0.0, 0.0, 2.2]\nlook_at = [0, 0, 0]\n"
                               "fov = 30.0\n[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\n"
                               "density_scale = 4.0\n[[light]]\ntype = \"distant\"\n"
                               "direction = [-1, -1, 0.3]\n[output]\naovs = [\"variance\"]\n";
        ColorPipeline color;
        Scene scene = loadScene(path, {}, color);
        scene.settings.progress = Progress::Mode::Quiet;
        const Image image = renderFrame(scene, color).image;
        double sum = 0;
        for (float v : findLayer(image, "variance")->pixels) sum += v;
        return sum;
    };
    const double v16 = meanVariance(16), v64 = meanVariance(64);
    ASSERT_GT(v64, 0.0);
    EXPECT_NEAR(v16 / v64, 4.0, 0.6);
}

// `mirage info` lists what the render writes beside the beauty, and says "none" or "off" for
// what a scene does not ask for.
TEST(Aov, InfoListsPassesGroupsCryptomatteHoldoutsAndDeep) {
    const std::string dir = test::tempDir();
    std::string out;
    const std::string asks =
        writeAovScene(dir, "single", std::string(kGroupAovs) + ", \"variance\"",
                      "cryptomatte = [\"volume\"]\ndeep = \"deep.exr\"\n");
    ASSERT_EQ(0, test::runMirage("info '" + asks + "'", &out)) << out;
    for (const std::string& line : std::vector<std::string>{
             "passes: lightgroup_emission, lightgroup_key, lightgroup_fill, variance, "
             "crypto_volume",
             "light groups: key, fill, and emission", "; light group 'key'",
             "cryptomatte: layers crypto_volume00–02, 6 ranks, of the volumes volume0, volume1",
             "holdouts: none", "deep: " + dir + "/deep.exr"})
        EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
    ASSERT_EQ(0, test::runMirage("info '" + writeAovScene(dir, "volpath", "") + "'", &out)) << out;
    for (const char* line : {"passes: none", "deep: off", "holdouts: none"})
        EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
}
