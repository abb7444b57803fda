// Replays the fuzzing corpus (tests/fuzz/corpus/{scene,vdb,lights}) through the entry points the
// libFuzzer targets use (tests/fuzz/fuzz_entry.cpp), built with the project's own compiler, so
// an input that once crashed Mirage stays a regression test without clang. Every input must
// either load or be refused with a MirageError; any other exception fails the test, and a crash
// fails the test program.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../fuzz/fuzz_entry.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> corpusFiles(const std::string& kind) {
    const fs::path dir = fs::path(mirage::test::sourceDir()) / "tests" / "fuzz" / "corpus" / kind;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<uint8_t> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// Runs every file of corpus/<kind> and returns how many were accepted (loaded).
template <typename Entry>
int replay(const std::string& kind, Entry entry, int& count) {
    int accepted = 0;
    count = 0;
    for (const fs::path& file : corpusFiles(kind)) {
        SCOPED_TRACE(file.string());
        const std::vector<uint8_t> bytes = readBytes(file);
        bool ok = false;
        EXPECT_NO_THROW(ok = entry(bytes.data(), bytes.size()));
        accepted += ok ? 1 : 0;
        ++count;
    }
    return accepted;
}

TEST(FuzzCorpus, SceneInputsLoadOrFailWithMirageError) {
    int count = 0;
    const int accepted = replay("scene", mirage::fuzz::runSceneInput, count);
    ASSERT_GE(count, 10) << "the scene corpus lost its seeds";
    // The seeds include the shipped scenes, which name the caches the harness provides: if none
    // of them loads any more, the harness (not the input) is broken and the replay tests nothing.
    EXPECT_GE(accepted, 5) << accepted << " of " << count << " scene inputs loaded";
}

TEST(FuzzCorpus, VdbInputsLoadOrFailWithMirageError) {
    int count = 0;
    const int accepted = replay("vdb", mirage::fuzz::runVdbInput, count);
    ASSERT_GE(count, 4) << "the VDB corpus lost its seeds";
    // The generated fog spheres (OpenVDB float and half, NanoVDB raw and zip) must all load.
    EXPECT_GE(accepted, 4) << accepted << " of " << count << " VDB inputs loaded";
}

TEST(FuzzCorpus, LightFileInputsLoadOrFailWithMirageError) {
    int count = 0;
    const int accepted = replay("lights", mirage::fuzz::runLightFileInput, count);
    ASSERT_GE(count, 5) << "the light files' corpus lost its seeds";
    // The seeds: two IES profiles (TILT=NONE and TILT=INCLUDE) and three RGBE pictures (flat,
    // run-length encoded, a header without FORMAT), each read by one of the two parsers.
    EXPECT_GE(accepted, 5) << accepted << " of " << count << " light files read";
}

}  // namespace
