// The tree of an OpenVDB grid, walked byte by byte before OpenVDB reads it.
//
// OpenVDB's reader trusts every count and size in a file: a corrupt root tile count makes
// RootNode::readTopology loop over a failed stream for tens of seconds, a corrupt compressed
// block size makes io::bloscFromStream / unzipFromStream allocate terabytes, and a raw block
// larger than its node is read into the node's buffer. This walk follows the same layout
// (file version 222 on; tree/RootNode.h, InternalNode.h, LeafNode*.h, io/Compression.h of
// OpenVDB 10) and checks, against the grid's byte extent from the file's index:
//   topology  int32 buffer count; root: background value, uint32 tile and child counts, tiles
//             (int32×3 origin, value, bool active), children (int32×3 origin, then the node);
//             internal nodes (5 and 4 levels of 32³ and 16³): child mask, value mask, the
//             node's values compressed as below, then its children in mask order; leaves
//             (8³): their value mask (a mask grid's leaves: their value bits).
//   buffers   per leaf in the same depth-first order: value mask, then 512 values compressed
//             as below (bool leaves: mask, origin, value bits; mask leaves: bits, origin).
//   values    int8 mask-compression flag, 0–2 inactive values, an optional selection mask,
//             then the active (or all) values: raw, or a zip / Blosc block (int64 size, raw
//             when negative) whose size must fit in the grid and, for Blosc, match its header.
// The walk also requires what every OpenVDB writer produces and the reader silently assumes:
// root children in ascending origin order (the reader keeps them in a std::map and reads their
// buffers in map order), the topology ending where the file's index says the data starts, the
// data ending where the grid ends, and a leaf's mask the same in topology and data.
//
// This file does not include OpenVDB headers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "volume/vdb_format.h"

namespace mirage::vdbformat {

// True when Mirage can walk this grid's tree: an OpenVDB grid of file version 222 or later
// whose tree is one of the standard 5-4-3 trees of float, double, int32, int64, vec3s, vec3d,
// vec3i, bool or mask values (an instance: that of its parent). Point grids are not.
bool treeIsWalkable(const FileLayout& layout, int index);

// Where a float tree's leaves keep their values in the file, found by the walk below, for
// volume/vdb_leaf_values.h to decode them without OpenVDB's delayed loading.
struct LeafDataIndex {
    std::vector<uint64_t> offsets;  // each leaf's data (its mask first), depth-first order
    float background = 0.f;         // the root's: what mask compression leaves out
    bool savedAsHalf = false;
    uint32_t compression = 0;  // the grid's OpenVDB flags (vdb_format.h)
};

// Walks the tree of OpenVDB grid `index` (that of its instance parent for an instance) and
// throws MirageError naming the file, the grid and the first byte that does not fit. Call it
// before OpenVDB reads the grid's topology or data. With `leaves`, a float tree's leaf data are
// indexed there (other trees leave it empty).
void checkOpenVdbTree(const std::string& path, const FileLayout& layout, int index,
                      LeafDataIndex* leaves = nullptr);

// The nodes of a grid's tree, from its topology: what its NanoVDB copy's size follows from.
struct TreeCounts {
    uint64_t rootEntries = 0;  // the root's tiles and children
    uint64_t upper = 0, lower = 0, leaves = 0;
};

// The node counts of OpenVDB grid `index`, walking its topology alone (checked as
// checkOpenVdbTree checks it; the leaves' values are not read): milliseconds where reading the
// grid takes minutes. Throws MirageError where checkOpenVdbTree would, or when the tree cannot
// be walked (treeIsWalkable false).
TreeCounts countOpenVdbTree(const std::string& path, const FileLayout& layout, int index);

}  // namespace mirage::vdbformat
