// Radiance RGBE pictures read without OpenImageIO (light/radiance_hdr.h): known values from both
// scanline encodings, the same floats as OIIO's reader, and the files it leaves to OIIO or
// refuses with the file's name.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "light/dome_light.h"
#include "light/radiance_hdr.h"
#include "test_support.h"

namespace mirage {
namespace {

using Pixel = std::array<unsigned char, 4>;

// A picture width × height whose pixel (i, j) is pixelAt(i, j), its scanlines run-length
// encoded (a run of each scanline's first pixel, then literals) or flat.
template <class F>
std::string writeHdr(const std::string& name, int width, int height, bool encoded, F pixelAt) {
    const std::string path = test::tempDir() + "/" + name;
    std::ofstream f(path, std::ios::binary);
    f << "#?RADIANCE\n# written by radiance_hdr_test\nFORMAT=32-bit_rle_rgbe\n\n-Y " << height
      << " +X " << width << "\n";
    for (int j = 0; j < height; ++j) {
        if (!encoded) {
            for (int i = 0; i < width; ++i)
                for (unsigned char b : pixelAt(i, j)) f.put(char(b));
            continue;
        }
        f.put(2).put(2).put(char(width >> 8)).put(char(width & 0xff));
        for (int plane = 0; plane < 4; ++plane) {
            // A run of 3 copies of pixel 0's byte, then the rest as literals.
            f.put(char(128 + 3)).put(char(pixelAt(0, j)[size_t(plane)]));
            f.put(char(width - 3));
            for (int i = 3; i < width; ++i) f.put(char(pixelAt(i < 3 ? 0 : i, j)[size_t(plane)]));
        }
    }
    return path;
}

Pixel sample(int i, int j) {
    // Exponents across the range, zero exponent (black) on one pixel per row.
    if (i == 5) return {200, 100, 50, 0};
    return {(unsigned char)(17 * i + j), (unsigned char)(255 - i), (unsigned char)(3 * j + 1),
            (unsigned char)(100 + 7 * i + j)};
}

float expected(const Pixel& p, int k) {
    return p[3] ? float(p[size_t(k)]) * std::ldexp(1.f, int(p[3]) - 136) : 0.f;
}

TEST(RadianceHdr, BothEncodingsGiveTheMantissaTimesTheExponent) {
    for (bool encoded : {true, false}) {
        // The encoded rows repeat pixel 0 three times, as written.
        auto at = [&](int i, int j) { return sample(encoded && i < 3 ? 0 : i, j); };
        const std::string path = writeHdr(encoded ? "rle.hdr" : "flat.hdr", 12, 3, encoded, at);
        RadianceHdr hdr;
        ASSERT_TRUE(readRadianceHdr(path, &hdr)) << path;
        ASSERT_EQ(hdr.width, 12);
        ASSERT_EQ(hdr.height, 3);
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 12; ++i)
                for (int k = 0; k < 3; ++k)
                    EXPECT_EQ(hdr.rgb[size_t(3 * (j * 12 + i) + k)], expected(at(i, j), k))
                        << "pixel " << i << ", " << j << ", channel " << k;
    }
}

// Pictures narrower than a run-length scanline's 12-byte least hold 4 bytes a pixel: a 1 × 1
// and a 2 × 2 picture are read, not refused as truncated (the fuzz corpus's seed found it).
TEST(RadianceHdr, TinyFlatPicturesAreRead) {
    for (int w : {1, 2}) {
        const std::string path =
            writeHdr("tiny" + std::to_string(w) + ".hdr", w, w, false, sample);
        RadianceHdr hdr;
        ASSERT_TRUE(readRadianceHdr(path, &hdr)) << path;
        ASSERT_EQ(hdr.width, w);
        ASSERT_EQ(hdr.height, w);
        for (int j = 0; j < w; ++j)
            for (int i = 0; i < w; ++i)
                EXPECT_EQ(hdr.rgb[size_t(3 * (j * w + i))], expected(sample(i, j), 0));
    }
}

// OIIO 2.4's reader is one ulp low at three exponents (40, 223 and 226: values near 1e-29 and
// 1e26, found by reading every exponent), exact elsewhere; a sky's pixels lie far inside.
TEST(RadianceHdr, TheSameFloatsAsOpenImageIO) {
    const std::string path = writeHdr("oiio.hdr", 40, 7, true, sample);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    std::vector<float> oiio(40 * 7 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeFloat, oiio.data()));
    const LatLongImage dome = readLatLongImage(path);
    ASSERT_EQ(dome.rgb.size(), oiio.size());
    int inside = 0;
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 40; ++i) {
            const int e = sample(i, j)[3];
            const bool oiioExact = e > 40 && e < 223;
            inside += oiioExact;
            for (int k = 0; k < 3; ++k) {
                const size_t v = size_t(3 * (j * 40 + i) + k);
                if (oiioExact)
                    EXPECT_EQ(dome.rgb[v], oiio[v]) << "pixel " << i << ", " << j;
                else
                    EXPECT_LE(std::abs(dome.rgb[v] - oiio[v]), std::abs(oiio[v]) * 1.2e-7f);
            }
        }
    EXPECT_GT(inside, 180);  // of 280 pixels
}

TEST(RadianceHdr, OtherFilesAreLeftToOpenImageIOAndBrokenOnesNamed) {
    RadianceHdr hdr;
    const std::string text = test::tempDir() + "/not_hdr.hdr";
    std::ofstream(text) << "P3\n1 1\n255\n0 0 0\n";
    EXPECT_FALSE(readRadianceHdr(text, &hdr));
    EXPECT_FALSE(readRadianceHdr(test::tempDir() + "/absent.hdr", &hdr));
    const std::string xyz = test::tempDir() + "/xyze.hdr";
    std::ofstream(xyz) << "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n";
    EXPECT_FALSE(readRadianceHdr(xyz, &hdr));

    const std::string whole = writeHdr("whole.hdr", 12, 3, true, sample);
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string cut = test::tempDir() + "/cut.hdr";
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 10);
    try {
        readRadianceHdr(cut, &hdr);
        FAIL() << "expected a MirageError";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find(cut + ": the RGBE picture is truncated"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace mirage
