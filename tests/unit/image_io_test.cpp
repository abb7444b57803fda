// Tests for film/image_io: EXR round trips (pixels and metadata), the header as OpenEXR's own
// tool sees it, atomic writes that fail cleanly, and display previews.

#include "film/image_io.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/rng.h"
#include "film/color.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

Image testImage(int width, int height) {
    Image img;
    img.width = width;
    img.height = height;
    img.rgba.resize(size_t(width) * height * 4);
    Sampler rng(5, 0, 0);
    // Scene-linear values: negatives (out-of-gamut colours), darks and highlights above 1.
    for (size_t i = 0; i < img.rgba.size(); ++i)
        img.rgba[i] = (i % 4 == 3) ? rng.get1D() : std::ldexp(rng.get1D() - 0.1f, int(i % 9) - 4);
    return img;
}

ExrOptions acescgOptions(bool halfFloat) {
    ExrOptions opt;
    opt.halfFloat = halfFloat;
    opt.colorSpace = "ACEScg";
    opt.chromaticities = {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f};
    opt.metadata = {{"spp", "64"}, {"scene", "smoke.toml"}, {"nonFiniteSamples", "0"}};
    return opt;
}

// Files in `dir` whose name marks them as an unfinished write.
std::vector<std::string> tempFiles(const std::string& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().filename().string().find(".tmp-") != std::string::npos)
            found.push_back(e.path().string());
    return found;
}

TEST(ImageIoTest, FloatRoundTripIsExactAndKeepsMetadata) {
    std::string path = test::tempDir() + "/beauty.exr";
    Image img = testImage(7, 5);
    writeExr(path, img, acescgOptions(false));
    std::map<std::string, std::string> meta;
    Image back = readExr(path, &meta);
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 5);
    ASSERT_EQ(back.rgba.size(), img.rgba.size());
    EXPECT_EQ(std::memcmp(back.rgba.data(), img.rgba.data(), img.rgba.size() * sizeof(float)), 0);
    EXPECT_EQ(meta["oiio:ColorSpace"], "ACEScg");
    EXPECT_EQ(meta["mirage:spp"], "64");
    EXPECT_EQ(meta["mirage:scene"], "smoke.toml");
    EXPECT_EQ(meta["mirage:nonFiniteSamples"], "0");
    EXPECT_EQ(meta["compression"], "zip");
    EXPECT_NE(meta["chromaticities"].find("0.713"), std::string::npos) << meta["chromaticities"];
    EXPECT_TRUE(tempFiles(fs::path(path).parent_path().string()).empty());
}

TEST(ImageIoTest, HalfRoundTripWithinHalfPrecision) {
    std::string path = test::tempDir() + "/beauty.exr";
    Image img = testImage(6, 3);
    img.rgba[0] = 1e6f;  // beyond half range: clamped to the largest half, not +∞
    img.rgba[1] = -1e6f;
    writeExr(path, img, acescgOptions(true));
    Image back = readExr(path);
    ASSERT_EQ(back.rgba.size(), img.rgba.size());
    EXPECT_EQ(back.rgba[0], 65504.f);
    EXPECT_EQ(back.rgba[1], -65504.f);
    double maxRel = 0.0;
    for (size_t i = 2; i < img.rgba.size(); ++i) {
        float v = img.rgba[i];
        // Half: 11 significant bits, relative error ≤ 2⁻¹¹ for normals; subnormals below 6.1e-5
        // have an absolute spacing of 2⁻²⁴.
        float tol = std::max(std::abs(v) * 0x1p-11f, 0x1p-25f);
        EXPECT_NEAR(back.rgba[i], v, tol) << i;
        if (std::abs(v) > 1e-4f) maxRel = std::max(maxRel, double(std::abs(back.rgba[i] - v) / v));
    }
    std::cout << "[ measured ] half round trip max relative error = " << maxRel << "\n";
}

TEST(ImageIoTest, HeaderAsExrheaderSeesIt) {
    if (::access("/usr/bin/exrheader", X_OK) != 0) GTEST_SKIP() << "exrheader is absent";
    std::string path = test::tempDir() + "/beauty.exr";
    writeExr(path, testImage(4, 4), acescgOptions(true));
    std::string out;
    ASSERT_EQ(test::runCommand("/usr/bin/exrheader '" + path + "'", &out), 0) << out;
    EXPECT_NE(out.find("chromaticities (type chromaticities)"), std::string::npos) << out;
    EXPECT_NE(out.find("red   (0.713 0.293)"), std::string::npos) << out;
    EXPECT_NE(out.find("white (0.32168 0.33767)"), std::string::npos) << out;
    EXPECT_NE(out.find("compression (type compression): zip"), std::string::npos) << out;
    EXPECT_NE(out.find("16-bit floating-point"), std::string::npos) << out;
    EXPECT_NE(out.find("mirage:spp (type string): \"64\""), std::string::npos) << out;
    EXPECT_NE(out.find("mirage:colorSpace (type string): \"ACEScg\""), std::string::npos) << out;
    EXPECT_NE(out.find("A, 16-bit"), std::string::npos) << out;
}

TEST(ImageIoTest, MissingOutputFolderIsCreated) {
    std::string path = test::tempDir() + "/shots/sh010/beauty.exr";
    writeExr(path, testImage(2, 2), ExrOptions());
    EXPECT_TRUE(fs::is_regular_file(path));
}

TEST(ImageIoTest, FailedWritesThrowAndLeaveNoTemporaryFile) {
    std::string dir = test::tempDir();
    Image img = testImage(3, 3);

    // The parent "folder" is a regular file: it cannot be created.
    std::ofstream(dir + "/notafolder") << "x";
    std::string path = dir + "/notafolder/beauty.exr";
    try {
        writeExr(path, img, ExrOptions());
        FAIL() << "expected a MirageError";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }

    // The target is an existing folder: the file is written, then cannot be renamed over it.
    fs::create_directories(dir + "/taken.exr/inside");
    EXPECT_THROW(writeExr(dir + "/taken.exr", img, ExrOptions()), MirageError);
    EXPECT_TRUE(tempFiles(dir).empty());

    // A read-only folder (root ignores permissions, so only as another user).
    if (::geteuid() != 0) {
        std::string ro = dir + "/readonly";
        fs::create_directories(ro);
        ::chmod(ro.c_str(), 0555);
        EXPECT_THROW(writeExr(ro + "/beauty.exr", img, ExrOptions()), MirageError);
        EXPECT_THROW(writeExr(ro + "/sub/beauty.exr", img, ExrOptions()), MirageError);
        EXPECT_TRUE(tempFiles(ro).empty());
        ::chmod(ro.c_str(), 0755);
    }
    // /proc refuses new entries, even for root.
    EXPECT_THROW(writeExr("/proc/mirage_test/beauty.exr", img, ExrOptions()), MirageError);

    // A failed write leaves an existing good file untouched.
    std::string good = dir + "/good.exr";
    writeExr(good, img, ExrOptions());
    Image empty;
    EXPECT_THROW(writeExr(good, empty, ExrOptions()), MirageError);
    EXPECT_EQ(readExr(good).rgba.size(), img.rgba.size());
    EXPECT_THROW(writeExr(dir + "/wrong.png", img, ExrOptions()), MirageError);
    EXPECT_TRUE(tempFiles(dir).empty());
}

TEST(ImageIoTest, ReadingAMissingOrBrokenFileThrows) {
    std::string dir = test::tempDir();
    EXPECT_THROW(readExr(dir + "/missing.exr"), MirageError);
    std::ofstream(dir + "/broken.exr") << "not an exr";
    try {
        readExr(dir + "/broken.exr");
        FAIL() << "expected a MirageError";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.exr"), std::string::npos) << e.what();
    }
}

TEST(ImageIoTest, MissingAlphaReadsAsOne) {
    if (::access("/usr/bin/oiiotool", X_OK) != 0) GTEST_SKIP() << "oiiotool is absent";
    std::string path = test::tempDir() + "/rgb.exr";
    std::string out;
    ASSERT_EQ(test::runCommand("/usr/bin/oiiotool --pattern constant:color=0.25,0.5,0.75 2x2 3 "
                               "-d float -o '" +
                                   path + "'",
                               &out),
              0)
        << out;
    Image img = readExr(path);
    ASSERT_EQ(img.rgba.size(), 16u);
    EXPECT_EQ(img.pixel(1, 1)[0], 0.25f);
    EXPECT_EQ(img.pixel(1, 1)[1], 0.5f);
    EXPECT_EQ(img.pixel(1, 1)[2], 0.75f);
    EXPECT_EQ(img.pixel(1, 1)[3], 1.f);
}

// ACEScg grey 0.18 stays grey through the sRGB display (white maps to white) and is encoded by
// the sRGB curve as 1.055·0.18^(1/2.4) − 0.055 = 0.4614 → 118 of 255.
TEST(ImageIoTest, PreviewIsDisplayEncoded8Bit) {
    ::unsetenv("OCIO");
    ColorPipeline color("", "ACEScg");
    std::string dir = test::tempDir();
    // Two 8×8 blocks (one JPEG block each, so the lossy codec does not mix them): middle grey,
    // and an over-range red that the display clips.
    Image img;
    img.width = 16;
    img.height = 8;
    img.rgba.resize(16 * 8 * 4);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 16; ++x) {
            float* p = img.pixel(x, y);
            p[0] = x < 8 ? 0.18f : 5.f;
            p[1] = p[2] = x < 8 ? 0.18f : 0.f;
            p[3] = 1.f;
        }
    }
    for (const char* name : {"preview.png", "preview.jpg"}) {
        std::string path = dir + "/" + name;
        writePreview(path, img, color, "sRGB", "Standard");
        Image back = readExr(path);  // OIIO reads any format; 8 bit comes back as [0, 1]
        ASSERT_EQ(back.width, 16);
        float tol = std::string(name).find(".png") != std::string::npos ? 0.5f : 3.f;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.pixel(3, 3)[c] * 255.f, 118.f, tol) << name;
        EXPECT_NEAR(back.pixel(12, 3)[0] * 255.f, 255.f, tol) << name;  // clipped highlight
    }
    EXPECT_THROW(writePreview(dir + "/preview.tif", img, color, "sRGB", "Standard"), MirageError);
    EXPECT_THROW(writePreview(dir + "/p.png", img, color, "sRGB", "Nope"), MirageError);
    EXPECT_TRUE(tempFiles(dir).empty());
}

}  // namespace
}  // namespace mirage
