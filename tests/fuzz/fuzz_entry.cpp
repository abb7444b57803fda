// Shared by the libFuzzer targets and the corpus replay test; see fuzz_entry.h.
#include "fuzz_entry.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "core/error.h"
#include "film/color.h"
#include "light/ies_file.h"
#include "light/radiance_hdr.h"
#include "scene/scene.h"
#include "tools/asset_writer.h"
#include "volume/vdb_file.h"

namespace mirage::fuzz {
namespace {

namespace fs = std::filesystem;

// Resolution 8 (the smallest make-asset allows) keeps a grid load well under a millisecond, so
// a fuzzer spends its time on parsing rather than on voxels.
constexpr int kAssetResolution = 8;
// Files the inputs write; the grids of a scene may name any of the caches below.
constexpr const char* kSceneName = "scene.toml";
constexpr const char* kVdbName = "input.vdb";
constexpr const char* kHdrName = "input.hdr";
// A corrupt index could list thousands of grids; a few cover every code path.
constexpr size_t kMaxGridsLoaded = 4;

// The private folder: made on first use with tiny caches under the names the shipped scenes
// (assets/scenes, tests/bench) give their grids, removed when the program exits.
struct Scratch {
    Scratch() {
        std::string pattern = (fs::temp_directory_path() / "mirage-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz harness: cannot mkdtemp");
        dir = pattern;
        const fs::path d(dir);
        writeProceduralAsset("fog-sphere", (d / "fog_sphere.vdb").string(), kAssetResolution);
        writeProceduralAsset("smoke", (d / "demo_smoke.vdb").string(), kAssetResolution);
        writeProceduralAsset("plume", (d / "demo_plume.vdb").string(), kAssetResolution);
        writeProceduralAsset("smoke", (d / "smoke1.vdb").string(), kAssetResolution);
        writeProceduralAsset("fire", (d / "fire_smoke.vdb").string(), kAssetResolution);
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::string dir;
};

std::string writeInput(const char* name, const uint8_t* data, size_t size) {
    const std::string path = (fs::path(scratchFolder()) / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) throw std::runtime_error("fuzz harness: cannot write " + path);
    return path;
}

const ColorPipeline& colorPipeline() {
    static const ColorPipeline color;
    return color;
}

}  // namespace

const std::string& scratchFolder() {
    static const Scratch scratch;
    return scratch.dir;
}

bool runSceneInput(const uint8_t* data, size_t size) {
    const ColorPipeline& color = colorPipeline();
    const std::string path = writeInput(kSceneName, data, size);
    try {
        loadScene(path, LoadOptions{}, color);
        return true;
    } catch (const MirageError&) {
        return false;
    }
}

bool runVdbInput(const uint8_t* data, size_t size) {
    const std::string path = writeInput(kVdbName, data, size);
    try {
        validateVdbFile(path);
        const VdbFileInfo info = inspectVdbFile(path);
        bool loaded = false;
        for (size_t i = 0; i < info.grids.size() && i < kMaxGridsLoaded; ++i) {
            try {
                loadFloatGrid(path, "#" + std::to_string(i));
                loaded = true;
            } catch (const MirageError&) {
                // A grid of the wrong type or class is rejected; the others may still load.
            }
        }
        return loaded;
    } catch (const MirageError&) {
        return false;
    }
}

bool runLightFileInput(const uint8_t* data, size_t size) {
    bool read = false;
    try {
        IesProfile::parse(std::string(reinterpret_cast<const char*>(data), size), "input.ies");
        read = true;
    } catch (const MirageError&) {
    }
    const std::string path = writeInput(kHdrName, data, size);
    try {
        RadianceHdr sky;
        read = readRadianceHdr(path, &sky) || read;
    } catch (const MirageError&) {
    }
    return read;
}

}  // namespace mirage::fuzz
