#include "scene/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "core/error.h"
#include "core/progress.h"
#include "film/aov.h"
#include "photon/photon_pass.h"
#include "scene/scene.h"
#include "volume/vdb_file.h"

namespace mirage {

uint64_t parseMemorySize(const std::string& text, const std::string& what) {
    const std::string expected =
        what + " '" + text + "': expected a size such as 4G, 512M, 1.5G or a number of bytes";
    if (text.empty()) throw MirageError(expected);
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    std::string unit(end);
    if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
    if (unit.size() == 2 && (unit[1] == 'i' || unit[1] == 'I')) unit.pop_back();  // GiB, MiB
    double scale = 1;
    if (unit.empty())
        scale = 1;
    else if (unit == "k" || unit == "K")
        scale = 1024.0;
    else if (unit == "m" || unit == "M")
        scale = 1024.0 * 1024;
    else if (unit == "g" || unit == "G")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "t" || unit == "T")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else
        throw MirageError(expected);
    if (end == text.c_str() || !std::isfinite(v) || v <= 0 || v * scale > 1.8e19 || v * scale < 1)
        throw MirageError(expected);
    return uint64_t(v * scale);
}

uint64_t MemoryEstimate::total() const {
    uint64_t t = 0;
    for (const auto& i : items) t += i.bytes;
    return t;
}

std::string MemoryEstimate::describe() const {
    std::vector<MemoryItem> sorted(items);
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const MemoryItem& a, const MemoryItem& b) { return a.bytes > b.bytes; });
    std::string s = formatBytes(total()) + " =";
    for (size_t i = 0; i < sorted.size(); ++i)
        s += (i ? " +" : "") + std::string(" ") + sorted[i].what + " " +
             formatBytes(sorted[i].bytes);
    return s;
}

uint64_t currentMemoryBytes() {
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long long size = 0, resident = 0;
    int n = std::fscanf(f, "%llu %llu", &size, &resident);
    std::fclose(f);
    return n == 2 ? resident * uint64_t(::sysconf(_SC_PAGESIZE)) : 0;
}

uint64_t availableMemoryBytes() {
    FILE* f = std::fopen("/proc/meminfo", "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kib = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f))
        found = std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1;
    std::fclose(f);
    return found ? uint64_t(kib) * 1024 : 0;
}

namespace {

// The float channels a pass develops into (film/film.cpp): alpha and depth one, a Cryptomatte
// three RGBA layers of rank pairs, the others three.
uint64_t developedChannels(const AovPass& pass) {
    switch (pass.kind) {
        case AovKind::Alpha:
        case AovKind::Depth:
            return 1;
        case AovKind::Cryptomatte:
            return 12;
        default:
            return 3;
    }
}

}  // namespace

uint64_t passBytesPerPixel(const AovLayout& layout) {
    uint64_t channels = 0;
    for (const AovPass& pass : layout.passes()) channels += developedChannels(pass);
    return uint64_t(layout.stride()) * kBytesPerPassSum + channels * kBytesPerPassChannel;
}

LoadedGrids loadedGrids(const Scene& scene) {
    LoadedGrids out;
    std::set<const void*> seen;
    for (const auto& m : scene.render.media)
        for (const FloatGrid& g : m->binding().grids())
            if (g.valid() && seen.insert(g.treeId()).second) out.bytes += g.memoryBytes();
    out.count = seen.size();
    return out;
}

MemoryEstimate estimateFrameMemory(const Scene& scene, const std::string& integrator) {
    MemoryEstimate e;
    const LoadedGrids loaded = loadedGrids(scene);
    const uint64_t grids = loaded.bytes;
    uint64_t resident = currentMemoryBytes();
    e.items.push_back({"grids (" + std::to_string(loaded.count) + ", as loaded)", grids});
    e.items.push_back({"program, libraries, surfaces and majorants (resident now)",
                       resident > grids ? resident - grids : 0});

    const RenderSettings& s = scene.settings;
    uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    e.items.push_back({"film (" + std::to_string(s.width) + "x" + std::to_string(s.height) + ")",
                       pixels * kBytesPerPixel});
    const AovLayout layout(s.aovs, scene.render.lightGroupNames(), scene.render.cryptoObjects);
    if (!layout.empty())
        e.items.push_back({"passes (" + std::to_string(layout.passes().size()) + ", " +
                               std::to_string(layout.stride()) + " sums per pixel)",
                           pixels * passBytesPerPixel(layout)});
    if (!s.deep.path.empty())
        e.items.push_back(
            {"deep samples (" + std::to_string(kDeepSamplesPlanned) + " per pixel planned)",
             pixels * kDeepBytesPerPixel});

    if (integratorInfo(integrator).photonPass && scene.photon.photons > 0) {
        // Pilot: how many photons a photon emitted leaves stored in this scene (absorbed or
        // escaped photons store none; a photon in a thick, bright medium stores many).
        std::vector<const Light*> lights;
        for (const auto& l : scene.render.lights) lights.push_back(l.get());
        PhotonPassSettings pilot;
        pilot.photons = std::min<uint64_t>(scene.photon.photons, 4096);
        pilot.seed = 0x70696c6f74ull;  // "pilot": any seed will do for a count
        pilot.maxBounces = scene.photon.maxBounces;
        pilot.storeFirstInteraction = false;
        pilot.progress = Progress::Mode::Quiet;
        // The caustic stream of projection maps in the same proportion to the main one.
        pilot.projection = scene.photon.projection;
        pilot.causticPhotons = std::max<uint64_t>(
            1, uint64_t(double(pilot.photons) * double(scene.photon.causticPhotonsOrDefault()) /
                        double(scene.photon.photons)));
        PhotonPassStats stats;
        PhotonMapLists lists = tracePhotonMaps(
            lights, scene.render.mediaPointers(),
            scene.render.hasSurfaces() ? scene.render.geometry.get() : nullptr, pilot, &stats);
        double stored =
            double(lists.volume.size() + lists.surfaceGlobal.size() + lists.surfaceCaustic.size());
        double perEmitted = stats.emitted > 0 ? stored / double(stats.emitted) : 0;
        // Emitted per map: the main stream, and the caustic one where the pilot traced it.
        const double emitted =
            double(scene.photon.photons) * double(stats.emitted) / double(pilot.photons);
        double photons = emitted * perEmitted;
        char what[160];
        std::snprintf(what, sizeof what, "photon maps (%.3g emitted x %.2f stored each x %llu B)",
                      emitted, perEmitted, (unsigned long long)kBytesPerStoredPhoton);
        e.items.push_back({what, uint64_t(photons * double(kBytesPerStoredPhoton))});
    }
    return e;
}

uint64_t gridBytesBeforeLoad(const GridInfo& grid, GridPrecision precision) {
    const uint64_t asFloat = std::max(grid.memoryBytes, grid.activeVoxels * 4);
    const uint64_t leaves = (grid.activeVoxels + 511) / 512;
    const uint64_t saved =
        leaves * (leafNodeBytes(GridPrecision::Float) - leafNodeBytes(precision));
    return std::max(asFloat > saved ? asFloat - saved : 0, leaves * leafNodeBytes(precision));
}

MemoryEstimate estimateBeforeGrid(const std::string& file, const std::string& grid,
                                  GridPrecision precision, uint64_t gridBytes, int width,
                                  int height) {
    MemoryEstimate e;
    e.items.push_back({"grid '" + grid + "' of " + file + " at precision " +
                           precisionName(precision) + " (file metadata)",
                       gridBytes});
    e.items.push_back({"resident now (program, grids so far)", currentMemoryBytes()});
    e.items.push_back(
        {"film (" + std::to_string(width) + "x" + std::to_string(height) + ")",
         uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)) * kBytesPerPixel});
    return e;
}

void checkMemoryBudget(const MemoryEstimate& estimate, uint64_t budget, const std::string& where,
                       const std::string& what) {
    if (estimate.total() <= budget) return;
    throw MirageError(where + ": " + what + " an estimated " + estimate.describe() +
                      ", more than --max-memory " + formatBytes(budget) +
                      "; reduce the largest item (or raise --max-memory)");
}

}  // namespace mirage
