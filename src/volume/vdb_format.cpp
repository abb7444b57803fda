#include "volume/vdb_format.h"

#include <nanovdb/NanoVDB.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/grid_name.h"
#include "volume/vdb_reader.h"

namespace mirage::vdbformat {

namespace {

// OpenVDB writes its magic number 0x56444220 (" BDV" read as little-endian int32) as an int64.
constexpr unsigned char kOpenVdbMagic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
constexpr unsigned char kNanoVdbMagic[8] = {'N', 'a', 'n', 'o', 'V', 'D', 'B', '0'};
constexpr uint32_t kNanoMajorVersion = 32;  // NANOVDB_MAJOR_VERSION_NUMBER: the file ABI
constexpr uint64_t kNanoHeaderBytes = 16, kNanoMetaBytes = 176;

// Offsets or sizes beyond this (1 TiB) are corrupt values rather than a truncated file.
constexpr uint64_t kMaxPlausibleBytes = uint64_t(1) << 40;
constexpr uint64_t kMaxCompressionRatio = 1032;

const char kUniqueNameSeparator = '\x1e';  // OpenVDB's "record separator" before "N"

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

std::string num(uint64_t v) { return std::to_string(v); }

std::string displayName(const GridRecord& g) {
    size_t sep = g.uniqueName.find(kUniqueNameSeparator);
    if (sep == std::string::npos) return g.uniqueName;
    return g.uniqueName.substr(0, sep) + "[" + g.uniqueName.substr(sep + 1) + "]";
}

std::string labelOf(const GridRecord& g, size_t index) {
    return g.name.empty() ? gridIndexName(index) : "'" + displayName(g) + "'";
}

// Bytes OpenVDB's registered metadata types read for their value (openvdb::initialize(); sizes
// checked against Metadata::createMetadata(type)->size() of OpenVDB 10). OpenVDB reads sizeof(T)
// whatever size the file states, so a different size would put its reader somewhere the scan
// never checked. 0: the type is not a fixed-size one.
uint32_t fixedMetadataBytes(const std::string& type) {
    static const std::pair<const char*, uint32_t> kTypes[] = {
        {"bool", 1},    {"double", 8},      {"float", 4},  {"int32", 4},  {"int64", 8},
        {"vec2i", 8},   {"vec2s", 8},       {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12},
        {"vec3d", 24},  {"vec4i", 16},      {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64},
        {"mat4d", 128}, {"ptdataidx32", 4}, {"ptidx32", 4}};
    for (const auto& [name, bytes] : kTypes)
        if (type == name) return bytes;
    return 0;
}

// OpenVDB's "__delayedload" metadata (io/DelayedLoadMetadata.cc): uint32 leaf count, then a
// mask array (uint32 byte count, Blosc-compressed when non-zero, else `count` raw bytes), then a
// compressed-size array (uint32 byte count, 0xFFFFFFFF when absent, Blosc or `count` × 8 raw
// bytes). OpenVDB sizes the arrays by the stored count before it reads them (4 GiB for a
// corrupt count), so the count is bounded by the grid's bytes (a leaf takes at least 64) and
// every part must fit in the item's stated size, which is what OpenVDB skips to afterwards.
void checkDelayedLoadMetadata(Reader& r, const std::string& what, uint32_t bytes, uint64_t extent) {
    if (bytes == 0) return;
    const uint64_t start = r.pos(), end = start + bytes;
    auto corrupt = [&](const std::string& why) {
        r.fail("corrupt: " + what + " at byte " + num(start) + ": " + why);
    };
    if (bytes < 8) corrupt("needs at least 8 bytes, has " + num(bytes));
    const uint32_t count = r.pod<uint32_t>(what);
    if (uint64_t(count) * 64 > extent)
        corrupt("claims " + num(count) + " leaves in a grid of " + num(extent) + " bytes");
    for (uint32_t elementBytes : {1u, 8u}) {
        if (r.pos() + 4 > end) corrupt("runs past its " + num(bytes) + " bytes");
        const uint32_t stored = r.pod<uint32_t>(what);
        if (elementBytes == 8 && stored == 0xFFFFFFFFu) break;  // no compressed sizes
        const uint64_t raw = uint64_t(count) * elementBytes;
        const uint64_t size = stored > 0 ? stored : raw;
        if (r.pos() + size > end) corrupt("runs past its " + num(bytes) + " bytes");
        if (stored > 0) {
            // A Blosc frame: its header states the uncompressed and compressed sizes.
            unsigned char header[16];
            if (stored < sizeof(header)) corrupt("has a Blosc frame of " + num(stored) + " bytes");
            r.read(header, sizeof(header), what);
            uint32_t nbytes, cbytes;
            std::memcpy(&nbytes, header + 4, 4);
            std::memcpy(&cbytes, header + 12, 4);
            // compression::bloscCompress pads inputs under 128 bytes to 128
            // (points/StreamCompression.cc); OpenVDB reserves what the header states.
            const bool padded = raw < 128 && nbytes == 128;
            if ((nbytes != raw && !padded) || cbytes != stored)
                corrupt("a Blosc frame of " + num(stored) + " bytes claims " + num(cbytes) +
                        " compressed and " + num(nbytes) + " uncompressed bytes for " + num(count) +
                        " leaves");
            r.skip(stored - sizeof(header), what);
        } else {
            r.skip(raw, what);
        }
    }
    r.seek(end);
}

// Skips a MetaMap (file or grid metadata), checking each length, and each value's layout where
// OpenVDB reads a type's own layout rather than the stated size. `extent` is the bytes of the
// grid the metadata belongs to (the file's size for file metadata).
void skipMetadata(Reader& r, const std::string& owner, uint64_t extent) {
    uint32_t count = r.pod<uint32_t>(owner + " metadata count");
    // Each item needs at least 12 bytes: two string lengths and a value size.
    if (uint64_t(count) * 12 > r.remaining())
        r.require(uint64_t(count) * 12, owner + " metadata (" + num(count) + " items)");
    for (uint32_t i = 0; i < count; ++i) {
        std::string name = r.str(owner + " metadata name");
        const std::string type = r.str(owner + " metadata type of '" + name + "'");
        uint32_t bytes = r.pod<uint32_t>(owner + " metadata size of '" + name + "'");
        const std::string what = owner + " metadata value '" + boundedMessage(name, 40) + "'";
        r.require(bytes, what);
        const uint32_t fixed = fixedMetadataBytes(type);
        if (fixed != 0 && bytes != fixed)
            r.fail("corrupt: " + what + " of type " + type + " at byte " + num(r.pos()) + " has " +
                   num(bytes) + " bytes, expected " + num(fixed));
        if (type == "__delayedload")
            checkDelayedLoadMetadata(r, what, bytes, extent);
        else
            r.skip(bytes, what);
    }
}

// Bytes of an index → object map after its type name, as each map's read() takes them
// (math/Maps.h): Vec3d members are 24 bytes, a Mat4d 128. A frustum holds a second, linear map.
uint64_t mapBytes(Reader& r, const std::string& type, const std::string& what, bool nested) {
    static const std::pair<const char*, uint64_t> kMaps[] = {{"AffineMap", 128},
                                                             {"UnitaryMap", 128},
                                                             {"ScaleMap", 5 * 24},
                                                             {"UniformScaleMap", 5 * 24},
                                                             {"TranslationMap", 24},
                                                             {"ScaleTranslateMap", 6 * 24},
                                                             {"UniformScaleTranslateMap", 6 * 24}};
    for (const auto& [name, bytes] : kMaps)
        if (type == name) return bytes;
    if (type == "NonlinearFrustumMap" && !nested) {
        // bbox (6 doubles, file version 221 on), taper, depth, then the second map.
        const uint64_t begin = r.pos();
        r.skip(48 + 16, what);
        const std::string second = r.str(what + " (second map type)");
        const uint64_t bytes = mapBytes(r, second, what, true);
        r.seek(begin);
        return 48 + 16 + 4 + second.size() + bytes;
    }
    r.fail("unsupported: " + what + " has map type '" + boundedMessage(type, 40) +
           "' (expected one of OpenVDB's registered maps)");
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

    skipMetadata(r, "file", L.fileSize);
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
        // An instance holds metadata and a transform only (io::Archive::writeGridInstance
        // leaves its data offset at 0): its tree is its parent's.
        if (!g.instanceParent.empty() && g.blockPos == 0) g.blockPos = g.endPos;
        if (g.gridPos < descriptorEnd || g.blockPos < g.gridPos || g.endPos < g.blockPos)
            fail(path, "corrupt: grid " + label + " has offsets out of order (descriptor ends at " +
                           num(descriptorEnd) + ", grid " + num(g.gridPos) + ", data " +
                           num(g.blockPos) + ", end " + num(g.endPos) + ")");

        r.seek(g.gridPos);
        g.compression =
            v >= 222 ? r.pod<uint32_t>("compression of grid " + label) : fileCompression;
        skipMetadata(r, "grid " + label, g.endPos - g.gridPos);
        if (r.pos() > g.blockPos)
            fail(path, "corrupt: the metadata of grid " + label + " runs past its data (byte " +
                           num(g.blockPos) + ")");
        // The transform follows (file version 216 on, io/Archive.cc): OpenVDB allocates its
        // map type name at whatever length the file claims (4 GiB in an input fuzz_vdb found)
        // before reading it, so the length is checked here. From version 222 on (the layout
        // vdb_tree.cpp walks) the map's own bytes are skipped too: the tree starts after them.
        if (v >= 216) {
            const std::string what = "transform of grid " + label;
            const std::string mapType = r.str(what);
            if (v >= 222) {
                r.skip(mapBytes(r, mapType, what, false), what);
                g.topologyPos = r.pos();
            }
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
            // Deflate cannot shrink data more than 1032:1 (zlib's technical notes), LZ4 in
            // Blosc about 255:1: a larger ratio is a corrupt size, which Mirage would otherwise
            // allocate before decompressing (128 GiB in an input fuzz_vdb found).
            if (codec != 0 && g.nanoGridBytes / kMaxCompressionRatio > bytes)
                r.fail("corrupt: NanoVDB grid " + label + " claims " + num(g.nanoGridBytes) +
                       " bytes from " + num(bytes) + " compressed bytes");
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
        std::string item = layout.grids[i].name.empty() ? gridIndexName(i) + " (unnamed)"
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

// True when the grid's fixed-size parts, the root's tile table and each level's node array lie
// within the `bytes` of its buffer. Unsigned arithmetic: an offset or count from a corrupt file
// cannot wrap the comparisons (each product is at most 2^32 × a node's size).
bool nanoLayoutFits(const nanovdb::FloatGrid& grid, uint64_t bytes) {
    using TreeT = nanovdb::FloatTree;
    const auto* base = reinterpret_cast<const uint8_t*>(&grid);
    auto fits = [&](const void* p, uint64_t size) {
        const auto* q = reinterpret_cast<const uint8_t*>(p);
        if (q < base) return false;
        const uint64_t at = uint64_t(q - base);
        return at <= bytes && size <= bytes - at;
    };
    const TreeT& tree = grid.tree();
    if (!fits(&tree, sizeof(TreeT))) return false;
    const auto* data = tree.data();
    // Every node type is a multiple of NanoVDB's 32-byte alignment and the buffer starts on
    // one: an offset off it is corrupt, and binding a node reference there is undefined
    // behaviour before any bound is checked (fuzz_vdb found a root 8 bytes off).
    for (uint64_t offset : data->mNodeOffset)
        if (offset % NANOVDB_DATA_ALIGNMENT != 0) return false;
    if (data->mNodeOffset[3] > bytes) return false;
    const auto* root = reinterpret_cast<const uint8_t*>(data) + data->mNodeOffset[3];
    if (!fits(root, sizeof(nanovdb::FloatTree::RootType))) return false;
    if (!fits(root, tree.root().memUsage())) return false;
    // The checksum's first span: grid, tree and root as one contiguous run.
    if (grid.memUsage() + tree.memUsage() + tree.root().memUsage() > bytes) return false;
    const uint64_t nodeBytes[3] = {sizeof(nanovdb::FloatTree::LeafNodeType),
                                   sizeof(nanovdb::FloatTree::Node1),
                                   sizeof(nanovdb::FloatTree::Node2)};
    for (int level = 0; level < 3; ++level) {
        if (data->mNodeCount[level] == 0) continue;
        if (data->mNodeOffset[level] > bytes) return false;
        const auto* first = reinterpret_cast<const uint8_t*>(data) + data->mNodeOffset[level];
        if (!fits(first, uint64_t(data->mNodeCount[level]) * nodeBytes[level])) return false;
    }
    return true;
}

std::string compressionName(uint32_t flags, Format format) {
    if (format == Format::NanoVdb) return flags == 2 ? "blosc" : (flags == 1 ? "zip" : "none");
    if (flags & kCompressBlosc) return "blosc";
    if (flags & kCompressZip) return "zip";
    return flags & kCompressActiveMask ? "active mask" : "none";
}

std::string nanoClassName(uint32_t c) {
    static const char* kNames[] = {"unknown",   "level set",    "fog volume",
                                   "staggered", "point index",  "point data",
                                   "topology",  "voxel volume", "index grid"};
    return c < sizeof(kNames) / sizeof(kNames[0]) ? kNames[c] : "unknown";
}

// What a value type is, for "expected a scalar fog volume" messages.
std::string describeValueType(const std::string& t) {
    if (t == "vec3s" || t == "vec3d" || t == "vec3i" || t == "vec3f") return "3-vector (" + t + ")";
    if (t == "bool" || t == "mask") return "boolean (" + t + ")";
    if (t.compare(0, 3, "int") == 0 || t.compare(0, 4, "uint") == 0) return "integer (" + t + ")";
    if (t.compare(0, 2, "fp") == 0) return "quantized (" + t + ")";
    if (t.compare(0, 6, "ptdata") == 0) return "point (" + t + ")";
    return "'" + t + "'";
}

}  // namespace mirage::vdbformat
