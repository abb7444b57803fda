#include "volume/mapped_file_pages.h"

#include <sys/mman.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace mirage {

void releaseMappedPages(const std::string& path) {
    std::error_code error;
    const std::string canonical = std::filesystem::canonical(path, error).string();
    if (error) return;
    std::ifstream maps("/proc/self/maps");
    std::string line;
    // "start-end perms offset dev inode   pathname", addresses in hexadecimal.
    while (std::getline(maps, line)) {
        unsigned long long start = 0, end = 0;
        int name = 0;
        if (std::sscanf(line.c_str(), "%llx-%llx %*s %*s %*s %*s %n", &start, &end, &name) < 2 ||
            name <= 0 || line.compare(size_t(name), std::string::npos, canonical) != 0)
            continue;
        madvise(reinterpret_cast<void*>(uintptr_t(start)), size_t(end - start), MADV_DONTNEED);
    }
}

void releaseFreedHeapPages() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

void adviseHugePages(void* data, size_t bytes) {
#if defined(MADV_HUGEPAGE)
    constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
    const uintptr_t begin = (uintptr_t(data) + kHugePage - 1) & ~(kHugePage - 1);
    const uintptr_t end = (uintptr_t(data) + bytes) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), size_t(end - begin), MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace mirage
