// --threads N: caps TBB's worker threads for as long as the returned object lives.
#pragma once

#include <tbb/global_control.h>

#include <cstddef>
#include <memory>

namespace mirage {

// No cap (nullptr) for threads ≤ 0: TBB then uses every core.
inline std::unique_ptr<tbb::global_control> limitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 size_t(threads));
}

}  // namespace mirage
