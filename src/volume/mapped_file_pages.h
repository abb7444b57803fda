// The pages of a file this process has mapped, given back while it reads on. OpenVDB's delayed
// loading maps the whole cache (io::MappedFile) and each leaf read touches its compressed bytes
// there: the pages stay in the process's resident set until the mapping goes, after the last
// leaf — at 10⁹ voxels 1.5 GB of density on top of the NanoVDB grid being filled. Dropping the
// mapping's page-table entries (madvise MADV_DONTNEED) leaves the file's pages in the page cache
// and the mapping valid: a later read of them faults them back in from the cache.
//
// The same holds for the heap: the ~2 million OpenVDB leaf nodes of a 10⁹-voxel cache's
// topology (~0.3 GB, allocated before any leaf is read) are freed one by one as they are
// converted, and the allocator keeps their pages resident until asked to give them back.
//
// And for a big buffer about to be filled: each first write to a 4 KB page is a fault, ~500 000
// of them for the 2 GB NanoVDB grid of a 10⁹-voxel cache, which `perf` put at a fifth of its
// load (the faults, and the stores that take them). Transparent huge pages (2 MB) cut that
// 512-fold where the system grants them on request (/sys/kernel/mm/transparent_hugepage/enabled
// "madvise", Debian's default; "always" needs no advice).
#pragma once

#include <cstddef>
#include <string>

namespace mirage {

// Drops this process's resident pages of every mapping of file `path` (found in
// /proc/self/maps by its canonical path). Does nothing where there is no such file or mapping.
// Safe while other threads read the mapping.
void releaseMappedPages(const std::string& path);

// Gives the heap's wholly free pages back to the system (glibc's malloc_trim; nothing elsewhere).
// Safe while other threads allocate.
void releaseFreedHeapPages();

// Asks for huge pages under the 2 MB-aligned interior of [data, data + bytes), a buffer not yet
// written (madvise MADV_HUGEPAGE). Only an advice: where it is refused, or the buffer spans no
// whole huge page, the buffer is the same and faults its pages in 4 KB at a time.
void adviseHugePages(void* data, size_t bytes);

}  // namespace mirage
