// The on-disk layout of OpenVDB and NanoVDB files, scanned with every length and offset checked
// against the file size before it is used. OpenVDB's own reader trusts the file: a truncated or
// corrupt file makes it seek past the end, allocate gigabytes for a garbage string length, or
// report a message of megabytes. Scanning first turns those into one clear message.
//
// OpenVDB layout (io/Archive.cc, io/File.cc, io/GridDescriptor.cc; all little-endian):
//   header    int64 magic 0x56444220, uint32 file version, uint32 × 2 library version (≥ 211),
//             char has-grid-offsets (≥ 212), char compression (220–221), uuid (36 ASCII bytes
//             from 218 on, 16 raw bytes before)
//   metadata  uint32 count, then per item: string name, string type, uint32 size, size bytes
//   grids     int32 count, then per grid a descriptor: string unique name, string type
//             (suffix "_HalfFloat" when stored as half), string instance parent (≥ 216),
//             int64 grid, block and end offsets; the grid itself lies in [grid, end) and the
//             next descriptor starts at end. A grid starts with uint32 compression flags
//             (≥ 222) and its own metadata.
//   Strings are a uint32 length then that many bytes.
// NanoVDB layout (nanovdb/util/IO.h): segments of a 16-byte header (magic "NanoVDB0", version,
// uint16 grid count, uint16 codec), per grid 176 bytes of metadata and its name, then the grids'
// data (raw, zip, or Blosc chunks of ≤ 1 GiB each prefixed by an int64 byte count).
//
// This file does not include OpenVDB headers; its constants are those of file version 224.
#pragma once

#include <nanovdb/NanoVDB.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mirage::vdbformat {

enum class Format { OpenVdb, NanoVdb };

// OpenVDB per-grid compression flags (io/Compression.h).
constexpr uint32_t kCompressZip = 0x1, kCompressActiveMask = 0x2, kCompressBlosc = 0x4;
// Newest OpenVDB file version this reader knows (OPENVDB_FILE_VERSION of OpenVDB 10).
constexpr uint32_t kMaxOpenVdbFileVersion = 224;
// Oldest one: library version numbers are in the header from 211 on.
constexpr uint32_t kMinOpenVdbFileVersion = 211;

// One grid as the file's own index describes it.
struct GridRecord {
    std::string name;        // as written (may be empty); OpenVDB's "[N]" suffix stripped
    std::string uniqueName;  // OpenVDB: name + "\x1e" + N for the N-th duplicate name
    std::string type;        // OpenVDB tree type ("Tree_float_5_4_3") or NanoVDB value type
    bool savedAsHalf = false;
    std::string instanceParent;
    uint64_t gridPos = 0, blockPos = 0, endPos = 0;  // byte offsets of the grid in the file
    // OpenVDB, file version 222 on: where the tree's topology starts (after the grid's
    // metadata and transform); 0 when unknown (older files).
    uint64_t topologyPos = 0;
    uint32_t compression = 0;  // OpenVDB flags above; NanoVDB codec (0 none, 1 zip, 2 blosc)
    // NanoVDB only: the segment's metadata for this grid.
    uint64_t nanoGridBytes = 0;  // uncompressed size in memory
    uint32_t nanoGridType = 0, nanoGridClass = 0;
    uint64_t nanoVoxelCount = 0;
    int32_t nanoIndexBBox[6] = {0, 0, 0, 0, 0, 0};
    double nanoWorldBBox[6] = {0, 0, 0, 0, 0, 0};
    double nanoVoxelSize[3] = {0, 0, 0};
    uint32_t nanoVersion = 0;
};

struct FileLayout {
    Format format = Format::OpenVdb;
    uint64_t fileSize = 0;
    uint32_t fileVersion = 0;  // OpenVDB file format version; NanoVDB packed version
    uint32_t libraryMajor = 0, libraryMinor = 0;
    std::vector<GridRecord> grids;  // in file order
};

// Checks existence, type, size, magic number and version, then walks every descriptor and
// offset. Throws MirageError "<path>: <what is wrong>".
FileLayout scanFile(const std::string& path);

// Index of the grid called `nameOrIndex` — an exact name first, then "#N" (0-based, file
// order), then OpenVDB's "name[N]" form for duplicate names — or -1.
int findGrid(const FileLayout& layout, const std::string& nameOrIndex);

// "'density'" for a named grid, "#0" for an unnamed one: how messages refer to a grid.
std::string gridLabel(const FileLayout& layout, int index);

// "density, heat" or "#0 (unnamed)" — the grids of a file for a "no such grid" message,
// bounded in length.
std::string gridList(const FileLayout& layout);

// "float" from "Tree_float_5_4_3"; NanoVDB type names pass through.
std::string valueTypeOf(const GridRecord& record);

// "nanovdb 32.4.2" style version text from NanoVDB's packed version number.
std::string nanoVersionString(uint32_t packed);

// True when a NanoVDB float grid's fixed-size parts, its root's tile table and each level's
// node array lie within the `bytes` of its buffer, each on NanoVDB's 32-byte alignment (a
// corrupt file's offsets, checked before any NanoVDB accessor follows them).
bool nanoLayoutFits(const nanovdb::FloatGrid& grid, uint64_t bytes);

// Names of a grid's fields for `mirage info` and messages: its compression, a NanoVDB grid
// class, and what a value type is ("expected a scalar fog volume").
std::string compressionName(uint32_t flags, Format format);
std::string nanoClassName(uint32_t gridClass);
std::string describeValueType(const std::string& valueType);

}  // namespace mirage::vdbformat
