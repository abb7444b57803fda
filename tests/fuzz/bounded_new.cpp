// Global operator new for the fuzz targets: a request above kLimit throws std::bad_alloc, as
// the C++ runtime of a normal build does for an impossible size, instead of reaching
// AddressSanitizer's allocator, which aborts on it. OpenVDB's Blosc reader allocates whatever
// compressed size a corrupt file claims (terabytes); Mirage turns the bad_alloc into one clear
// message, and that path is what the VDB target must exercise. Smaller requests go to malloc,
// which ASan still instruments (overflows, use after free, leaks).
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kLimit = std::size_t(1) << 36;  // 64 GiB: above any grid Mirage can load

void* allocate(std::size_t size) {
    if (size > kLimit) throw std::bad_alloc();
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    return size > kLimit ? nullptr : std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    return size > kLimit ? nullptr : std::malloc(size ? size : 1);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
