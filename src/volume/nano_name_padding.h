// NanoVDB's converter (openToNanoVDB, NanoVDB 32.4) keeps a grid name too long for the grid's
// header as blind data at the end of the buffer, one element of the whole string padded to
// NANOVDB_DATA_ALIGNMENT, and leaves two things as the allocator left them: that padding, and
// the 256-byte name field of the blind data's own record, which it never writes. The same file
// converted twice differed in those bytes (ParallelLoad.AGridOfALongNameIsReadWholeByOpenVdb
// compared the two byte for byte and failed about one run in eight). zeroNamePadding writes
// zeros there, so a converted grid is the same bytes every time.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>

#include <cstring>

namespace mirage {

template <typename BufferT>
void zeroNamePadding(nanovdb::GridHandle<BufferT>& handle) {
    auto* grid = reinterpret_cast<nanovdb::GridData*>(handle.data());
    if (!grid) return;
    const uint8_t* end = handle.data() + handle.size();
    for (uint32_t i = 0; i < grid->mBlindMetadataCount; ++i) {
        const nanovdb::GridBlindMetaData* meta = grid->blindMetaData(i);
        if (meta->mDataClass != nanovdb::GridBlindDataClass::GridName) continue;
        auto* record = const_cast<nanovdb::GridBlindMetaData*>(meta);
        std::memset(record->mName, 0, sizeof record->mName);
        // One element, the whole string with its NUL (its byte count is not recorded).
        auto* name = const_cast<uint8_t*>(meta->template getBlindData<uint8_t>());
        if (!(name < end)) continue;
        const size_t bytes =
            strnlen(reinterpret_cast<const char*>(name), size_t(end - name) - 1) + 1;
        uint8_t* used = name + bytes;
        const uint8_t* padded = name + nanovdb::AlignUp<NANOVDB_DATA_ALIGNMENT>(bytes);
        if (padded > end) padded = end;
        if (used < padded) std::memset(used, 0, size_t(padded - used));
    }
}

}  // namespace mirage
