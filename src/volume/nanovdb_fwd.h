// The NanoVDB names the grid handles mention (volume/grid.h, volume/vector_grid.h,
// volume/index_map.h), declared without NanoVDB's headers; volume/grid_lookup.h completes them.
#pragma once

namespace nanovdb {
struct Map;
class HostBuffer;
template <typename BufferT>
class GridHandle;
}  // namespace nanovdb
