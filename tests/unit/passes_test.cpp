// Renders in passes (render/passes.h) and the film's error estimate (film/film_error.h): the
// variance of the mean against its closed form; the estimated relMSE against the error measured
// against a converged render; N passes of K samples equal to one render of N·K samples; a
// time-limited render reproduced bit for bit by its pass count, for a path integrator and for
// the progressive photon mapper, with one thread or two; the noise threshold met, with the
// later passes sampling only the noisy pixels; a render in passes interrupted and resumed equal
// to one rendered in one go; and the command's EXR records its passes, which reproduce it.
#include "render/passes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <thread>

#include "core/interrupt.h"
#include "film/film_error.h"
#include "film/image_io.h"
#include "render/photon_integrator.h"
#include "test_support.h"

using namespace mirage;

namespace {

PassSettings passes(int maxPasses, int spp = 2) {
    PassSettings p;
    p.maxPasses = maxPasses;
    p.sppPerPass = spp;
    return p;
}

std::unique_ptr<Integrator> photonMapper(uint64_t seed) {
    PhotonIntegratorSettings ps;
    ps.photons = 4000;
    ps.seed = seed;
    ps.progress = Progress::Mode::Quiet;
    return makePhotonIntegrator(ps);
}

Film renderInPasses(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
                    const PassSettings& p, PassReport* report = nullptr,
                    PassCheckpoint* checkpoint = nullptr) {
    integrator.preprocess(scene);
    PassRun run;
    run.checkpoint = checkpoint;
    PassResult r = renderPasses(scene, integrator, s, p, run);
    if (report) *report = r.report;
    return std::move(r.film);
}

}  // namespace

TEST(FilmError, VarianceOfTheMeanIsTheSampleVarianceOverN) {
    Film film(2, 1);
    // Y samples 1, 2, 3, 6 (a flat spectrum's XYZ scale cancels in the relative check): mean 3,
    // sample variance ((−2)² + (−1)² + 0² + 3²)/3 = 14/3, variance of the mean 14/12.
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    for (float v : {1.f, 2.f, 3.f, 6.f})
        film.addSample(0, 0, SampledSpectrum(0.f), w, 1.f, Vec3(v));
    for (int i = 0; i < 4; ++i) film.addSample(1, 0, SampledSpectrum(0.f), w, 1.f, Vec3(2.f));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(varianceOfMean(film.pixel(0, 0), c), 14.0 / 12.0, 1e-12);
    EXPECT_EQ(varianceOfMean(film.pixel(1, 0), 1), 0.0);  // a constant pixel
    // relMSE = mean over the two pixels of (14/12)/(3² + ε) and 0; ε = 10⁻³ · 2.5².
    FilmError e = estimateFilmError(film);
    EXPECT_EQ(e.pixels, 2u);
    EXPECT_NEAR(e.relMse, 0.5 * (14.0 / 12.0) / (9.0 + 6.25e-3), 1e-9);
    EXPECT_FLOAT_EQ(e.pixelError[1], 0.f);
}

TEST(FilmError, EstimatedRelMseMatchesTheErrorAgainstAConvergedRender) {
    // The estimator's promise: its relMSE is the expected relMSE against the converged image.
    // Measured here with the single-scatter integrator (independent samples) at 16 spp against
    // 512 spp (whose own noise adds 16/512 of the measured error), in XYZ over the covered
    // pixels as the estimator counts them. The estimate runs low by ~15 %: a pixel whose mean
    // came out high (a bright sample) has a larger m² in its denominator.
    RenderScene scene = test::sunlitSmokeBox();
    auto single = makeSingleScatterIntegrator();
    RenderSettings s = test::smallRenderSettings(16, 3, 24, 24);
    s.sampler = SamplerKind::Random;  // the estimator assumes independent samples
    Film image = render(scene, *single, s, nullptr);
    RenderSettings ref = test::smallRenderSettings(512, 4, 24, 24);
    Film reference = render(scene, *single, ref, nullptr);
    const FilmError estimate = estimateFilmError(image);
    double sum = 0, meanRef = 0;
    size_t n = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x)
            if (estimate.pixelError[size_t(y) * 24 + x] > 0)
                for (int c = 0; c < 3; ++c, ++n)
                    meanRef += reference.pixel(x, y).xyz[c] / reference.pixel(x, y).samples;
    const double eps = 1e-3 * std::pow(meanRef / double(n), 2.0);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            if (!(estimate.pixelError[size_t(y) * 24 + x] > 0)) continue;
            for (int c = 0; c < 3; ++c) {
                const double m = image.pixel(x, y).xyz[c] / image.pixel(x, y).samples;
                const double r = reference.pixel(x, y).xyz[c] / reference.pixel(x, y).samples;
                sum += (m - r) * (m - r) / (r * r + eps);
            }
        }
    const double measured = sum / double(n);
    std::printf("relMSE estimated %.4g, measured %.4g over %zu pixels\n", estimate.relMse, measured,
                estimate.pixels);
    EXPECT_GT(estimate.relMse, 0.7 * measured);
    EXPECT_LT(estimate.relMse, 1.3 * measured);
}

TEST(Passes, NPassesOfKSamplesAreOneRenderOfNKSamples) {
    RenderScene scene = test::sunlitSmokeBox();
    auto volpath = makeVolPathIntegrator();
    RenderSettings s = test::smallRenderSettings(6, 5, 20, 18);
    Film once = render(scene, *volpath, s, nullptr);
    PassReport report;
    Film inPasses = renderInPasses(scene, *volpath, s, passes(3), &report);
    EXPECT_EQ(report.passes, 3);
    EXPECT_EQ(report.stop, "passes");
    EXPECT_EQ(report.samples, uint64_t(6) * 20 * 18);
    EXPECT_TRUE(test::sameFilm(once, inPasses));
}

TEST(Passes, ATimeLimitedRenderIsReproducedByItsPassCount) {
    RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(1, 7, 24, 24);
    for (bool photon : {false, true}) {
        auto integrator = photon ? photonMapper(9) : makeVolPathIntegrator();
        PassSettings limited = passes(0);
        limited.timeLimit = 0.3;
        PassReport report;
        Film timed = renderInPasses(scene, *integrator, s, limited, &report);
        EXPECT_EQ(report.stop, "time limit");
        ASSERT_GE(report.passes, 1);
        for (int threads : {1, 2}) {
            tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
            auto again = photon ? photonMapper(9) : makeVolPathIntegrator();
            Film counted = renderInPasses(scene, *again, s, passes(report.passes));
            EXPECT_TRUE(test::sameFilm(timed, counted))
                << (photon ? "photon" : "volpath") << ", " << report.passes << " passes, "
                << threads << " thread(s)";
        }
    }
}

// An integrator whose second pass's set-up outlasts the time limit (a photon map larger than
// the first, as the progressive photon mapper's are): that pass starts no tile and is dropped.
class SlowSecondPass : public Integrator {
public:
    const IntegratorInfo& info() const override { return mInner->info(); }
    void beginPass(const RenderScene&, int pass) override {
        if (pass == 1) std::this_thread::sleep_for(std::chrono::milliseconds(1300));
    }
    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        return mInner->Li(scene, ray, w, sampler, ts);
    }
    bool lightShapedRadiance() const override { return mInner->lightShapedRadiance(); }

private:
    std::unique_ptr<Integrator> mInner = makeVolPathIntegrator();
};

TEST(Passes, APassStillRunningAtTheTimeLimitIsDropped) {
    const RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(1, 7, 16, 16);
    SlowSecondPass slow;
    PassSettings limited = passes(0);
    limited.timeLimit = 1.0;
    PassReport report;
    const Film timed = renderInPasses(scene, slow, s, limited, &report);
    EXPECT_EQ(report.stop, "time limit");
    EXPECT_EQ(report.passes, 1);  // pass 1 began after the limit: no tile of it is in the image
    auto volpath = makeVolPathIntegrator();
    EXPECT_TRUE(test::sameFilm(timed, renderInPasses(scene, *volpath, s, passes(1))));
}

TEST(Passes, NoiseThresholdIsMetAndLaterPassesSampleOnlyNoisyPixels) {
    RenderScene scene = test::sunlitSmokeBox();
    auto single = makeSingleScatterIntegrator();
    const RenderSettings s = test::smallRenderSettings(1, 2, 24, 24);
    PassSettings p = passes(0, 4);
    p.noiseThreshold = 0.03;
    PassReport report;
    Film film = renderInPasses(scene, *single, s, p, &report);
    EXPECT_EQ(report.stop.rfind("noise threshold", 0), 0u) << report.stop;
    EXPECT_LE(report.estimatedError, 0.03);
    EXPECT_NEAR(report.estimatedError, estimateFilmError(film).relError(), 1e-12);
    // Adaptive: the background (no smoke, no noise) stopped after the first passes, so pixels
    // hold different sample counts and the last pass sampled fewer than all of them.
    EXPECT_LT(report.lastPassPixels, size_t(24 * 24));
    uint32_t fewest = ~0u, most = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            fewest = std::min(fewest, film.pixel(x, y).samples);
            most = std::max(most, film.pixel(x, y).samples);
        }
    EXPECT_EQ(fewest, uint32_t(kMinAdaptivePasses * 4));
    EXPECT_GT(most, fewest);
}

TEST(Passes, InterruptedAndResumedEqualsOneGo) {
    RenderScene scene = test::sunlitSmokeBox();
    const RenderSettings s = test::smallRenderSettings(1, 3, 20, 20);
    PassSettings p = passes(5, 2);
    p.noiseThreshold = 1e-4;  // adaptive masks in play, never met
    for (bool photon : {false, true}) {
        auto whole = photon ? photonMapper(4) : makeVolPathIntegrator();
        Film oneGo = renderInPasses(scene, *whole, s, p);

        std::unique_ptr<Film> saved;
        int savedPasses = 0;
        PassCheckpoint stop;
        stop.stopAfterPasses = 3;
        stop.passFinished = [&](const Film& film, int n, double) {
            saved = std::make_unique<Film>(film);
            savedPasses = n;
        };
        auto first = photon ? photonMapper(4) : makeVolPathIntegrator();
        PassReport report;
        renderInPasses(scene, *first, s, p, &report, &stop);
        EXPECT_EQ(report.stop, "interrupted");
        EXPECT_EQ(report.passes, 3);
        clearInterrupt();
        ASSERT_TRUE(saved);

        PassCheckpoint resume;
        resume.initial = saved.get();
        resume.passesDone = savedPasses;
        auto second = photon ? photonMapper(4) : makeVolPathIntegrator();
        Film resumed = renderInPasses(scene, *second, s, p, &report, &resume);
        EXPECT_EQ(report.passes, 5);
        EXPECT_TRUE(test::sameFilm(oneGo, resumed)) << (photon ? "photon" : "volpath");
    }
}

TEST(PassesCli, ATimeLimitedFrameRecordsItsPassesAndIsReproducedByThem) {
    const std::string dir = test::tempDir();
    const std::string vdb = test::makeFogSphere(dir, 16);
    const std::string common = "render '" + vdb + "' --resolution 24x24 -q ";
    std::string out;
    ASSERT_EQ(
        0, test::runMirage(common + "--threads 2 --time-limit 1 -o '" + dir + "/timed.exr'", &out))
        << out;
    std::map<std::string, std::string> meta;
    const Image timed = readExr(dir + "/timed.exr", &meta);
    EXPECT_EQ(meta["mirage:stopped_by"], "time limit");
    EXPECT_EQ(meta["mirage:pass_spp"], "4");
    EXPECT_FALSE(meta["mirage:estimated_error"].empty());
    const int passes = std::atoi(meta["mirage:passes"].c_str());
    ASSERT_GE(passes, 1);
    EXPECT_EQ(meta["mirage:samples"], std::to_string(passes * 4 * 24 * 24));
    ASSERT_EQ(0, test::runMirage(common + "--threads 1 --passes " + std::to_string(passes) +
                                     " -o '" + dir + "/counted.exr'",
                                 &out))
        << out;
    const Image counted = readExr(dir + "/counted.exr");
    ASSERT_EQ(timed.rgba.size(), counted.rgba.size());
    EXPECT_EQ(
        0, std::memcmp(timed.rgba.data(), counted.rgba.data(), timed.rgba.size() * sizeof(float)));
}

// [render] passes: a scene that needs several photon maps states them. It renders in that many
// passes of pass_spp samples (the same bits as --passes), --quality final takes 4× the passes
// (and so 4× the maps, each of the stated photons), --passes replaces the count, and `mirage
// info` says it.
TEST(PassesCli, ASceneStatesItsPassesAndPhotonMaps) {
    const std::string dir = test::tempDir();
    test::makeFogSphere(dir, 16);
    const std::string body =
        "[film]\nresolution = [16, 16]\nseed = 3\n"
        "[render]\nintegrator = \"photon\"\nphotons = 2000\npass_spp = 2\n";
    const std::string light =
        "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
        "[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n";
    const std::string stated = test::writeFile(dir, "stated.toml", body + "passes = 3\n" + light);
    const std::string plain = test::writeFile(dir, "plain.toml", body + light);
    std::string out;
    auto render = [&](const std::string& scene, const std::string& args, const std::string& exr) {
        return test::renderMetadata(scene, args, dir + "/" + exr);
    };
    EXPECT_EQ(render(stated, "", "stated.exr")["mirage:passes"], "3");
    EXPECT_EQ(render(plain, "--passes 3", "cli.exr")["mirage:passes"], "3");
    const Image a = readExr(dir + "/stated.exr"), b = readExr(dir + "/cli.exr");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));
    std::map<std::string, std::string> final = render(stated, "--quality final", "final.exr");
    EXPECT_EQ(final["mirage:passes"], "12");
    EXPECT_EQ(final["mirage:photons_traced"], std::to_string(12 * 2000));  // 2000 per map
    EXPECT_EQ(render(stated, "--passes 1", "one.exr")["mirage:passes"], "1");
    ASSERT_EQ(0, test::runMirage("info '" + stated + "'", &out)) << out;
    EXPECT_NE(out.find("3 passes of 2 spp (a photon map each)"), std::string::npos) << out;
}
