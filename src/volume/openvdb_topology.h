// A float grid's tree read by OpenVDB as topology only: nodes, masks and tiles, its leaves left
// without values, for the converter to fill from Mirage's own leaf decoder
// (volume/vdb_leaf_values.h).
//
// OpenVDB's delayed loading also passes over every leaf's data to note where it lies, allocating
// a record per leaf (1.9 s of a 10⁹-voxel load, on one thread): the tree walk (vdb_tree.h) has
// indexed them already. The grid's metadata and transform come from OpenVDB's
// File::readGridMetadata; the topology from Grid::readTopology on a stream positioned where the
// file's index puts it, tagged as io::Archive tags it (OpenVDB 10, io/Archive.cc: file and
// library versions, the grid's compression flags and class, whether it was saved as half
// floats). Its leaves are partial (no value buffer): only their masks and origins may be read.
//
// Includes OpenVDB: only vdb_file.cpp includes it.
#pragma once

#include <openvdb/io/File.h>
#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "volume/openvdb_to_nano.h"
#include "volume/vdb_format.h"
#include "volume/vdb_tree.h"

namespace mirage {

// Grid `name` of `file` (open), record `record` of `layout` (a float tree, not an instance):
// its metadata, transform and topology, whose leaves are those `leaves` indexes; null where
// the converter does not take the grid (convertsDirectly: a staggered class, a long name), which
// the caller then reads whole. Throws MirageError naming `path` when the stream fails or the
// leaves are not the index's.
inline openvdb::FloatGrid::Ptr readFloatTopology(openvdb::io::File& file, const std::string& path,
                                                 const vdbformat::FileLayout& layout,
                                                 const vdbformat::GridRecord& record,
                                                 const std::string& name,
                                                 const vdbformat::LeafDataIndex& leaves) {
    openvdb::FloatGrid::Ptr grid =
        openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGridMetadata(name));
    if (!grid || !convertsDirectly(*grid)) return nullptr;
    std::ifstream is(path, std::ios::binary);
    auto meta = std::make_shared<openvdb::io::StreamMetadata>();
    meta->setFileVersion(layout.fileVersion);
    meta->setLibraryVersion(openvdb::VersionId(layout.libraryMajor, layout.libraryMinor));
    meta->setCompression(record.compression);
    meta->setGridClass(uint32_t(grid->getGridClass()));
    meta->setHalfFloat(grid->saveFloatAsHalf());
    openvdb::io::setStreamMetadataPtr(is, meta, /*transfer=*/true);
    openvdb::io::setVersion(is, openvdb::VersionId(layout.libraryMajor, layout.libraryMinor),
                            layout.fileVersion);
    openvdb::io::setDataCompression(is, record.compression);
    openvdb::io::setGridClass(is, uint32_t(grid->getGridClass()));
    openvdb::io::setHalfFloat(is, grid->saveFloatAsHalf());
    is.seekg(std::streamoff(record.topologyPos));
    grid->readTopology(is);
    if (!is || grid->tree().leafCount() != leaves.offsets.size())
        throw MirageError(FileLoc{path}, "the topology of grid '" + name +
                                             "' could not be read as the tree walk read it");
    return grid;
}

}  // namespace mirage
