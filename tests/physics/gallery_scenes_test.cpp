// The gallery's scenes show the effect each is there for (their header comments say what to look
// for), measured on a cheap, reduced render of the shipped scene file:
//  - fata_morgana.toml (Gutierrez et al. 2005, figure 4): images of the ship stacked in one
//    column, upright and inverted: its red funnel above its white deck house in some, below it
//    in others (~5 s on 2 cores).
//  - cornell_water_series.toml (figure 3): the bloom (5 mg/m³ of chlorophyll) greener, G/B,
//    than the clear box (0.05 mg/m³), the yellow-matter box the least blue (~10 s).
//  - split_sun.toml (figure 5): two bright bands of the sun separated by the fog's dark gap
//    along the vertical through the sun (~10 s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// Renders a copy of a shipped scene quietly on two threads (with the procedural cache it reads,
// made by `make-asset ASSET` at a low resolution); the image, or a failed assertion.
Image renderShipped(const std::string& name, const std::string& args,
                    const std::string& asset = "", const std::string& file = "") {
    const std::string scene = test::shippedSceneCopy(test::tempDir(), name, asset, file, 32);
    const std::string out = scene + ".exr";
    std::string log;
    EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + out + "' --threads 2 --quiet " + args,
                              &log),
              0)
        << log;
    return readExr(out);
}

enum class Paint { Other, Red, White };

// The ship's paints in the linear image: the funnel's red (reflectance 0.8, 0.1, 0.08: R ≈ 3 G
// as lit) and the deck house's white (0.85 grey), told from the blue sky (emission 0.55, 0.7,
// 1.0), the dark sea and the black hull.
Paint paintAt(const Image& im, int x, int y) {
    const float* p = im.pixel(x, y);
    if (p[0] > 0.2f && p[0] > 2.f * p[1]) return Paint::Red;
    if (p[1] > 0.4f && p[1] > 0.75f * p[0] && p[2] < 1.3f * p[1]) return Paint::White;
    return Paint::Other;
}

TEST(GalleryScenes, FataMorganaStacksUprightAndInvertedImages) {
    // 40 × 80 pixels over the scene's 0.7° of height: the centre column band holds the funnel.
    const Image im = renderShipped("fata_morgana.toml", "--resolution 40x80 --spp 4");
    ASSERT_EQ(im.height, 80);
    // The column richest in red: through the funnel's images.
    int best = -1, bestRed = 0;
    for (int x = 0; x < im.width; ++x) {
        int red = 0;
        for (int y = 0; y < im.height; ++y) red += paintAt(im, x, y) == Paint::Red ? 1 : 0;
        if (red > bestRed) {
            bestRed = red;
            best = x;
        }
    }
    ASSERT_GE(best, 0) << "no red funnel in the frame";
    // The column's runs of paint from the bottom up, runs of one pixel (edges, noise) and other
    // colours between them dropped.
    std::vector<Paint> runs;
    for (int y = im.height - 1; y >= 0;) {
        const Paint p = paintAt(im, best, y);
        int length = 0;
        while (y >= 0 && paintAt(im, best, y) == p) {
            ++length;
            --y;
        }
        if (p != Paint::Other && length >= 2 && (runs.empty() || runs.back() != p))
            runs.push_back(p);
    }
    int redRuns = 0, upright = 0, inverted = 0;
    std::string seq;
    for (size_t i = 0; i < runs.size(); ++i) {
        seq += runs[i] == Paint::Red ? 'R' : 'W';
        if (runs[i] != Paint::Red) continue;
        ++redRuns;
        if (i > 0 && runs[i - 1] == Paint::White) ++upright;                 // red above white
        if (i + 1 < runs.size() && runs[i + 1] == Paint::White) ++inverted;  // red below white
    }
    std::printf("column %d, bottom to top: %s\n", best, seq.c_str());
    // Straight rays would show one upright ship: one red run, above the white. Here (measured:
    // RWRW from the bottom) the inverted image under the ship, the ship, and the inverted image
    // above it, whose funnel meets the ship's: two red runs, both under white, one over it.
    EXPECT_GE(redRuns, 2) << seq;
    EXPECT_GE(upright, 1) << seq;
    EXPECT_GE(inverted, 2) << seq;
}

// Mean linear R, G, B over a window of the image given as fractions of its width and height.
struct Rgb {
    double r = 0, g = 0, b = 0;
};
Rgb meanOver(const Image& im, double x0, double x1, double y0, double y1) {
    Rgb m;
    int n = 0;
    for (int y = int(y0 * im.height); y < int(y1 * im.height); ++y)
        for (int x = int(x0 * im.width); x < int(x1 * im.width); ++x) {
            const float* p = im.pixel(x, y);
            m.r += p[0];
            m.g += p[1];
            m.b += p[2];
            ++n;
        }
    m.r /= n;
    m.g /= n;
    m.b /= n;
    return m;
}

TEST(GalleryScenes, CornellWaterSeriesBloomIsGreener) {
    // 128 × 34 pixels, 64 samples: each box's back wall through its water, a window about the
    // box's centre (the centres of the back walls fall at 0.16, 0.39, 0.61, 0.84 of the width).
    const Image im = renderShipped("cornell_water_series.toml", "--resolution 128x34 --spp 64");
    ASSERT_EQ(im.width, 128);
    Rgb box[4];
    const double centre[4] = {0.162, 0.387, 0.613, 0.838};
    for (int i = 0; i < 4; ++i) {
        box[i] = meanOver(im, centre[i] - 0.05, centre[i] + 0.05, 0.3, 0.8);
        std::printf("box %d: R %.4f G %.4f B %.4f  G/B %.3f\n", i, box[i].r, box[i].g, box[i].b,
                    box[i].g / box[i].b);
    }
    // Clear water is blue-green (more blue than red); the bloom's particles and their green
    // light raise G/B well above it (published: chlorophyll moves the sea from blue to green,
    // ocean_colour_test.cpp measures the same on deep water).
    EXPECT_GT(box[0].b, box[0].r);
    EXPECT_GT(box[2].g / box[2].b, 1.15 * (box[0].g / box[0].b));  // measured 1.29×
    // Yellow matter absorbs the blue first: the least blue box relative to its green.
    for (int i = 0; i < 3; ++i) EXPECT_GT(box[3].g / box[3].b, box[i].g / box[i].b) << i;
}

TEST(GalleryScenes, VolumeCausticConeGlowsGreen) {
    // 48 × 48 pixels, 8 passes (a photon map each): the focused cone under the ball (columns
    // 0.46–0.54, rows 0.56–0.69) and the beam above it (rows 0.12–0.25). The spot light is
    // white (5500 K) and the dye absorbs around 490 nm: without its re-emission at 515 nm the
    // cone is reddish (measured G/R 0.77 with Γ = 0), with it green (measured G/R 1.42, G/B 1.9).
    const Image im = renderShipped("volume_caustic.toml", "--resolution 48x48 --passes 8",
                                   "fog-sphere", "fog_sphere.vdb");
    ASSERT_EQ(im.width, 48);
    const Rgb cone = meanOver(im, 0.46, 0.54, 0.56, 0.69),
              beam = meanOver(im, 0.46, 0.54, 0.12, 0.25);
    std::printf("cone: R %.4f G %.4f B %.4f; beam: R %.4f G %.4f B %.4f\n", cone.r, cone.g, cone.b,
                beam.r, beam.g, beam.b);
    for (const Rgb& c : {cone, beam}) {
        EXPECT_GT(c.g, 1.2 * c.r);
        EXPECT_GT(c.g, 1.4 * c.b);
    }
}

TEST(GalleryScenes, SplitSunShowsTwoSeparatedBands) {
    // 90 × 60 pixels over the scene's 1° of height (measured on the round Earth: sun rows 16–24
    // and 34–43, gap 9 rows).
    const Image im = renderShipped("split_sun.toml", "--resolution 90x60 --spp 4", "fog-sphere",
                                   "fog_sphere.vdb");
    ASSERT_EQ(im.height, 60);
    auto luminance = [&](int x, int y) {
        const float* p = im.pixel(x, y);
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    };
    // The vertical through the sun: the brightest column.
    int column = 0;
    double best = -1;
    for (int x = 0; x < im.width; ++x) {
        double sum = 0;
        for (int y = 0; y < im.height; ++y) sum += luminance(x, y);
        if (sum > best) {
            best = sum;
            column = x;
        }
    }
    double peak = 0;
    for (int y = 0; y < im.height; ++y) peak = std::max(peak, luminance(column, y));
    // Runs of sun (above half the peak) from the top down, and the darkest pixel between the
    // first two.
    std::vector<std::pair<int, int>> bands;
    for (int y = 0; y < im.height; ++y) {
        if (luminance(column, y) < 0.5 * peak) continue;
        if (!bands.empty() && bands.back().second == y - 1)
            bands.back().second = y;
        else
            bands.push_back({y, y});
    }
    std::string profile;
    for (const auto& b : bands)
        profile += "[" + std::to_string(b.first) + "–" + std::to_string(b.second) + "] ";
    std::printf("column %d, peak %.3f, sun rows %s\n", column, peak, profile.c_str());
    // Straight through clear air it would be one band; the fog layer cuts it in two.
    ASSERT_EQ(bands.size(), 2u) << profile;
    double gap = peak;
    for (int y = bands[0].second + 1; y < bands[1].first; ++y)
        gap = std::min(gap, luminance(column, y));
    EXPECT_GE(bands[1].first - bands[0].second - 1, 2) << profile;  // a gap of 2+ rows
    EXPECT_LT(gap, 0.1 * peak) << "gap " << gap << ", peak " << peak;
}

}  // namespace
}  // namespace mirage
