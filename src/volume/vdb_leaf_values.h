// The values of a float OpenVDB grid's leaves, decoded straight from the mapped file at the
// offsets the tree walk found (volume/vdb_tree.h, LeafDataIndex), on any thread.
//
// OpenVDB's delayed loading reads a leaf through a new stream over its mapping, a stat() of the
// file (to warn when it changed), a heap buffer for the values and one for the half floats:
// `perf` put a quarter of a 10⁹-voxel load there. This reader does io::readCompressedValues's
// work (OpenVDB 10, io/Compression.h) in place, into the caller's 512 floats: the
// mask-compression flag (0 inactive values are +background, 1 −background, 2 one stored value;
// 3–5 a selection mask between two of them; 6 every value stored), the stored inactive values
// (as floats, also in a half-float grid), the selection mask, then the active (or all) values,
// raw or as a Blosc or zip block, half floats widened exactly. The walk has already checked
// every count and block size, so only a block's compressed bytes can still be wrong here.
//
// No OpenVDB headers: the file is mapped here (mmap), Blosc and zlib decompress.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "volume/vdb_tree.h"

namespace mirage {

class LeafValueReader {
public:
    // Maps file `path`; throws MirageError naming it when it cannot.
    LeafValueReader(const std::string& path, vdbformat::LeafDataIndex index);
    ~LeafValueReader();
    LeafValueReader(const LeafValueReader&) = delete;
    LeafValueReader& operator=(const LeafValueReader&) = delete;

    size_t leafCount() const { return mIndex.offsets.size(); }

    // Leaf i's 512 values, in OpenVDB's order (x major, z minor), into `out`, given its value
    // mask from the topology (8 words). False, with *error saying why, when its data do not
    // repeat that mask or a block does not decompress to its size.
    bool read(size_t i, const uint64_t* mask, float* out, std::string* error) const;

private:
    vdbformat::LeafDataIndex mIndex;
    const uint8_t* mData = nullptr;
    size_t mSize = 0;
};

}  // namespace mirage
