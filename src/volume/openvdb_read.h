// The values of an OpenVDB grid read with delayed loading (vdb_file.cpp, ReadMode::Lazy), leaf
// by leaf in parallel: OpenVDB's own reader decompresses the leaves (Blosc or zip) and widens
// half floats one after the other, which dominates the load of a big cache; touching each
// leaf's buffer from TBB's threads does the same work on every core. A progress bar reports the
// grid's bytes in the file read so far (core/progress.h). A float grid's leaves are decoded
// from the file by Mirage itself where the tree walk indexed them (vdb_leaf_values.h), faster
// than OpenVDB's per-leaf streams.
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
#include "volume/mapped_file_pages.h"
#include "volume/vdb_leaf_values.h"

namespace mirage {

// Where broken leaf buffers are kept, never freed (LeafReads::load).
inline std::vector<std::shared_ptr<void>>& brokenLeafBuffers() {
    static auto* parked = new std::vector<std::shared_ptr<void>>();
    return *parked;
}

// The reads of one grid's leaves, from any thread: each leaf's values loaded, the bar advanced
// as leaves are done, and the first failure kept for finish() to report. `fileBytes` is the
// grid's extent in file `path`; `gridLabel` names it on the bar and in the error.
template <typename LeafT>
class LeafReads {
public:
    // With `decoder`, values() decodes the leaves from the file itself (vdb_leaf_values.h).
    LeafReads(uint64_t fileBytes, size_t leafCount, const std::string& path,
              const std::string& gridLabel, const LeafValueReader* decoder = nullptr)
        : mDecoder(decoder),
          mPath(path),
          mLabel(gridLabel),
          mLeaves(leafCount),
          mMegabytes(fileBytes / 1000000 + 1),
          mProgress("reading", path, gridLabel, fileBytes, mMegabytes, "MB") {}

    // Loads the leaf's values; false when OpenVDB could not (corrupt compressed data). Such a
    // leaf's buffer is left by OpenVDB half loaded (allocated, yet marked as still in the file)
    // and would crash when freed: it is swapped for an empty buffer and the broken one is
    // parked for the process's life (brokenLeafBuffers: one leaf per failure, on a corrupt file
    // only; reachable, so not a leak to LeakSanitizer).
    bool load(LeafT& leaf) {
        if (mFailed) return false;
        try {
            leaf.buffer().data();
            return true;
        } catch (const std::exception& e) {
            using Buffer = typename LeafT::Buffer;
            auto* broken = new Buffer();
            broken->swap(leaf.buffer());
            fail(e.what(), broken);
            return false;
        }
    }
    bool failed() const { return mFailed; }

    // The values of `leaf`, the i-th in depth-first order: decoded into `scratch` (512 floats)
    // by the decoder where there is one, else loaded by OpenVDB into the leaf's own buffer.
    // Null when they could not be read.
    const float* values(size_t i, LeafT& leaf, float* scratch) {
        if (!mDecoder) return load(leaf) ? leaf.buffer().data() : nullptr;
        if (mFailed) return nullptr;
        uint64_t mask[LeafT::SIZE / 64];
        for (uint32_t w = 0; w < LeafT::SIZE / 64; ++w)
            mask[w] = leaf.valueMask().template getWord<uint64_t>(w);
        std::string error;
        if (mDecoder->read(i, mask, scratch, &error)) return scratch;
        fail(error);
        return nullptr;
    }

    // `leaves` more leaves are done: the bar's steps add up to the grid's size. Every
    // kReleaseMegabytes read, the file's mapped pages and the freed leaves' heap pages are given
    // back (mapped_file_pages.h), by one thread at a time.
    void advance(size_t leaves) {
        const size_t before = mDone.fetch_add(leaves);
        const uint64_t from = megabytesBefore(before), to = megabytesBefore(before + leaves);
        mProgress.advance(to - from);
        if (from / kReleaseMegabytes != to / kReleaseMegabytes) {
            std::unique_lock<std::mutex> lock(mReleaseMutex, std::try_to_lock);
            if (lock) {
                releaseMappedPages(mPath);
                releaseFreedHeapPages();
            }
        }
    }

    // Ends the bar; throws MirageError naming the file and grid, with what OpenVDB said, when a
    // leaf could not be read.
    void finish() {
        mProgress.finish();
        if (mFailed)
            throw MirageError(FileLoc{mPath},
                              std::string(mDecoder ? "cannot" : "OpenVDB could not") +
                                  " read grid " + mLabel + ": " + boundedMessage(mError));
    }

private:
    // Keeps the first failure's message, and parks a broken leaf buffer where there is one.
    void fail(const std::string& why, void* brokenBuffer = nullptr) {
        std::lock_guard<std::mutex> lock(mErrorMutex);
        if (brokenBuffer) brokenLeafBuffers().emplace_back(brokenBuffer, [](void*) {});
        if (!mFailed.exchange(true)) mError = why;
    }

    static constexpr uint64_t kReleaseMegabytes = 128;
    uint64_t megabytesBefore(size_t i) const {
        return mLeaves == 0 ? 0 : uint64_t(double(mMegabytes) * double(i) / double(mLeaves));
    }

    const LeafValueReader* mDecoder;
    std::string mPath, mLabel;
    size_t mLeaves;
    uint64_t mMegabytes;
    LoadStage mProgress;
    std::atomic<size_t> mDone{0};
    std::atomic<bool> mFailed{false};
    std::string mError;
    std::mutex mErrorMutex, mReleaseMutex;
};

// Reads every leaf's values of `grid` (lazily read: its leaves still in the file), in parallel.
// Throws MirageError naming the file and grid when OpenVDB cannot read a leaf.
template <typename GridT>
void readLeavesInParallel(GridT& grid, uint64_t fileBytes, const std::string& path,
                          const std::string& gridLabel) {
    using LeafT = typename GridT::TreeType::LeafNodeType;
    openvdb::tree::LeafManager<typename GridT::TreeType> leaves(grid.tree());
    LeafReads<LeafT> reads(fileBytes, leaves.leafCount(), path, gridLabel);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.leafCount(), 64), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end() && reads.load(leaves.leaf(i)); ++i) {
        }
        reads.advance(r.size());
    });
    reads.finish();
}

}  // namespace mirage
