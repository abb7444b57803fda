#include "volume/voxel_rule.h"

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridStats.h>

#include <cstdio>
#include <mutex>
#include <set>

#include "volume/stored_values.h"

namespace mirage {

// The voxel rule (docs/hostile-input.md, "Input rules"), in leaves (active and inactive values: the
// sampler reads both) and tiles: NaN and negative values (−∞ included) become 0, +∞ and values
// above kMaxVoxelValue become kMaxVoxelValue. Fog volumes are densities: a negative σ would make
// free-flight sampling meaningless, a NaN poisons every pixel it reaches, and an unbounded value
// overflows σ = scale × value × cross-section. Counts are of voxels (a tile counts all of its
// voxels).
SanitizeCounts sanitizeScalarVoxels(nanovdb::GridHandle<nanovdb::HostBuffer>& handle) {
    nanovdb::FloatGrid& grid = *handle.grid<float>();
    SanitizeCounts count;
    forEachStoredValue(grid.tree(), [&count](float& v, uint64_t voxels) {
        applyScalarVoxelRule(v, voxels, count);
    });
    if (count.total() > 0) {
        // The node statistics (min/max) and the checksum describe the old values.
        nanovdb::gridStats(grid, nanovdb::StatsMode::All);
        nanovdb::updateChecksum(grid, nanovdb::ChecksumMode::Partial);
    }
    return count;
}

void warnSanitizedOnce(const std::string& path, const std::string& label,
                       const SanitizeCounts& count, bool vectors) {
    static std::mutex mutex;
    static std::set<std::string> warned;
    std::lock_guard<std::mutex> lock(mutex);
    if (!warned.insert(path + '\n' + label).second) return;
    char max[32];
    std::snprintf(max, sizeof max, "%g", double(kMaxVoxelValue));
    const std::string maxText = max;
    std::string what;
    if (count.zeroed > 0)
        what = std::to_string(count.zeroed) +
               (vectors ? " vectors had a NaN or infinite component and were set to 0"
                        : " voxels were negative or NaN and were set to 0");
    if (count.clamped > 0)
        what += (what.empty() ? "" : "; ") + std::to_string(count.clamped) +
                (vectors ? " vectors were longer than " + maxText + " and were shortened to it"
                         : " voxels were +inf or above " + maxText + " and were clamped to it");
    std::fprintf(stderr, "warning: %s: grid %s: %s\n", path.c_str(), label.c_str(), what.c_str());
}

}  // namespace mirage
