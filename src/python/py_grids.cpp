// Grids in memory (py_grids.h).
#include "python/py_grids.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "tools/dense_vdb.h"

namespace mirage::python {

namespace py = pybind11;

namespace {

std::string typeName(py::handle v) { return py::str(py::type::of(v).attr("__name__")); }

bool isOpenVdbGrid(py::handle v) {
    return std::string(py::str(py::type::of(v).attr("__module__"))) == "pyopenvdb" &&
           py::hasattr(v, "activeVoxelCount");
}

bool inMemory(py::handle v) {
    return py::isinstance<PyGrid>(v) || isOpenVdbGrid(v) || py::isinstance<py::array>(v) ||
           ((py::isinstance<py::dict>(v) || py::isinstance<py::list>(v) ||
             py::isinstance<py::tuple>(v)) &&
            py::len(v) > 0);
}

// A volume's in-memory grids as (name, grid) pairs, each a mirage.Grid or a pyopenvdb grid.
std::vector<std::pair<std::string, py::object>> namedGrids(py::handle file,
                                                           const std::string& key) {
    std::vector<std::pair<std::string, py::object>> out;
    auto refuse = [&](const std::string& where, py::handle v) {
        if (py::isinstance<py::array>(v))
            throw MirageError("scene dict: '" + where +
                              "' is a bare numpy array, which has no voxel size: give "
                              "mirage.Grid(array, voxel_size=…, offset=…)");
        if (py::isinstance<PyGrid>(v))
            throw MirageError("scene dict: '" + where +
                              "' is a mirage.Grid, which has no name: give the volume's file as "
                              "a dict of grid name → mirage.Grid");
        throw MirageError("scene dict: '" + where + "' is a " + typeName(v) +
                          "; a volume's grids in memory are mirage.Grid or pyopenvdb grids");
    };
    if (py::isinstance<py::dict>(file)) {
        for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(file)) {
            const std::string name = py::str(k);
            if (!py::isinstance<PyGrid>(v) && !isOpenVdbGrid(v)) refuse(key + "." + name, v);
            out.emplace_back(name, py::reinterpret_borrow<py::object>(v));
        }
        return out;
    }
    py::list items;
    if (isOpenVdbGrid(file))
        items.append(file);
    else if (py::isinstance<py::list>(file) || py::isinstance<py::tuple>(file))
        for (py::handle v : file) items.append(v);
    else
        refuse(key, file);
    for (size_t i = 0; i < items.size(); ++i) {
        py::handle v = items[i];
        if (!isOpenVdbGrid(v)) refuse(key + "." + std::to_string(i), v);
        const std::string name = py::str(v.attr("name"));
        if (name.empty())
            throw MirageError("scene dict: the pyopenvdb grid at '" + key + "." +
                              std::to_string(i) +
                              "' has no name: set grid.name, or give a dict of name → grid");
        out.emplace_back(name, py::reinterpret_borrow<py::object>(v));
    }
    return out;
}

// mirage.Grid values through the dense writer (the GIL released while OpenVDB works).
void writeDenseGrids(const std::string& path,
                     const std::vector<std::pair<std::string, py::object>>& grids) {
    std::vector<DenseGrid> dense;
    for (const auto& [name, object] : grids) {
        const PyGrid& g = object.cast<const PyGrid&>();
        DenseGrid d;
        d.name = name;
        for (int a = 0; a < 3; ++a) d.dims[size_t(a)] = int64_t(g.values.shape(a));
        d.components = g.values.ndim() == 4 ? 3 : 1;
        d.values = g.values.data();
        d.voxelSize = g.voxelSize;
        d.offset = g.offset;
        d.origin = Vec3d(g.origin[0], g.origin[1], g.origin[2]);
        dense.push_back(d);
    }
    py::gil_scoped_release release;
    writeDenseVdbFile(path, dense);
}

// pyopenvdb grids through pyopenvdb's own writer: sparse as they are, with their transforms.
// Copies (which share the trees) carry the names, so the caller's grids keep theirs.
void writeOpenVdbGrids(const std::string& path,
                       const std::vector<std::pair<std::string, py::object>>& grids) {
    py::list copies;
    for (const auto& [name, grid] : grids) {
        py::object copy = grid.attr("copy")();
        copy.attr("name") = name;
        copies.append(copy);
    }
    py::module_::import("pyopenvdb").attr("write")(path, copies);
}

// Writes a volume's grids; a problem with them is named by the volume's key, not by the file
// the user never named.
void writeGrids(const std::string& path, const std::string& key,
                const std::vector<std::pair<std::string, py::object>>& grids, bool openVdb) {
    try {
        if (openVdb)
            writeOpenVdbGrids(path, grids);
        else
            writeDenseGrids(path, grids);
    } catch (const MirageError& e) {
        std::string message = e.what();
        const std::string file = e.location().str() + ": ";
        if (!e.location().file.empty() && message.compare(0, file.size(), file) == 0)
            message.erase(0, file.size());
        throw MirageError("scene dict: '" + key + "': " + message);
    } catch (const py::error_already_set& e) {
        throw MirageError("scene dict: '" + key +
                          "': pyopenvdb cannot write its grids: " + std::string(e.what()));
    }
}

}  // namespace

PyGrid::PyGrid(const py::array& array, double size, std::array<int32_t, 3> index,
               std::array<double, 3> at)
    : values(py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array)),
      voxelSize(size),
      offset(index),
      origin(at) {
    if (!values) throw MirageError("mirage.Grid: values are not an array of numbers");
    const bool scalar = values.ndim() == 3, vector = values.ndim() == 4 && values.shape(3) == 3;
    if (!scalar && !vector) {
        std::string shape;
        for (py::ssize_t a = 0; a < values.ndim(); ++a)
            shape += (a ? ", " : "") + std::to_string(values.shape(a));
        throw MirageError("mirage.Grid: values of shape (" + shape +
                          "); a grid is [x, y, z] (a scalar) or [x, y, z, 3] (a vector)");
    }
    if (!(voxelSize > 0.0) || !std::isfinite(voxelSize))
        throw MirageError("mirage.Grid: voxel_size " + std::to_string(voxelSize) +
                          " is not a positive finite number of metres");
    for (double o : origin)
        if (!std::isfinite(o)) throw MirageError("mirage.Grid: origin is not finite");
}

MemoryGrids::~MemoryGrids() {
    if (mFolder.empty()) return;
    std::error_code ec;
    std::filesystem::remove_all(mFolder, ec);
}

std::string MemoryGrids::folder() {
    if (mFolder.empty()) {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "mirage-grids-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw MirageError("cannot create a folder for in-memory grids: " + pattern);
        mFolder = pattern;
    }
    return mFolder;
}

py::dict MemoryGrids::resolve(const py::dict& scene) {
    if (!scene.contains("volume") || !py::isinstance<py::list>(scene["volume"])) return scene;
    py::list volumes;
    bool changed = false;
    size_t i = 0;
    for (py::handle v : scene["volume"]) {
        const std::string key = "volume." + std::to_string(i);
        if (!py::isinstance<py::dict>(v) || !py::reinterpret_borrow<py::dict>(v).contains("file") ||
            !inMemory(v["file"])) {
            volumes.append(v);
            ++i;
            continue;
        }
        const auto grids = namedGrids(v["file"], key + ".file");
        size_t openVdb = 0;
        for (const auto& g : grids) openVdb += isOpenVdbGrid(g.second) ? 1 : 0;
        if (openVdb != 0 && openVdb != grids.size())
            throw MirageError("scene dict: '" + key +
                              ".file' mixes mirage.Grid and pyopenvdb grids; give one kind per "
                              "volume (pyopenvdb's grid.copyToArray makes an array of a grid)");
        const std::string path = folder() + "/volume" + std::to_string(i) + ".vdb";
        writeGrids(path, key + ".file", grids, openVdb != 0);
        py::dict copy = v.attr("copy")();
        copy["file"] = path;
        volumes.append(copy);
        changed = true;
        ++i;
    }
    if (!changed) return scene;
    py::dict out = scene.attr("copy")();
    out["volume"] = volumes;
    return out;
}

}  // namespace mirage::python
