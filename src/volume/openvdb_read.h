// The values of an OpenVDB grid read with delayed loading (vdb_file.cpp, ReadMode::Lazy), leaf
// by leaf in parallel: OpenVDB's own reader decompresses the leaves (Blosc or zip) and widens
// half floats one after the other, which dominates the load of a big cache; touching each
// leaf's buffer from TBB's threads does the same work on every core. A progress bar reports the
// grid's bytes in the file read so far (core/progress.h).
// Includes OpenVDB: only vdb_file.cpp includes it.
#pragma once

#include <openvdb/openvdb.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/progress.h"
#include "volume/load_progress.h"

namespace mirage {

// Reads every leaf's values of `grid` (lazily read: its leaves still in the file), in parallel.
// `fileBytes` is the grid's extent in file `path`; `gridLabel` names it on the bar. Throws
// MirageError naming the file and grid when OpenVDB cannot read a leaf (corrupt compressed
// data), with what it said. Such a leaf's
// buffer is left by OpenVDB half loaded (allocated, yet marked as still in the file) and would
// crash when freed: it is swapped for an empty buffer and the broken one is parked for the
// process's life (brokenLeafBuffers: one leaf per failure, on a corrupt file only; reachable,
// so not a leak to LeakSanitizer).
// Where broken leaf buffers are kept, never freed (readLeavesInParallel).
inline std::vector<std::shared_ptr<void>>& brokenLeafBuffers() {
    static auto* parked = new std::vector<std::shared_ptr<void>>();
    return *parked;
}

template <typename GridT>
void readLeavesInParallel(GridT& grid, uint64_t fileBytes, const std::string& path,
                          const std::string& gridLabel) {
    using Buffer = typename GridT::TreeType::LeafNodeType::Buffer;
    const std::string label = path.substr(path.find_last_of('/') + 1) + " " + gridLabel;
    openvdb::tree::LeafManager<typename GridT::TreeType> leaves(grid.tree());
    const size_t count = leaves.leafCount();
    const uint64_t megabytes = fileBytes / 1000000 + 1;
    const Progress::Mode mode =
        fileBytes >= kLoadProgressBytes ? gridLoadProgress() : Progress::Mode::Quiet;
    Progress progress("reading " + label, megabytes, "MB", mode);
    // The bytes of leaves [0, i): the bar's steps add up to the grid's size.
    auto megabytesBefore = [&](size_t i) { return uint64_t(double(megabytes) * i / count); };
    std::atomic<bool> failed{false};
    std::string error;
    std::mutex errorMutex;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end() && !failed; ++i) {
            try {
                leaves.leaf(i).buffer().data();
            } catch (const std::exception& e) {
                auto* broken = new Buffer();
                broken->swap(leaves.leaf(i).buffer());
                std::lock_guard<std::mutex> lock(errorMutex);
                brokenLeafBuffers().emplace_back(broken, [](void*) {});
                if (!failed.exchange(true)) error = e.what();
            }
        }
        progress.advance(megabytesBefore(r.end()) - megabytesBefore(r.begin()));
    });
    progress.finish();
    if (failed)
        throw MirageError(FileLoc{path}, "OpenVDB could not read grid " + gridLabel + ": " +
                                             boundedMessage(error));
}

}  // namespace mirage
