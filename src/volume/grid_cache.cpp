// Grids kept between loads (grid_cache.h).
#include "volume/grid_cache.h"

#include <filesystem>

#include "volume/grid_quantise.h"

namespace mirage {

namespace {

// The file as it is on disk: its path, size and modification time, one line each of the two.
std::string fileStamp(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    const auto time = fs::last_write_time(path, ec).time_since_epoch().count();
    return fs::absolute(path, ec).lexically_normal().string() + '\n' + std::to_string(size) + ' ' +
           std::to_string(time) + '\n';
}

}  // namespace

GridCache::Entry GridCache::lookup(const std::string& key,
                                   const std::function<void(Entry*)>& read) {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        for (const Entry& e : mEntries)
            if (e.key == key) {
                ++mHits;
                return e;
            }
    }
    // Read outside the lock: another scene's grids may load meanwhile.
    Entry entry{key, {}, {}, {}};
    read(&entry);
    std::lock_guard<std::mutex> lock(mMutex);
    ++mReads;
    // Entries of an older version of the file are dropped: its grids are gone from the disk.
    const size_t pathEnd = key.find('\n') + 1, stampEnd = key.find('\n', pathEnd) + 1;
    std::vector<Entry> kept;
    for (Entry& e : mEntries) {
        const bool sameFile = e.key.compare(0, pathEnd, key, 0, pathEnd) == 0;
        if (!sameFile || e.key.compare(0, stampEnd, key, 0, stampEnd) == 0)
            kept.push_back(std::move(e));
    }
    kept.push_back(entry);
    mEntries = std::move(kept);
    return entry;
}

std::vector<FloatGrid> GridCache::loadFloatGrids(const std::string& path,
                                                 const std::vector<std::string>& gridNames,
                                                 const std::vector<GridExpression>& expressions,
                                                 std::vector<double>* expressionSeconds,
                                                 const PrecisionSpec& precision) {
    std::string key = fileStamp(path);
    key += std::string("precision ") + precisionName(precision.precision) + ' ' +
           std::to_string(precision.relativeTolerance) + '\n';
    for (const std::string& g : gridNames) key += "grid " + g + '\n';
    for (const GridExpression& e : expressions) {
        key += "expression " + e.code + '\n';
        for (const auto& [name, grid] : e.bindings) key += "  " + name + "=" + grid + '\n';
    }
    Entry entry = lookup(key, [&](Entry* e) {
        e->grids = loadGridsAt(path, gridNames, expressions, &e->seconds, precision);
    });
    if (expressionSeconds) *expressionSeconds = entry.seconds;
    return entry.grids;
}

VectorGrid GridCache::loadVectorGrid(const std::string& path, const std::string& gridName,
                                     bool fromScalars) {
    const std::string key =
        fileStamp(path) + (fromScalars ? "vector from scalars " : "vector ") + gridName + '\n';
    return lookup(key,
                  [&](Entry* e) {
                      e->vector = fromScalars ? loadVectorGridFromScalars(path, gridName)
                                              : mirage::loadVectorGrid(path, gridName);
                  })
        .vector;
}

size_t GridCache::reads() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mReads;
}

size_t GridCache::hits() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mHits;
}

}  // namespace mirage
