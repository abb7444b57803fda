// Grids in memory as a scene's volume: mirage.Grid (a numpy array with a voxel size, an index
// offset and an origin, as a Houdini or Blender session holds a volume) and pyopenvdb grids, given
// in a scene dict where a [[volume]] names its `file`. They are written into a folder of the
// scene's own (removed with the scene) and the volume reads that file, so in-memory grids go
// through the one loader: the same bindings, expressions, velocity and messages as a cache on
// disk (docs/python.md, "Grids in memory").
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <string>

namespace mirage::python {

// mirage.Grid(values, voxel_size, offset=(0, 0, 0), origin=(0, 0, 0)): values[x][y][z] (or
// [x][y][z][3], a vector grid such as a velocity in m/s) as float32 in C order, values[0][0][0]
// at index `offset`, a voxel's world position origin + voxel_size · index (metres).
struct PyGrid {
    PyGrid(const pybind11::array& values, double voxelSize, std::array<int32_t, 3> offset,
           std::array<double, 3> origin);
    pybind11::array_t<float, pybind11::array::c_style | pybind11::array::forcecast> values;
    double voxelSize;
    std::array<int32_t, 3> offset;
    std::array<double, 3> origin;
};

// The files a scene's in-memory grids were written to: a private folder, created at the first
// grid and removed with this object.
class MemoryGrids {
public:
    MemoryGrids() = default;
    MemoryGrids(const MemoryGrids&) = delete;
    MemoryGrids& operator=(const MemoryGrids&) = delete;
    ~MemoryGrids();

    // `scene` with each volume whose `file` is in memory — a dict of grid name → mirage.Grid or
    // pyopenvdb grid, or one pyopenvdb grid or a list of them (named by their own names) —
    // pointing at the file written for it instead (volume<i>.vdb). Other values pass untouched
    // (the loader judges them); `scene` itself is not modified. Throws MirageError naming the
    // volume's key for anything else in memory.
    pybind11::dict resolve(const pybind11::dict& scene);

    bool empty() const { return mFolder.empty(); }

private:
    std::string folder();  // created on first use
    std::string mFolder;
};

}  // namespace mirage::python
