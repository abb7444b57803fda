// Saved photon passes (photon/photon_file.h, mirage photons, mirage render --photons-file): the
// file gives back every photon and figure bit for bit; a truncated, corrupt, foreign-version or
// foreign-magic file is refused with its reason; a render from the file is the same bits as a
// render that traces its own photons; a file of another frame or other settings is refused.
#include "photon/photon_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

PhotonPassResult samplePass() {
    PhotonPassResult r;
    for (int i = 0; i < 5; ++i) {
        Photon p;
        p.p = Vec3(0.1f * i, -2.f, 3.5f + i);
        p.wi = Vec3(0.f, 0.6f, -0.8f);
        p.lambda = 400.f + i;
        p.power = 1e-6f * float(i + 1);
        p.lambdaIn = i == 2 ? 380.f : 0.f;
        p.time = -0.01f * i;
        p.light = i == 3 ? Photon::kFromMedium : uint32_t(i);
        r.maps.volume.push_back(p);
        if (i < 2) r.maps.surfaceGlobal.push_back(p);
        if (i == 4) r.maps.surfaceCaustic.push_back(p);
    }
    r.stats.emitted = 1000;
    r.stats.stored = 8;
    r.stats.cappedPaths = 3;
    r.stats.nonFinite = 1;
    r.stats.fromMedia = 7;
    r.stats.mediumPower = 12.5;
    r.stats.emittedPower = 99.25;
    r.stats.seconds = 0.125;
    return r;
}

PhotonFileHeader sampleHeader() {
    PhotonFileHeader h;
    h.frame = 42;
    h.fingerprint = "0123456789abcdef";
    return h;
}

bool samePhotons(const PhotonList& a, const PhotonList& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Photon)) == 0);
}

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// The MirageError message of reading `path`, "" when it reads.
std::string refusal(const std::string& path) {
    try {
        readPhotonFile(path, nullptr);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PhotonFile, RoundTripsEveryPhotonAndFigureBitForBit) {
    const std::string path = test::tempDir() + "/f.photons";
    const PhotonPassResult pass = samplePass();
    writePhotonFile(path, sampleHeader(), pass);
    PhotonFileHeader h;
    const PhotonPassResult back = readPhotonFile(path, &h);
    EXPECT_EQ(h.version, kPhotonFileVersion);
    EXPECT_EQ(h.frame, 42u);
    EXPECT_EQ(h.fingerprint, "0123456789abcdef");
    EXPECT_EQ(h.volume, 5u);
    EXPECT_EQ(h.global, 2u);
    EXPECT_EQ(h.caustic, 1u);
    EXPECT_TRUE(samePhotons(back.maps.volume, pass.maps.volume));
    EXPECT_TRUE(samePhotons(back.maps.surfaceGlobal, pass.maps.surfaceGlobal));
    EXPECT_TRUE(samePhotons(back.maps.surfaceCaustic, pass.maps.surfaceCaustic));
    EXPECT_EQ(back.stats.emitted, 1000u);
    EXPECT_EQ(back.stats.cappedPaths, 3u);
    EXPECT_EQ(back.stats.fromMedia, 7u);
    EXPECT_EQ(back.stats.emittedPower, 99.25);
    EXPECT_TRUE(readPhotonFileHeader(path, nullptr));
}

TEST(PhotonFile, TruncatedCorruptAndForeignFilesAreRefusedWithTheirReason) {
    const std::string dir = test::tempDir();
    const std::string good = dir + "/good.photons";
    writePhotonFile(good, sampleHeader(), samplePass());
    const std::string bytes = bytesOf(good);
    const std::string bad = dir + "/bad.photons";

    writeBytes(bad, bytes.substr(0, bytes.size() - 9));
    EXPECT_NE(refusal(bad).find("truncated"), std::string::npos) << refusal(bad);
    writeBytes(bad, bytes.substr(0, 20));
    EXPECT_NE(refusal(bad).find("truncated"), std::string::npos) << refusal(bad);
    EXPECT_FALSE(readPhotonFileHeader(bad, nullptr));

    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;  // one bit of one photon
    writeBytes(bad, flipped);
    EXPECT_NE(refusal(bad).find("checksum does not match"), std::string::npos) << refusal(bad);
    EXPECT_FALSE(readPhotonFileHeader(bad, nullptr));

    std::string version = bytes;
    version[8] = 9;  // the format version's low byte
    writeBytes(bad, version);
    EXPECT_NE(refusal(bad).find("format version 9, this mirage reads version 2"), std::string::npos)
        << refusal(bad);

    writeBytes(bad, "P3\n2 2\n255\n" + bytes);
    EXPECT_NE(refusal(bad).find("magic 'MIRAGEPH'"), std::string::npos) << refusal(bad);
    EXPECT_NE(refusal(bad).find(bad), std::string::npos) << "the message names the file";
    EXPECT_NE(refusal(dir + "/none.photons").find("cannot open"), std::string::npos);
}

namespace {

// The fog sphere, photon integrator.
std::string writeScene(const std::string& dir) {
    return test::writeFogSphereScene(dir, "resolution = [32, 20]\ntile_size = 8\nspp = 2\nseed = 5",
                                     "integrator = \"photon\"\nphotons = 8000");
}

int mirage(const std::string& args, std::string* out) {
    return test::runCommand("'" + test::mirageBinary() + "' " + args, out);
}

}  // namespace

TEST(PhotonFileCli, ARenderFromTheFileIsTheRenderThatTracedItsOwnPhotons) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    ASSERT_EQ(
        mirage("photons '" + scene + "' --frame 3 -q --threads 1 -o '" + dir + "/p.$F4.photons'",
               &out),
        0)
        << out;
    ASSERT_TRUE(fs::exists(dir + "/p.0003.photons")) << out;
    ASSERT_EQ(mirage("render '" + scene + "' --frame 3 -q --float -o '" + dir + "/own.exr'", &out),
              0)
        << out;
    ASSERT_EQ(mirage("render '" + scene + "' --frame 3 -q --float --threads 2 --photons-file '" +
                         dir + "/p.$F4.photons' -o '" + dir + "/file.exr'",
                     &out),
              0)
        << out;
    std::map<std::string, std::string> a, b;
    const Image own = readExr(dir + "/own.exr", &a), file = readExr(dir + "/file.exr", &b);
    ASSERT_EQ(own.rgba.size(), file.rgba.size());
    size_t differ = 0;
    for (size_t i = 0; i < own.rgba.size(); ++i) differ += own.rgba[i] != file.rgba[i];
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(a["mirage:photons_stored"], b["mirage:photons_stored"]);

    // --skip-existing keeps an intact file.
    const auto stamp = fs::last_write_time(dir + "/p.0003.photons");
    ASSERT_EQ(
        mirage("photons '" + scene + "' --frame 3 --skip-existing -o '" + dir + "/p.0003.photons'",
               &out),
        0)
        << out;
    EXPECT_NE(out.find("is complete, skipped"), std::string::npos) << out;
    EXPECT_EQ(fs::last_write_time(dir + "/p.0003.photons"), stamp);
}

TEST(PhotonFileCli, AFileOfAnotherFrameOrOtherSettingsIsRefused) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    const std::string file = dir + "/p.photons";
    std::string out;
    ASSERT_EQ(mirage("photons '" + scene + "' -q -o '" + file + "'", &out), 0) << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --frame 2 --photons-file '" + file + "' -o '" +
                         dir + "/r.exr'",
                     &out),
              1);
    EXPECT_NE(out.find("holds the photons of frame 1, not of frame 2"), std::string::npos) << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --seed 9 --photons-file '" + file + "' -o '" + dir +
                         "/r.exr'",
                     &out),
              1);
    EXPECT_NE(out.find("made from another scene or other settings"), std::string::npos) << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --set render.photons=9000 --photons-file '" + file +
                         "' -o '" + dir + "/r.exr'",
                     &out),
              1);
    EXPECT_EQ(mirage("render '" + scene + "' -q --integrator single --photons-file '" + file +
                         "' -o '" + dir + "/r.exr'",
                     &out),
              1);
    EXPECT_NE(out.find("traces no photons"), std::string::npos) << out;
    // What does not decide the photons may differ: samples, resolution, the region.
    EXPECT_EQ(mirage("render '" + scene + "' -q --spp 1 --region 0,0,8,8 --photons-file '" + file +
                         "' -o '" + dir + "/r.exr'",
                     &out),
              0)
        << out;
    EXPECT_EQ(readExr(dir + "/r.exr").width, 8);
}

TEST(FarmCli, DryRunPrintsThePhotonRenderAndAssemblyArrays) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    ASSERT_EQ(mirage("farm '" + scene +
                         "' --frames 1-3 --tiles 2x2 --partition gpu --time-limit "
                         "1:00:00 --dry-run -d '" +
                         dir + "/shot' --spp 4 --set film.seed=2",
                     &out),
              0)
        << out;
    EXPECT_FALSE(fs::exists(dir + "/shot")) << "a dry run writes nothing";
    auto has = [&](const std::string& s) { return out.find(s) != std::string::npos; };
    EXPECT_TRUE(has("/shot/scripts/photons.sh\n")) << out;
    EXPECT_TRUE(has("#SBATCH --array=1-3\n")) << out;
    EXPECT_TRUE(has("#SBATCH --requeue\n")) << out;
    EXPECT_TRUE(has("#SBATCH --partition=gpu\n")) << out;
    EXPECT_TRUE(has("#SBATCH --time=1:00:00\n")) << out;
    EXPECT_TRUE(has("/shot/logs/render.f%4a.t03.log")) << out;
    EXPECT_TRUE(has("photons '" + scene + "' --frame \"$F\" -o " + dir +
                    "/shot/photons/\"$F4\".photons -q '--set' 'film.seed=2'"))
        << out;
    // The 32×20 frame in 2×2 tiles, each render after its frame's photons.
    for (const char* region : {"0,0,16,10", "16,0,32,10", "0,10,16,20", "16,10,32,20"})
        EXPECT_TRUE(has(std::string("--region ") + region)) << region << "\n" << out;
    EXPECT_TRUE(has("render.t02.sh  (aftercorr: photons.sh)")) << out;
    EXPECT_TRUE(has("--resume -q --photons-file")) << out;
    EXPECT_TRUE(has("'--spp' '4'")) << out;
    EXPECT_TRUE(
        has("assemble.sh  (aftercorr: render.t00.sh, render.t01.sh, render.t02.sh, "
            "render.t03.sh)"))
        << out;
    EXPECT_TRUE(has("/shot/frames/'scene'.\"$F4\".exr")) << out;

    // Without a photon pass: no photon array, no dependency of the renders.
    ASSERT_EQ(mirage("farm '" + scene + "' --frames 2-2 --integrator single --dry-run -d '" + dir +
                         "/shot'",
                     &out),
              0)
        << out;
    EXPECT_FALSE(has("photons.sh")) << out;
    EXPECT_TRUE(has("render.t00.sh\n")) << out;
    EXPECT_TRUE(has("--region 0,0,32,20")) << out;

    // A bad tile grid is one clear error.
    EXPECT_EQ(mirage("farm '" + scene + "' --frames 1-2 --tiles 2by2 --dry-run", &out), 1);
    EXPECT_TRUE(has("--tiles '2by2': expected CxR")) << out;
}

}  // namespace mirage
