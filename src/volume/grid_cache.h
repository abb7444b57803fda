// Grids kept between loads of scenes in one process: a program that loads a scene again after an
// edit (the Python module's Session.update, a render with other settings) reads a file's grids
// (density and the other scalars, and the velocity) again only when the file changed (its size
// or modification time), or the grids or expressions asked of it did. A FloatGrid shares its
// NanoVDB buffer and dense copy (grid.h), so a grid both cached and in a medium is in memory once;
// dropping the cache returns what no medium holds.
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "volume/grid_precision.h"
#include "volume/vdb_file.h"

namespace mirage {

class GridCache {
public:
    // loadFloatGrids (vdb_file.h) held at `precision` (grid_quantise.h), or the grids of an
    // earlier call with the same file, unchanged on disk, the same names, the same expressions
    // (their code and bindings) and the same precision. Thread-safe.
    std::vector<FloatGrid> loadFloatGrids(const std::string& path,
                                          const std::vector<std::string>& gridNames,
                                          const std::vector<GridExpression>& expressions,
                                          std::vector<double>* expressionSeconds = nullptr,
                                          const PrecisionSpec& precision = {});
    // loadVectorGrid, or loadVectorGridFromScalars when `fromScalars` (vdb_file.h), cached
    // alike: a velocity grid of an unchanged file is read once.
    VectorGrid loadVectorGrid(const std::string& path, const std::string& gridName,
                              bool fromScalars);
    size_t reads() const;  // the calls that read the file
    size_t hits() const;   // the calls served from the cache

private:
    struct Entry {
        std::string key;  // path, size and time, then what was asked of the file
        std::vector<FloatGrid> grids;
        VectorGrid vector;
        std::vector<double> seconds;
    };
    // The entry of `key` (its first line the file), from the cache or from `read`.
    Entry lookup(const std::string& key, const std::function<void(Entry*)>& read);
    mutable std::mutex mMutex;
    std::vector<Entry> mEntries;
    size_t mReads = 0, mHits = 0;
};

}  // namespace mirage
