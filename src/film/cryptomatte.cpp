#include "film/cryptomatte.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>

namespace mirage {

namespace {

uint32_t rotl32(uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }

// MurmurHash3's finalisation: every input bit avalanches into every output bit.
uint32_t finalMix(uint32_t h) {
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

std::string hex8(uint32_t v) {
    char buf[9];
    std::snprintf(buf, sizeof buf, "%08x", v);
    return buf;
}

}  // namespace

// The algorithm as Appleby published it: the key in little-endian 4-byte blocks, each mixed
// (× c1, rotate 15, × c2) into the state (rotate 13, × 5 + 0xe6546b64); the 1–3 bytes left
// mixed the same way without the state's step; the length xored in, then the finalisation.
uint32_t murmurHash3_32(const std::string& key, uint32_t seed) {
    constexpr uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
    const auto* bytes = reinterpret_cast<const unsigned char*>(key.data());
    const size_t n = key.size();
    uint32_t h = seed;
    auto scramble = [&](uint32_t k) { return rotl32(k * c1, 15) * c2; };
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        const uint32_t k = uint32_t(bytes[i]) | uint32_t(bytes[i + 1]) << 8 |
                           uint32_t(bytes[i + 2]) << 16 | uint32_t(bytes[i + 3]) << 24;
        h = rotl32(h ^ scramble(k), 13) * 5u + 0xe6546b64u;
    }
    uint32_t tail = 0;
    for (size_t j = n - i; j > 0; --j) tail = tail << 8 | bytes[i + j - 1];
    if (n > i) h ^= scramble(tail);
    return finalMix(h ^ uint32_t(n));
}

float cryptomatteId(uint32_t hash) {
    const uint32_t exponent = (hash >> 23) & 0xffu;
    if (exponent == 0 || exponent == 0xffu) hash ^= 1u << 23;
    float id;
    std::memcpy(&id, &hash, sizeof id);
    return id;
}

std::vector<ImageLayer> cryptomatteLayers(const std::string& type,
                                          const std::vector<std::string>& objects,
                                          const std::vector<float>& coverage, size_t pixels) {
    // Objects of one name are one ID: their coverages add.
    std::vector<std::string> names = objects;
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    std::vector<size_t> slotOf(objects.size());
    std::vector<float> ids(names.size());
    for (size_t i = 0; i < objects.size(); ++i)
        slotOf[i] =
            size_t(std::lower_bound(names.begin(), names.end(), objects[i]) - names.begin());
    for (size_t s = 0; s < names.size(); ++s) ids[s] = cryptomatteId(murmurHash3_32(names[s]));

    std::vector<ImageLayer> layers(kCryptomatteRanks / 2);
    for (size_t l = 0; l < layers.size(); ++l) {
        char suffix[24];  // room for any size_t: no truncation for the compiler to warn of
        std::snprintf(suffix, sizeof suffix, "%02zu", l);
        layers[l].name = type + suffix;
        layers[l].channels = {"R", "G", "B", "A"};
        layers[l].pixels.assign(pixels * 4, 0.f);
        layers[l].convertColor = false;
        layers[l].fullFloat = true;
    }
    std::vector<std::pair<float, size_t>> ranked(names.size());  // (coverage, slot)
    for (size_t p = 0; p < pixels; ++p) {
        for (size_t s = 0; s < names.size(); ++s) ranked[s] = {0.f, s};
        for (size_t i = 0; i < objects.size(); ++i)
            ranked[slotOf[i]].first += coverage[p * objects.size() + i];
        // Decreasing coverage; ties in name order, so the ranks are deterministic.
        std::stable_sort(ranked.begin(), ranked.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        for (int r = 0; r < kCryptomatteRanks && size_t(r) < ranked.size(); ++r) {
            if (!(ranked[size_t(r)].first > 0.f)) break;
            float* out = &layers[size_t(r / 2)].pixels[p * 4 + size_t(r % 2) * 2];
            out[0] = ids[ranked[size_t(r)].second];
            out[1] = ranked[size_t(r)].first;
        }
    }
    return layers;
}

std::vector<std::pair<std::string, std::string>> cryptomatteAttributes(
    const std::string& type, const std::vector<std::string>& objects) {
    const std::string prefix = "cryptomatte/" + hex8(murmurHash3_32(type)).substr(0, 7) + "/";
    std::map<std::string, std::string> manifest;
    for (const std::string& o : objects) manifest[o] = hex8(murmurHash3_32(o));
    std::string json = "{";
    for (const auto& [name, hash] : manifest)
        json += (json.size() > 1 ? "," : "") + ("\"" + name + "\":\"" + hash + "\"");
    json += "}";
    return {{prefix + "name", type},
            {prefix + "hash", "MurmurHash3_32"},
            {prefix + "conversion", "uint32_to_float32"},
            {prefix + "manifest", json}};
}

bool validCryptomatteName(const std::string& name) {
    if (name.empty()) return false;
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || (c && std::strchr("_-./:", c))))
            return false;
    return true;
}

}  // namespace mirage
