#include "volume/vdb_format.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace mirage::vdbformat {

namespace {

// OpenVDB writes its magic number 0x56444220 (" BDV" read as little-endian int32) as an int64.
constexpr unsigned char kOpenVdbMagic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
constexpr unsigned char kNanoVdbMagic[8] = {'N', 'a', 'n', 'o', 'V', 'D', 'B', '0'};
constexpr uint32_t kNanoMajorVersion = 32;  // NANOVDB_MAJOR_VERSION_NUMBER: the file ABI
constexpr uint64_t kNanoHeaderBytes = 16, kNanoMetaBytes = 176;

// Names and type names longer than this are a corrupt length field, not a long name.
constexpr uint32_t kMaxNameBytes = 1u << 16;
// Offsets or sizes beyond this (1 TiB) are corrupt values rather than a truncated file.
constexpr uint64_t kMaxPlausibleBytes = uint64_t(1) << 40;

const char kUniqueNameSeparator = '\x1e';  // OpenVDB's "record separator" before "N"

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

std::string num(uint64_t v) { return std::to_string(v); }

// Sequential reads from the file where every read is first checked against the file size, so
// that a bad length is reported, never trusted.
class Reader {
public:
    Reader(const std::string& path, std::ifstream& in, uint64_t size)
        : mPath(path), mIn(in), mSize(size) {}

    uint64_t pos() const { return mPos; }
    uint64_t size() const { return mSize; }
    uint64_t remaining() const { return mPos < mSize ? mSize - mPos : 0; }
    void seek(uint64_t p) { mPos = p; }

    void require(uint64_t n, const std::string& what) const {
        if (n > mSize || mPos > mSize - n)
            fail(mPath, "truncated: " + what + " at byte " + num(mPos) + " needs " + num(n) +
                            " bytes but the file has " + num(mSize) + " bytes");
    }
    void read(void* dst, uint64_t n, const std::string& what) {
        require(n, what);
        if (mStreamPos != mPos) mIn.seekg(std::streamoff(mPos));
        mIn.read(static_cast<char*>(dst), std::streamsize(n));
        if (!mIn) fail(mPath, "read error at byte " + num(mPos) + ": " + std::strerror(errno));
        mPos += n;
        mStreamPos = mPos;
    }
    template <typename T>
    T pod(const std::string& what) {
        T v{};
        read(&v, sizeof(T), what);
        return v;
    }
    void skip(uint64_t n, const std::string& what) {
        require(n, what);
        mPos += n;
    }
    // OpenVDB string: uint32 length, then the bytes.
    std::string str(const std::string& what) {
        uint32_t n = pod<uint32_t>(what);
        if (n > kMaxNameBytes)
            fail(mPath,
                 "corrupt: " + what + " at byte " + num(mPos - 4) + " claims " + num(n) + " bytes");
        std::string s(n, '\0');
        read(s.data(), n, what);
        return s;
    }

private:
    const std::string& mPath;
    std::ifstream& mIn;
    uint64_t mSize;
    uint64_t mPos = 0;
    uint64_t mStreamPos = ~uint64_t(0);  // where the stream is; unknown at first
};

std::string displayName(const GridRecord& g) {
    size_t sep = g.uniqueName.find(kUniqueNameSeparator);
    if (sep == std::string::npos) return g.uniqueName;
    return g.uniqueName.substr(0, sep) + "[" + g.uniqueName.substr(sep + 1) + "]";
}

std::string labelOf(const GridRecord& g, size_t index) {
    return g.name.empty() ? "#" + num(index) : "'" + displayName(g) + "'";
}

// Skips a MetaMap (file or grid metadata), checking each length.
void skipMetadata(Reader& r, const std::string& owner) {
    uint32_t count = r.pod<uint32_t>(owner + " metadata count");
    // Each item needs at least 12 bytes: two string lengths and a value size.
    if (uint64_t(count) * 12 > r.remaining())
        r.require(uint64_t(count) * 12, owner + " metadata (" + num(count) + " items)");
    for (uint32_t i = 0; i < count; ++i) {
        std::string name = r.str(owner + " metadata name");
        r.str(owner + " metadata type of '" + name + "'");
        uint32_t bytes = r.pod<uint32_t>(owner + " metadata size of '" + name + "'");
        r.skip(bytes, owner + " metadata value '" + name + "'");
    }
}

void checkGridExtent(const std::string& path, const std::string& label, uint64_t end,
                     uint64_t fileSize) {
    if (end <= fileSize) return;
    if (end > kMaxPlausibleBytes)
        fail(path, "corrupt: grid " + label + " claims to end at byte " + num(end));
    fail(path, "truncated: grid " + label + " ends at byte " + num(end) + " but the file has " +
                   num(fileSize) + " bytes");
}

void scanOpenVdb(const std::string& path, Reader& r, FileLayout& L) {
    r.skip(8, "magic number");
    uint32_t v = L.fileVersion = r.pod<uint32_t>("OpenVDB header");
    if (v < kMinOpenVdbFileVersion || v > kMaxOpenVdbFileVersion)
        fail(path, "unsupported OpenVDB file format version " + num(v) + " (this build reads " +
                       num(kMinOpenVdbFileVersion) + " to " + num(kMaxOpenVdbFileVersion) +
                       (v > 1000 ? "; the header is probably corrupt)" : ")"));
    L.libraryMajor = r.pod<uint32_t>("OpenVDB header");
    L.libraryMinor = r.pod<uint32_t>("OpenVDB header");
    bool hasGridOffsets = true;
    if (v >= 212) hasGridOffsets = r.pod<char>("OpenVDB header") != 0;

    // Before 222 compression was a file-wide setting; from 222 on each grid states its own.
    uint32_t fileCompression = kCompressZip | kCompressActiveMask;
    if (v >= 220 && v < 222)
        fileCompression = r.pod<char>("OpenVDB header") != 0 ? kCompressZip : 0;
    r.skip(v >= 218 ? 36 : 16, "OpenVDB header (uuid)");

    skipMetadata(r, "file");
    if (!hasGridOffsets)
        fail(path,
             "is an OpenVDB stream without grid offsets (written by io::Stream); Mirage "
             "reads seekable .vdb files: re-save it with OpenVDB's io::File");

    int32_t count = r.pod<int32_t>("grid count");
    // A descriptor needs at least three string lengths and three offsets (36 bytes).
    if (count < 0 || uint64_t(count) * 36 > r.remaining()) {
        if (count < 0 || count > (1 << 24))
            fail(path,
                 "corrupt: grid count " + std::to_string(count) + " at byte " + num(r.pos() - 4));
        r.require(uint64_t(count) * 36, "descriptors of " + num(uint64_t(count)) + " grids");
    }
    for (int32_t i = 0; i < count; ++i) {
        GridRecord g;
        g.uniqueName = r.str("name of grid #" + num(uint64_t(i)));
        g.name = g.uniqueName.substr(0, g.uniqueName.find(kUniqueNameSeparator));
        const std::string label = labelOf(g, size_t(i));
        g.type = r.str("type of grid " + label);
        static const std::string kHalf = "_HalfFloat";
        if (g.type.size() > kHalf.size() &&
            g.type.compare(g.type.size() - kHalf.size(), kHalf.size(), kHalf) == 0) {
            g.savedAsHalf = true;
            g.type.resize(g.type.size() - kHalf.size());
        }
        if (v >= 216) g.instanceParent = r.str("instance parent of grid " + label);
        int64_t offsets[3];
        r.read(offsets, sizeof(offsets), "offsets of grid " + label);
        uint64_t descriptorEnd = r.pos();
        for (int64_t o : offsets)
            if (o < 0) fail(path, "corrupt: grid " + label + " has a negative offset");
        g.gridPos = uint64_t(offsets[0]);
        g.blockPos = uint64_t(offsets[1]);
        g.endPos = uint64_t(offsets[2]);
        checkGridExtent(path, label, g.endPos, L.fileSize);
        if (g.gridPos < descriptorEnd || g.blockPos < g.gridPos || g.endPos < g.blockPos)
            fail(path, "corrupt: grid " + label + " has offsets out of order (descriptor ends at " +
                           num(descriptorEnd) + ", grid " + num(g.gridPos) + ", data " +
                           num(g.blockPos) + ", end " + num(g.endPos) + ")");

        r.seek(g.gridPos);
        g.compression =
            v >= 222 ? r.pod<uint32_t>("compression of grid " + label) : fileCompression;
        skipMetadata(r, "grid " + label);
        if (r.pos() > g.blockPos)
            fail(path, "corrupt: the metadata of grid " + label + " runs past its data (byte " +
                           num(g.blockPos) + ")");
        // The transform follows (file version 216 on, io/Archive.cc): OpenVDB allocates its
        // map type name at whatever length the file claims (4 GiB in an input fuzz_vdb found)
        // before reading it, so the length is checked here.
        if (v >= 216) {
            r.str("transform type of grid " + label);
            if (r.pos() > g.blockPos)
                fail(path, "corrupt: the transform of grid " + label +
                               " runs past its data (byte " + num(g.blockPos) + ")");
        }
        r.seek(g.endPos);
        L.grids.push_back(std::move(g));
    }
}

template <typename T>
T field(const unsigned char* p, size_t offset) {
    T v;
    std::memcpy(&v, p + offset, sizeof(T));
    return v;
}

void scanNanoVdb(const std::string& path, Reader& r, FileLayout& L) {
    while (r.remaining() > 0) {
        const uint64_t segmentStart = r.pos();
        unsigned char header[kNanoHeaderBytes];
        r.read(header, kNanoHeaderBytes, "NanoVDB segment header");
        if (std::memcmp(header, kNanoVdbMagic, 8) != 0)
            fail(path, "corrupt: NanoVDB segment at byte " + num(segmentStart) +
                           " has a bad magic number");
        uint32_t version = field<uint32_t>(header, 8);
        if (L.grids.empty()) L.fileVersion = version;
        if ((version >> 21) != kNanoMajorVersion)
            fail(path, "NanoVDB file version " + nanoVersionString(version) +
                           " is not supported (this build reads " + num(kNanoMajorVersion) +
                           ".x; re-convert the file with this version's nanovdb_convert)");
        uint16_t count = field<uint16_t>(header, 12), codec = field<uint16_t>(header, 14);
        if (codec > 2)
            fail(path, "corrupt: NanoVDB segment at byte " + num(segmentStart) +
                           " has unknown codec " + num(codec));

        const size_t first = L.grids.size();
        for (uint16_t i = 0; i < count; ++i) {
            unsigned char meta[kNanoMetaBytes];
            const std::string what = "NanoVDB metadata of grid #" + num(first + i);
            r.read(meta, kNanoMetaBytes, what);
            GridRecord g;
            g.nanoGridBytes = field<uint64_t>(meta, 0);
            g.endPos = field<uint64_t>(meta, 8);  // the grid's size in the file, for now
            g.nanoVoxelCount = field<uint64_t>(meta, 24);
            g.nanoGridType = field<uint32_t>(meta, 32);
            g.nanoGridClass = field<uint32_t>(meta, 36);
            std::memcpy(g.nanoWorldBBox, meta + 40, sizeof(g.nanoWorldBBox));
            std::memcpy(g.nanoIndexBBox, meta + 88, sizeof(g.nanoIndexBBox));
            std::memcpy(g.nanoVoxelSize, meta + 112, sizeof(g.nanoVoxelSize));
            uint32_t nameSize = field<uint32_t>(meta, 136);
            g.nanoVersion = field<uint32_t>(meta, 172);
            if (nameSize > kMaxNameBytes)
                fail(path, "corrupt: " + what + " claims a name of " + num(nameSize) + " bytes");
            std::string name(nameSize, '\0');
            r.read(name.data(), nameSize, "name of NanoVDB grid #" + num(first + i));
            g.name = g.uniqueName = std::string(name.c_str());
            g.type = valueTypeOf(g);
            g.compression = codec;
            L.grids.push_back(std::move(g));
        }
        // The grids' data follow the segment's metadata, one after the other.
        uint64_t cursor = r.pos();
        for (size_t i = first; i < L.grids.size(); ++i) {
            GridRecord& g = L.grids[i];
            const std::string label = labelOf(g, i);
            uint64_t bytes = g.endPos;
            if (bytes > kMaxPlausibleBytes || g.nanoGridBytes > kMaxPlausibleBytes)
                fail(path, "corrupt: NanoVDB grid " + label + " claims " +
                               num(std::max(bytes, g.nanoGridBytes)) + " bytes");
            if (codec == 0 && bytes != g.nanoGridBytes)
                fail(path, "corrupt: uncompressed NanoVDB grid " + label + " has " + num(bytes) +
                               " bytes in the file but " + num(g.nanoGridBytes) + " in memory");
            g.gridPos = g.blockPos = cursor;
            g.endPos = cursor + bytes;
            checkGridExtent(path, label, g.endPos, L.fileSize);
            cursor = g.endPos;
        }
        r.seek(cursor);
    }
    if (L.grids.empty() && L.fileSize < kNanoHeaderBytes)
        fail(path, "truncated: a NanoVDB header needs " + num(kNanoHeaderBytes) +
                       " bytes but the file has " + num(L.fileSize) + " bytes");
}

// A guess at what a non-VDB file is, to make "bad magic number" actionable.
std::string guessFormat(const unsigned char* b, size_t n) {
    auto starts = [&](const char* sig, size_t len) {
        return n >= len && std::memcmp(b, sig, len) == 0;
    };
    if (starts("\x89PNG", 4)) return "a PNG image";
    if (starts("\x76\x2f\x31\x01", 4)) return "an OpenEXR image";
    if (starts("\xff\xd8\xff", 3)) return "a JPEG image";
    if (starts("\x1f\x8b", 2)) return "gzip-compressed";
    if (starts("PK\x03\x04", 4)) return "a zip archive";
    bool text = true;
    for (size_t i = 0; i < n; ++i)
        text = text && (b[i] == '\n' || b[i] == '\r' || b[i] == '\t' || (b[i] >= 32 && b[i] < 127));
    return text ? "text" : "";
}

}  // namespace

FileLayout scanFile(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (st.type() == fs::file_type::not_found) fail(path, "file not found");
    if (ec) fail(path, "cannot be accessed: " + ec.message());
    if (fs::is_directory(st)) fail(path, "is a directory, not an OpenVDB file");
    if (!fs::is_regular_file(st)) fail(path, "is not a regular file");
    FileLayout L;
    L.fileSize = fs::file_size(path, ec);
    if (ec) fail(path, "cannot be accessed: " + ec.message());
    if (L.fileSize == 0) fail(path, "is empty (0 bytes); expected an OpenVDB file");

    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, std::string("cannot be opened: ") + std::strerror(errno));
    unsigned char magic[8] = {};
    size_t n = size_t(std::min<uint64_t>(8, L.fileSize));
    if (!in.read(reinterpret_cast<char*>(magic), std::streamsize(n)))
        fail(path, std::string("read error: ") + std::strerror(errno));

    Reader r(path, in, L.fileSize);
    if (std::memcmp(magic, kOpenVdbMagic, n) == 0) {
        L.format = Format::OpenVdb;
        scanOpenVdb(path, r, L);
    } else if (std::memcmp(magic, kNanoVdbMagic, n) == 0) {
        L.format = Format::NanoVdb;
        scanNanoVdb(path, r, L);
    } else {
        std::string guess = guessFormat(magic, n);
        fail(path, "not an OpenVDB file (bad magic number)" +
                       (guess.empty() ? std::string() : "; it looks like " + guess));
    }
    return L;
}

int findGrid(const FileLayout& layout, const std::string& nameOrIndex) {
    const auto& grids = layout.grids;
    for (size_t i = 0; i < grids.size(); ++i)
        if (grids[i].name == nameOrIndex) return int(i);
    if (nameOrIndex.size() > 1 && nameOrIndex[0] == '#' && nameOrIndex.size() < 10 &&
        nameOrIndex.find_first_not_of("0123456789", 1) == std::string::npos) {
        size_t index = std::stoul(nameOrIndex.substr(1));
        if (index < grids.size()) return int(index);
    }
    for (size_t i = 0; i < grids.size(); ++i)
        if (displayName(grids[i]) == nameOrIndex) return int(i);
    return -1;
}

std::string gridLabel(const FileLayout& layout, int index) {
    return labelOf(layout.grids.at(size_t(index)), size_t(index));
}

std::string gridList(const FileLayout& layout) {
    if (layout.grids.empty()) return "the file has no grids";
    std::string s;
    for (size_t i = 0; i < layout.grids.size(); ++i) {
        std::string item = layout.grids[i].name.empty() ? "#" + num(i) + " (unnamed)"
                                                        : displayName(layout.grids[i]);
        if (s.size() + item.size() > 160) return s + ", … (" + num(layout.grids.size()) + " grids)";
        s += (s.empty() ? "" : ", ") + boundedMessage(item, 40);
    }
    return s;
}

std::string valueTypeOf(const GridRecord& g) {
    if (!g.type.empty()) {
        // OpenVDB tree type "Tree_<value>_5_4_3".
        if (g.type.compare(0, 5, "Tree_") != 0) return g.type;
        std::string value = g.type.substr(5, g.type.find('_', 5) - 5);
        return value == "float" && g.savedAsHalf ? "half" : value;
    }
    static const char* kNanoTypes[] = {"unknown", "float", "double", "int16", "int32",
                                       "int64",   "vec3s", "vec3d",  "mask",  "half",
                                       "uint32",  "bool",  "rgba8",  "fp4",   "fp8",
                                       "fp16",    "fpN",   "vec4s",  "vec4d", "index"};
    return g.nanoGridType < sizeof(kNanoTypes) / sizeof(kNanoTypes[0]) ? kNanoTypes[g.nanoGridType]
                                                                       : "unknown";
}

std::string nanoVersionString(uint32_t packed) {
    return num(packed >> 21) + "." + num((packed >> 10) & 0x7ff) + "." + num(packed & 0x3ff);
}

}  // namespace mirage::vdbformat
