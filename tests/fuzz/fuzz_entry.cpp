// Shared by the libFuzzer targets and the corpus replay test; see fuzz_entry.h.
#include "fuzz_entry.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <system_error>

#include "core/error.h"
#include "film/color.h"
#include "scene/scene.h"
#include "volume/asset_writer.h"
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
// A corrupt index could list thousands of grids; a few cover every code path.
constexpr size_t kMaxGridsLoaded = 4;

void removeScratch();

std::string makeScratch() {
    std::string pattern = (fs::temp_directory_path() / "mirage-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw MirageError("cannot create a folder under /tmp");
    std::atexit(removeScratch);
    const fs::path dir(pattern);
    // The caches the shipped scenes (assets/scenes, tests/bench) name, as tiny procedural grids.
    writeProceduralAsset("fog-sphere", (dir / "fog_sphere.vdb").string(), kAssetResolution);
    writeProceduralAsset("smoke", (dir / "demo_smoke.vdb").string(), kAssetResolution);
    writeProceduralAsset("smoke", (dir / "smoke1.vdb").string(), kAssetResolution);
    writeProceduralAsset("fire", (dir / "fire_smoke.vdb").string(), kAssetResolution);
    return pattern;
}

void removeScratch() {
    std::error_code ec;
    fs::remove_all(scratchFolder(), ec);
}

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
    static const std::string dir = makeScratch();
    return dir;
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

}  // namespace mirage::fuzz
