// FNV-1a, 64-bit (Fowler, Noll, Vo): a fast hash to tell scenes, settings and files apart (the
// fingerprints of partial files and photon files, the checksum of a photon file). Not a
// security hash: it detects accidents (a truncated copy, a flipped bit, another scene), not
// tampering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace mirage {

struct Fnv1a {
    uint64_t h = 0xcbf29ce484222325ull;

    void bytes(const void* data, size_t n) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    }
    // A string and a separator after it, so that "ab" + "c" differs from "a" + "bc".
    void add(const std::string& s) {
        bytes(s.data(), s.size());
        h = (h ^ 0xff) * 0x100000001b3ull;
    }
    // The hash as 16 lowercase hex digits.
    std::string hex() const {
        static const char* digits = "0123456789abcdef";
        std::string out(16, '0');
        for (int i = 0; i < 16; ++i) out[15 - i] = digits[(h >> (4 * i)) & 0xf];
        return out;
    }
};

}  // namespace mirage
