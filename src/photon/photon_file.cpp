#include "photon/photon_file.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv1a.h"

namespace mirage {

namespace {

constexpr char kMagic[8] = {'M', 'I', 'R', 'A', 'G', 'E', 'P', 'H'};
constexpr size_t kFingerprintBytes = 16;
constexpr size_t kPhotonBytes = 10 * sizeof(float) + sizeof(uint32_t);
// Magic, version, frame, fingerprint, 3 counts, 5 u64 and 3 f64 figures.
constexpr size_t kHeaderBytes = 8 + 4 + 4 + kFingerprintBytes + 3 * 8 + 5 * 8 + 3 * 8;

// Every field of Photon is written; a new field must be added here and the version raised.
static_assert(sizeof(Photon) == kPhotonBytes, "Photon changed: update photon_file.cpp");
static_assert(sizeof(float) == 4 && sizeof(double) == 8, "IEEE 754 binary32/64 expected");

// The file is little-endian; every supported host is too (x86-64, AArch64), so values are
// copied as they lie in memory.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "a little-endian host is expected");

struct Writer {
    std::string bytes;
    template <typename T>
    void put(const T& v) {
        bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void putPhotons(const PhotonList& list) {
        for (const Photon& p : list) {
            const float f[10] = {p.p.x,  p.p.y,    p.p.z,   p.wi.x,     p.wi.y,
                                 p.wi.z, p.lambda, p.power, p.lambdaIn, p.time};
            bytes.append(reinterpret_cast<const char*>(f), sizeof f);
            put(p.light);
        }
    }
};

struct Reader {
    const std::string& bytes;
    size_t at = 0;
    template <typename T>
    T get() {
        T v;
        std::memcpy(&v, bytes.data() + at, sizeof v);
        at += sizeof v;
        return v;
    }
    PhotonList getPhotons(uint64_t n) {
        PhotonList list(n);
        for (Photon& p : list) {
            float f[10];
            std::memcpy(f, bytes.data() + at, sizeof f);
            at += sizeof f;
            p.p = Vec3(f[0], f[1], f[2]);
            p.wi = Vec3(f[3], f[4], f[5]);
            p.lambda = f[6];
            p.power = f[7];
            p.lambdaIn = f[8];
            p.time = f[9];
            p.light = get<uint32_t>();
        }
        return list;
    }
};

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw MirageError(FileLoc{path, 0, 0}, "not a usable photon file: " + why);
}

std::string readWhole(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw MirageError(FileLoc{path, 0, 0}, "cannot open the photon file");
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// Checks magic, version, size and checksum and reads the header; "" when intact, else why not.
std::string checkFile(const std::string& bytes, PhotonFileHeader* h, Reader* r) {
    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return "it does not start with the magic 'MIRAGEPH'";
    if (bytes.size() < kHeaderBytes + 8)
        return "truncated: " + std::to_string(bytes.size()) + " bytes, shorter than the header";
    r->at = sizeof kMagic;
    h->version = r->get<uint32_t>();
    if (h->version != kPhotonFileVersion)
        return "format version " + std::to_string(h->version) + ", this mirage reads version " +
               std::to_string(kPhotonFileVersion);
    h->frame = r->get<uint32_t>();
    h->fingerprint.assign(bytes.data() + r->at, kFingerprintBytes);
    r->at += kFingerprintBytes;
    h->volume = r->get<uint64_t>();
    h->global = r->get<uint64_t>();
    h->caustic = r->get<uint64_t>();
    // Counts too large to be real would overflow the size below: refuse them first.
    const uint64_t limit = uint64_t(1) << 40;
    if (h->volume > limit || h->global > limit || h->caustic > limit)
        return "corrupt photon counts in the header";
    const uint64_t expected =
        kHeaderBytes + (h->volume + h->global + h->caustic) * kPhotonBytes + 8;
    if (bytes.size() != expected)
        return (bytes.size() < expected ? "truncated: " : "too long: ") +
               std::to_string(bytes.size()) + " bytes, the header's counts need " +
               std::to_string(expected);
    Fnv1a sum;
    sum.bytes(bytes.data(), bytes.size() - 8);
    uint64_t stored;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != sum.h) return "corrupt: the checksum does not match the content";
    return "";
}

}  // namespace

void writePhotonFile(const std::string& path, const PhotonFileHeader& header,
                     const PhotonPassResult& pass) {
    MIRAGE_CHECK(header.fingerprint.size() == kFingerprintBytes);
    const PhotonMapLists& m = pass.maps;
    const PhotonPassStats& s = pass.stats;
    Writer w;
    w.bytes.reserve(kHeaderBytes + 8 +
                    (m.volume.size() + m.surfaceGlobal.size() + m.surfaceCaustic.size()) *
                        kPhotonBytes);
    w.bytes.append(kMagic, sizeof kMagic);
    w.put(kPhotonFileVersion);
    w.put(header.frame);
    w.bytes.append(header.fingerprint);
    w.put(uint64_t(m.volume.size()));
    w.put(uint64_t(m.surfaceGlobal.size()));
    w.put(uint64_t(m.surfaceCaustic.size()));
    for (uint64_t v : {s.emitted, s.stored, s.cappedPaths, s.nonFinite, s.fromMedia}) w.put(v);
    for (double v : {s.mediumPower, s.emittedPower, s.seconds}) w.put(v);
    MIRAGE_CHECK(w.bytes.size() == kHeaderBytes);
    w.putPhotons(m.volume);
    w.putPhotons(m.surfaceGlobal);
    w.putPhotons(m.surfaceCaustic);
    Fnv1a sum;
    sum.bytes(w.bytes.data(), w.bytes.size());
    w.put(sum.h);

    createParentFolders(path);
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            std::ofstream f(tmp, std::ios::binary);
            f.write(w.bytes.data(), std::streamsize(w.bytes.size()));
            f.close();
            if (!f) throw MirageError(FileLoc{path, 0, 0}, "cannot write the photon file");
        },
        "cannot move the photon file into place");
}

PhotonPassResult readPhotonFile(const std::string& path, PhotonFileHeader* header) {
    const std::string bytes = readWhole(path);
    PhotonFileHeader h;
    Reader r{bytes};
    const std::string why = checkFile(bytes, &h, &r);
    if (!why.empty()) refuse(path, why);
    PhotonPassResult pass;
    PhotonPassStats& s = pass.stats;
    for (uint64_t* v : {&s.emitted, &s.stored, &s.cappedPaths, &s.nonFinite, &s.fromMedia})
        *v = r.get<uint64_t>();
    for (double* v : {&s.mediumPower, &s.emittedPower, &s.seconds}) *v = r.get<double>();
    pass.maps.volume = r.getPhotons(h.volume);
    pass.maps.surfaceGlobal = r.getPhotons(h.global);
    pass.maps.surfaceCaustic = r.getPhotons(h.caustic);
    if (header) *header = h;
    return pass;
}

bool readPhotonFileHeader(const std::string& path, PhotonFileHeader* header) {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return false;
    probe.close();
    const std::string bytes = readWhole(path);
    PhotonFileHeader h;
    Reader r{bytes};
    if (!checkFile(bytes, &h, &r).empty()) return false;
    if (header) *header = h;
    return true;
}

}  // namespace mirage
