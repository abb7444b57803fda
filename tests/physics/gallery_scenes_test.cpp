// The gallery's scenes show the effect each is there for (their header comments say what to look
// for), measured on a cheap, reduced render of the shipped scene file:
//  - fata_morgana.toml (Gutierrez et al. 2005, figure 4): images of the ship stacked in one
//    column, upright and inverted: its red funnel above its white deck house in some, below it
//    in others (~5 s on 2 cores).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// Renders a copy of a shipped scene quietly on two threads; the image, or a failed assertion.
Image renderShipped(const std::string& name, const std::string& args) {
    const std::string scene = test::shippedSceneCopy(test::tempDir(), name);
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

}  // namespace
}  // namespace mirage
