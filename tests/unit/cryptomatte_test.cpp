// Cryptomatte (film/cryptomatte.h): MurmurHash3_x86_32 against the published test vectors, the
// float32 ID's exponent rule, and a render of two volumes and two shapes whose layers decode
// back to coverages that sum to the pixel's alpha and name the right objects, with the header
// metadata of the specification.
#include "film/cryptomatte.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "film/color.h"
#include "film/image_io.h"
#include "frame/render_frame.h"
#include "scene/scene.h"
#include "test_support.h"
#include "tools/asset_writer.h"

using namespace mirage;

namespace {

std::string bytes(std::initializer_list<int> b) {
    std::string s;
    for (int c : b) s.push_back(char(c));
    return s;
}

uint32_t bitsOf(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

}  // namespace

// The vectors of Appleby's SMHasher verification for MurmurHash3_x86_32: the empty key under
// three seeds, the four tail lengths, little-endian block order, embedded zero bytes.
TEST(Cryptomatte, MurmurHash3MatchesThePublishedVectors) {
    EXPECT_EQ(murmurHash3_32("", 0), 0u);
    EXPECT_EQ(murmurHash3_32("", 1), 0x514E28B7u);
    EXPECT_EQ(murmurHash3_32("", 0xffffffffu), 0x81F16F39u);
    EXPECT_EQ(murmurHash3_32(bytes({0xff, 0xff, 0xff, 0xff}), 0), 0x76293B50u);
    EXPECT_EQ(murmurHash3_32(bytes({0x21, 0x43, 0x65, 0x87}), 0), 0xF55B516Bu);
    EXPECT_EQ(murmurHash3_32(bytes({0x21, 0x43, 0x65, 0x87}), 0x5082EDEEu), 0x2362F9DEu);
    EXPECT_EQ(murmurHash3_32(bytes({0x21, 0x43, 0x65}), 0), 0x7E4A8634u);
    EXPECT_EQ(murmurHash3_32(bytes({0x21, 0x43}), 0), 0xA0F7B07Au);
    EXPECT_EQ(murmurHash3_32(bytes({0x21}), 0), 0x72661CF4u);
    EXPECT_EQ(murmurHash3_32(bytes({0, 0, 0, 0}), 0), 0x2362F9DEu);
    EXPECT_EQ(murmurHash3_32(bytes({0, 0, 0}), 0), 0x85F0B427u);
    EXPECT_EQ(murmurHash3_32(bytes({0, 0}), 0), 0x30F4C306u);
    EXPECT_EQ(murmurHash3_32(bytes({0}), 0), 0x514E28B7u);
}

// uint32_to_float32: the hash's bits, with exponent 0 or 255 moved to 1 or 254 by flipping the
// exponent's lowest bit, so that every ID is a normal float.
TEST(Cryptomatte, IdsAreNormalFloatsWithTheHashBits) {
    EXPECT_EQ(bitsOf(cryptomatteId(0x3f800000u)), 0x3f800000u);  // 1.0: unchanged
    EXPECT_EQ(bitsOf(cryptomatteId(0x00000001u)), 0x00800001u);  // denormal → exponent 1
    EXPECT_EQ(bitsOf(cryptomatteId(0x80000000u)), 0x80800000u);  // −0 → exponent 1
    EXPECT_EQ(bitsOf(cryptomatteId(0x7f800000u)), 0x7f000000u);  // ∞ → exponent 254
    EXPECT_EQ(bitsOf(cryptomatteId(0xffc00001u)), 0xff400001u);  // NaN → exponent 254
    for (uint32_t i = 0; i < 1000; ++i) {
        const float id = cryptomatteId(murmurHash3_32("object" + std::to_string(i)));
        EXPECT_TRUE(std::isnormal(id)) << i;
    }
}

// Fire and a fog sphere, a floor and a mirror ball, named; the Cryptomatte of both kinds.
// Per pixel, the coverages of all ranks (at most 4 objects: no rank is cut) sum to the alpha
// to float rounding: each sample's coverages are scaled to its own alpha.
TEST(Cryptomatte, LayersDecodeToCoveragesThatSumToAlpha) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fire", dir + "/fire.vdb", 16, 3);
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    const std::string path = dir + "/crypto.toml";
    std::ofstream(path)
        << "[film]\nresolution = [16, 12]\nspp = 8\nseed = 3\n[render]\nintegrator = \"single\"\n"
           "[camera]\nposition = [0.0, 1.0, 3.6]\nlook_at = [0.0, 0.8, 0.0]\nfov = 40.0\n"
           "[[volume]]\nname = \"fire\"\nfile = \"fire.vdb\"\nshader = \"fire\"\n"
           "density_scale = 6.0\n"
           "[[volume]]\nname = \"fog\"\nfile = \"fog.vdb\"\nshader = \"smoke\"\n"
           "density_scale = 3.0\ntransform = { scale = 0.5, translate = [0.6, 0.5, 0.2] }\n"
           "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 0.7\n"
           "[[material]]\nname = \"chrome\"\ntype = \"mirror\"\n"
           "[[shape]]\nname = \"floor\"\ntype = \"quad\"\ncorner = [-2, 0, 2]\n"
           "edge_u = [4, 0, 0]\nedge_v = [0, 0, -4]\nmaterial = \"white\"\n"
           "[[shape]]\nname = \"ball\"\ntype = \"sphere\"\ncenter = [-0.7, 0.3, 0.4]\n"
           "radius = 0.3\nmaterial = \"chrome\"\n"
           "[[light]]\ntype = \"point\"\nposition = [1.5, 2.5, 2.0]\npower = 20000\n"
           "[output]\ncryptomatte = [\"volume\", \"shape\"]\n";
    ColorPipeline color;
    Scene scene = loadScene(path, {}, color);
    scene.settings.progress = Progress::Mode::Quiet;
    const Image rendered = renderFrame(scene, color).image;

    // Through the file: half float beauty, the IDs must survive as float32.
    const std::string exr = dir + "/crypto.exr";
    writeExr(exr, rendered, ExrOptions());
    auto in = OIIO::ImageInput::open(exr);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    std::map<std::string, float> idOf;
    for (const char* name : {"fire", "fog", "floor", "ball"})
        idOf[name] = cryptomatteId(murmurHash3_32(name));
    for (const char* type : {"crypto_volume", "crypto_shape"}) {
        char key[16];
        std::snprintf(key, sizeof key, "%08x", murmurHash3_32(type));
        const std::string prefix = "cryptomatte/" + std::string(key).substr(0, 7) + "/";
        EXPECT_EQ(spec.get_string_attribute(prefix + "name"), type);
        EXPECT_EQ(spec.get_string_attribute(prefix + "hash"), "MurmurHash3_32");
        EXPECT_EQ(spec.get_string_attribute(prefix + "conversion"), "uint32_to_float32");
        const std::string manifest = spec.get_string_attribute(prefix + "manifest");
        for (const char* name : std::string(type) == "crypto_volume"
                                    ? std::vector<const char*>{"fire", "fog"}
                                    : std::vector<const char*>{"floor", "ball"}) {
            std::snprintf(key, sizeof key, "%08x", murmurHash3_32(name));
            EXPECT_NE(manifest.find("\"" + std::string(name) + "\":\"" + key + "\""),
                      std::string::npos)
                << manifest;
        }
    }
    const Image image = readExr(exr);
    std::vector<const ImageLayer*> layers;
    for (const char* name : {"crypto_volume00", "crypto_volume01", "crypto_volume02",
                             "crypto_shape00", "crypto_shape01", "crypto_shape02"}) {
        const ImageLayer* found = nullptr;
        for (const ImageLayer& l : image.layers)
            if (l.name == name) found = &l;
        ASSERT_TRUE(found) << name;
        EXPECT_EQ(found->channels, (std::vector<std::string>{"R", "G", "B", "A"}));
        layers.push_back(found);
    }
    EXPECT_EQ(spec.channelformat(spec.channelindex("crypto_volume00.R")), OIIO::TypeFloat);

    // Decoded: per pixel, each object's coverage from the ranks that name its ID.
    const size_t pixels = size_t(image.width) * size_t(image.height);
    std::map<std::string, double> total;
    double worst = 0;
    for (size_t p = 0; p < pixels; ++p) {
        double sum = 0;
        for (const ImageLayer* l : layers)
            for (int rank = 0; rank < 2; ++rank) {
                const float id = l->pixels[p * 4 + size_t(rank) * 2];
                const float coverage = l->pixels[p * 4 + size_t(rank) * 2 + 1];
                if (coverage == 0.f) continue;
                bool known = false;
                for (const auto& [name, value] : idOf)
                    if (bitsOf(value) == bitsOf(id)) {
                        known = true;
                        total[name] += coverage;
                    }
                EXPECT_TRUE(known) << "pixel " << p << " id " << id;
                sum += coverage;
            }
        const double alpha = rendered.rgba[p * 4 + 3];
        EXPECT_LE(sum, alpha + 1e-5) << p;
        worst = std::max(worst, alpha - sum);
    }
    EXPECT_LT(worst, 1e-5);
    // Every object is seen; the floor fills the bottom rows, opaque.
    for (const char* name : {"fire", "fog", "floor", "ball"}) EXPECT_GT(total[name], 0.0) << name;
    const size_t bottom = (pixels - size_t(image.width) / 2);
    EXPECT_EQ(bitsOf(layers[3]->pixels[bottom * 4]), bitsOf(idOf["floor"]));
    EXPECT_NEAR(layers[3]->pixels[bottom * 4 + 1], 1.f, 1e-5f);
}

// A name Cryptomatte cannot carry, and a Cryptomatte of a kind the scene lacks: the line.
TEST(Cryptomatte, BadInputNamesTheLine) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    auto error = [&](const std::string& extra, const std::string& output) {
        const std::string path = dir + "/crypto_bad.toml";
        std::ofstream(path) << "[[volume]]\nfile = \"fog.vdb\"\n"
                            << extra << "[output]\n"
                            << output;
        try {
            ColorPipeline color;
            loadScene(path, {}, color);
        } catch (const MirageError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::string e = error("name = \"my fog, thick\"\n", "cryptomatte = [\"volume\"]\n");
    EXPECT_NE(e.find("crypto_bad.toml:3"), std::string::npos) << e;
    e = error("", "cryptomatte = [\"shape\"]\n");
    EXPECT_NE(e.find("no [[shape]]"), std::string::npos) << e;
    EXPECT_NE(e.find("crypto_bad.toml:"), std::string::npos) << e;
    e = error("", "cryptomatte = [\"material\"]\n");
    EXPECT_NE(e.find("expected volume or shape"), std::string::npos) << e;
}
