#include "volume/vdb_leaf_values.h"

#include <blosc.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace mirage {

namespace {

constexpr uint32_t kLeafValues = 512;
constexpr size_t kMaskBytes = kLeafValues / 8;

// A half float's value as a float: exact, as every half is a float (normal halves rebias the
// exponent by 127 − 15; subnormal ones are their mantissa times 2⁻²⁴; ±∞ and NaN keep their
// bits, as Imath's conversion does).
float halfToFloat(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
    uint32_t bits;
    if (exponent == 0x1fu) {
        bits = sign | 0x7f800000u | (mantissa << 13);
    } else if (exponent != 0) {
        bits = sign | ((exponent + 112u) << 23) | (mantissa << 13);
    } else {
        const float magnitude = float(mantissa) * 5.9604644775390625e-8f;  // 2⁻²⁴
        std::memcpy(&bits, &magnitude, 4);
        bits |= sign;
    }
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

bool bitOn(const uint8_t* mask, uint32_t i) { return (mask[i >> 3] >> (i & 7)) & 1u; }

// One leaf's bytes, read forward; every read is inside the file (the walk checked the sizes).
struct Cursor {
    const uint8_t* p;
    template <typename T>
    T pod() {
        T v;
        std::memcpy(&v, p, sizeof(T));
        p += sizeof(T);
        return v;
    }
};

}  // namespace

LeafValueReader::LeafValueReader(const std::string& path, vdbformat::LeafDataIndex index)
    : mIndex(std::move(index)) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (fd < 0 || ::fstat(fd, &st) != 0) {
        const std::string why = std::strerror(errno);
        if (fd >= 0) ::close(fd);
        throw MirageError(FileLoc{path}, "cannot be opened: " + why);
    }
    mSize = size_t(st.st_size);
    void* map = mSize ? ::mmap(nullptr, mSize, PROT_READ, MAP_PRIVATE, fd, 0) : MAP_FAILED;
    ::close(fd);
    if (map == MAP_FAILED)
        throw MirageError(FileLoc{path}, std::string("cannot be mapped: ") + std::strerror(errno));
    mData = static_cast<const uint8_t*>(map);
}

LeafValueReader::~LeafValueReader() {
    if (mData) ::munmap(const_cast<uint8_t*>(mData), mSize);
}

bool LeafValueReader::read(size_t i, const uint64_t* mask, float* out, std::string* error) const {
    auto fail = [&](const std::string& why) {
        *error = "leaf " + std::to_string(i) + " at byte " + std::to_string(mIndex.offsets[i]) +
                 ": " + why;
        return false;
    };
    if (i >= mIndex.offsets.size() || mIndex.offsets[i] + kMaskBytes + 1 > mSize)
        return fail("outside the file");
    Cursor c{mData + mIndex.offsets[i]};
    if (std::memcmp(c.p, mask, kMaskBytes) != 0) return fail("its mask differs from its topology");
    const uint8_t* valueMask = c.p;
    c.p += kMaskBytes;

    const int8_t flag = c.pod<int8_t>();
    const float bg = mIndex.background;
    float inactive0 = flag == 0 ? bg : -bg, inactive1 = bg;
    if (flag == 2 || flag == 4 || flag == 5) inactive0 = c.pod<float>();
    if (flag == 5) inactive1 = c.pod<float>();
    const uint8_t* selection = nullptr;
    if (flag == 3 || flag == 4 || flag == 5) {
        selection = c.p;
        c.p += kMaskBytes;
    }
    uint32_t active = 0;
    for (size_t w = 0; w < kLeafValues / 64; ++w) active += uint32_t(__builtin_popcountll(mask[w]));
    const bool maskCompressed = (mIndex.compression & vdbformat::kCompressActiveMask) != 0;
    const uint32_t count = maskCompressed && flag != 6 ? active : kLeafValues;
    const size_t elementBytes = mIndex.savedAsHalf ? 2 : 4;
    const size_t bytes = elementBytes * count;

    // The stored values: raw, or a block whose int64 size is ≤ 0 when it is stored raw.
    alignas(16) uint8_t stored[kLeafValues * 4];
    const uint8_t* values = c.p;
    const bool noneStored = mIndex.savedAsHalf && count == 0;  // io::HalfReader reads nothing
    const bool blosc = (mIndex.compression & vdbformat::kCompressBlosc) != 0;
    const bool zip = !blosc && (mIndex.compression & vdbformat::kCompressZip) != 0;
    if (!noneStored && (blosc || zip)) {
        const int64_t size = c.pod<int64_t>();
        values = c.p;
        if (size > 0) {
            if (blosc) {
                if (blosc_decompress_ctx(c.p, stored, bytes, 1) != int(bytes))
                    return fail("its Blosc block does not decompress to " + std::to_string(bytes) +
                                " bytes");
            } else {
                uLongf length = uLongf(bytes);
                if (uncompress(stored, &length, c.p, uLong(size)) != Z_OK || length != bytes)
                    return fail("its zip block does not decompress to " + std::to_string(bytes) +
                                " bytes");
            }
            values = stored;
        }
    }

    float read[kLeafValues];
    float* dest = count == kLeafValues ? out : read;
    if (mIndex.savedAsHalf) {
        for (uint32_t n = 0; n < count; ++n) {
            uint16_t h;
            std::memcpy(&h, values + 2 * n, 2);
            dest[n] = halfToFloat(h);
        }
    } else {
        std::memcpy(dest, values, bytes);
    }
    if (count == kLeafValues) return true;
    // Mask compression: the active values in order, the others as the flag and selection say.
    for (uint32_t n = 0, next = 0; n < kLeafValues; ++n)
        out[n] = bitOn(valueMask, n) ? read[next++]
                                     : (selection && bitOn(selection, n) ? inactive1 : inactive0);
    return true;
}

}  // namespace mirage
