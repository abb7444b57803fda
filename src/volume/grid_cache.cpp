// Grids kept between loads (grid_cache.h).
#include "volume/grid_cache.h"

#include <filesystem>

namespace mirage {

namespace {

// What decides the grids a call returns: the file as it is on disk, then what is asked of it.
std::string cacheKey(const std::string& path, const std::vector<std::string>& gridNames,
                     const std::vector<GridExpression>& expressions) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    const auto time = fs::last_write_time(path, ec).time_since_epoch().count();
    std::string key = fs::absolute(path, ec).lexically_normal().string() + '\n' +
                      std::to_string(size) + ' ' + std::to_string(time) + '\n';
    for (const std::string& g : gridNames) key += "grid " + g + '\n';
    for (const GridExpression& e : expressions) {
        key += "expression " + e.code + '\n';
        for (const auto& [name, grid] : e.bindings) key += "  " + name + "=" + grid + '\n';
    }
    return key;
}

}  // namespace

std::vector<FloatGrid> GridCache::loadFloatGrids(const std::string& path,
                                                 const std::vector<std::string>& gridNames,
                                                 const std::vector<GridExpression>& expressions,
                                                 std::vector<double>* expressionSeconds) {
    const std::string key = cacheKey(path, gridNames, expressions);
    {
        std::lock_guard<std::mutex> lock(mMutex);
        for (const Entry& e : mEntries)
            if (e.key == key) {
                ++mHits;
                if (expressionSeconds) *expressionSeconds = e.seconds;
                return e.grids;
            }
    }
    // Read outside the lock: another scene's grids may load meanwhile.
    Entry entry{key, {}, {}};
    entry.grids = mirage::loadFloatGrids(path, gridNames, expressions, &entry.seconds);
    if (expressionSeconds) *expressionSeconds = entry.seconds;
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
    return entry.grids;
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
