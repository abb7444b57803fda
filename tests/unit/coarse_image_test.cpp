// The coarse image (render/coarse_image.h) and its magnification (film/film_resample.h): the
// bilinear magnification exact on a linear image, empty pixels left out; the coarse image's
// samples continuing so that 1 + 1 + 2 samples are the same bits as 4; a time limit below one
// full pass delivering it, and a time limit that fits full passes dropping it (the image is the
// passes' bits); a render's deadline leaving every tile undone; and the command: a time-limited
// frame records its coarse image and `--coarse` reproduces it bit for bit.
#include "render/coarse_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "film/film_resample.h"
#include "film/image_io.h"
#include "render/passes.h"
#include "test_support.h"

using namespace mirage;

namespace {

// A render in passes with a coarse stage by the path tracer; `prepared` counts the calls of the
// deferred set-up.
Film renderWithCoarse(const RenderScene& scene, const RenderSettings& s, const PassSettings& p,
                      PassReport* report, int* prepared) {
    auto frameIntegrator = makeVolPathIntegrator();
    auto coarse = makeVolPathIntegrator();
    PassRun run;
    run.coarse.integrator = coarse.get();
    run.coarse.prepareFullPasses = [&] { ++*prepared; };
    PassResult r = renderPasses(scene, *frameIntegrator, s, p, run);
    *report = r.report;
    return std::move(r.film);
}

Film coarseOf(const RenderScene& scene, const RenderSettings& s, int spp) {
    auto volpath = makeVolPathIntegrator();
    CoarseImage image(s);
    EXPECT_TRUE(addCoarseSamples(scene, *volpath, s, spp, &image));
    return magnifyCoarse(image, s);
}

}  // namespace

// Bilinear interpolation reproduces a linear function exactly: result pixel centres read the
// source at ((X + ½)·n/m − ½), clamped to the outer pixel centres.
TEST(FilmResample, MagnifyIsExactOnALinearImageAndLeavesOutEmptyPixels) {
    Film src(4, 3);
    auto value = [](double u, double v) { return 2.0 + 0.5 * u - 0.25 * v; };
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            Film::Pixel& p = src.pixel(x, y);
            p.samples = 1 + x + y;  // sums over several samples: the means are interpolated
            for (int c = 0; c < 3; ++c) p.xyz[c] = p.samples * value(x, y) * (c + 1);
            p.alpha = p.samples * 0.5;
        }
    const Film out = magnify(src, 8, 6);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            const double u = std::fmin(std::fmax((x + 0.5) / 2 - 0.5, 0.0), 3.0);
            const double v = std::fmin(std::fmax((y + 0.5) / 2 - 0.5, 0.0), 2.0);
            const Film::Pixel& q = out.pixel(x, y);
            ASSERT_EQ(q.samples, 1u);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(q.xyz[c], value(u, v) * (c + 1), 1e-12) << x << "," << y;
                EXPECT_DOUBLE_EQ(q.xyzSq[c], q.xyz[c] * q.xyz[c]);
            }
            EXPECT_NEAR(q.alpha, 0.5, 1e-12);
        }

    // A source pixel without samples is no pixel: it weighs nothing, and a result pixel that
    // reads only it stays empty.
    src.pixel(0, 0) = Film::Pixel{};
    src.pixel(0, 0).xyz[0] = 1e30;
    const Film holed = magnify(src, 8, 6);
    EXPECT_EQ(holed.pixel(0, 0).samples, 0u);
    EXPECT_NEAR(holed.pixel(1, 0).xyz[0], value(1, 0), 1e-12);  // src (1, 0) alone
}

TEST(CoarseImage, SamplesContinueSoOneOneAndTwoAreTheBitsOfFour) {
    const RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(4, 5, 30, 18);
    auto volpath = makeVolPathIntegrator();
    CoarseImage stepped(s), once(s);
    EXPECT_EQ(stepped.film.width(), 15);
    EXPECT_EQ(stepped.film.height(), 9);
    for (int spp : {1, 1, 2}) ASSERT_TRUE(addCoarseSamples(scene, *volpath, s, spp, &stepped));
    ASSERT_TRUE(addCoarseSamples(scene, *volpath, s, 4, &once));
    EXPECT_EQ(stepped.spp, 4);
    EXPECT_TRUE(test::sameFilm(stepped.film, once.film));
    const Film big = magnifyCoarse(once, s);
    EXPECT_EQ(big.width(), 30);
    EXPECT_EQ(big.height(), 18);
    EXPECT_GT(big.pixel(15, 9).xyz[1], 0.0);  // the smoke is in the middle
}

// A time limit that no full pass fits in: the image is the coarse image, whose sample count
// --coarse reproduces, and the frame integrator's set-up never runs.
TEST(CoarseImage, ATimeLimitBelowAFullPassDeliversTheCoarseImage) {
    const RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(4, 5, 24, 24);
    PassSettings limited;
    limited.sppPerPass = 4;
    limited.timeLimit = 1e-9;
    PassReport report;
    int prepared = 0;
    const Film film = renderWithCoarse(scene, s, limited, &report, &prepared);
    EXPECT_EQ(report.passes, 0);
    EXPECT_EQ(report.coarseSpp, 1);
    EXPECT_EQ(report.stop, "time limit (coarse image: no full pass fits)");
    EXPECT_EQ(report.samples, 12u * 12u);
    EXPECT_EQ(prepared, 0);
    EXPECT_TRUE(test::sameFilm(film, coarseOf(scene, s, 1)));

    PassSettings asked;
    asked.coarseSpp = 3;
    const Film three = renderWithCoarse(scene, s, asked, &report, &prepared);
    EXPECT_EQ(report.coarseSpp, 3);
    EXPECT_EQ(report.stop, "coarse image (--coarse)");
    EXPECT_EQ(prepared, 0);
    EXPECT_TRUE(test::sameFilm(three, coarseOf(scene, s, 3)));
}

// A time limit that full passes fit in: the coarse image is dropped and the image is the bits of
// the same passes rendered without a coarse stage; the set-up runs once, before them.
TEST(CoarseImage, FullPassesThatFitDropTheCoarseImage) {
    const RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(4, 5, 24, 24);
    PassSettings p;
    p.sppPerPass = 2;
    p.maxPasses = 2;
    p.timeLimit = 1e6;
    PassReport report;
    int prepared = 0;
    const Film film = renderWithCoarse(scene, s, p, &report, &prepared);
    EXPECT_EQ(report.passes, 2);
    EXPECT_EQ(report.coarseSpp, 0);
    EXPECT_EQ(report.stop, "passes");
    EXPECT_EQ(prepared, 1);
    auto volpath = makeVolPathIntegrator();
    p.timeLimit = 0;
    const Film plain = renderPasses(scene, *volpath, s, p).film;
    EXPECT_TRUE(test::sameFilm(film, plain));
}

// The deadline a time limit sets on the first full pass: no tile starts after it.
TEST(CoarseImage, NoTileStartsAfterTheDeadline) {
    const RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(2, 5, 24, 24);
    auto volpath = makeVolPathIntegrator();
    TileCheckpoint late;
    late.deadline = std::chrono::steady_clock::now();
    RenderStats stats;
    const Film film = render(scene, *volpath, s, &stats, &late);
    EXPECT_TRUE(stats.interrupted);
    EXPECT_EQ(stats.tilesDone, 0);
    EXPECT_EQ(film.pixel(12, 12).samples, 0u);
}

// The command: a photon render whose time limit no full pass fits gets the coarse image by the
// path tracer, recorded in its header, and `--coarse <coarse_spp>` renders the same bits.
TEST(CoarseImageCli, ATimeLimitedFrameRecordsItsCoarseImageAndIsReproducedByIt) {
    const std::string dir = test::tempDir();
    const std::string scene =
        test::writeFogSphereScene(dir, "resolution = [24, 24]\n", "integrator = \"photon\"\n");
    std::map<std::string, std::string> timed =
        test::renderMetadata(scene, "--time-limit 0.001", dir + "/timed.exr");
    EXPECT_EQ(timed["mirage:passes"], "0");
    EXPECT_EQ(timed["mirage:coarse_spp"], "1");
    EXPECT_EQ(timed["mirage:coarse_resolution"], "12x12");
    EXPECT_EQ(timed["mirage:integrator"], "photon");
    EXPECT_EQ(timed["mirage:coarse_integrator"], "volpath");  // no photon map in the image
    EXPECT_EQ(timed["mirage:photons_traced"], "0");
    EXPECT_EQ(timed["mirage:stopped_by"], "time limit (coarse image: no full pass fits)");
    EXPECT_EQ(timed["mirage:spp"], "1");
    std::map<std::string, std::string> asked =
        test::renderMetadata(scene, "--coarse 1", dir + "/coarse.exr");
    EXPECT_EQ(asked["mirage:coarse_spp"], "1");
    const Image a = readExr(dir + "/timed.exr"), b = readExr(dir + "/coarse.exr");
    ASSERT_EQ(a.width, 24);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));

    std::string out;
    EXPECT_NE(0,
              test::runMirage(
                  "render '" + scene + "' -q --coarse 2 --aov depth -o '" + dir + "/x.exr'", &out));
    EXPECT_NE(out.find("--coarse renders the whole frame's beauty alone"), std::string::npos)
        << out;
    EXPECT_NE(
        0, test::runMirage("render '" + scene + "' -q --coarse 2 --passes 2 -o '" + dir + "/y.exr'",
                           &out));
    EXPECT_NE(out.find("--passes excludes --coarse"), std::string::npos) << out;
}
