// The Python module `mirage` (its compiled part, mirage._mirage; python/mirage/__init__.py
// re-exports it): scenes loaded from files or dicts, their `mirage info` record, finished
// renders and progressive sessions, errors as mirage.Error with the command's messages
// (docs/python.md).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/error.h"
#include "film/image_io.h"
#include "python/py_grids.h"
#include "python/py_render.h"
#include "python/py_scene.h"
#include "python/py_session.h"

namespace py = pybind11;
using namespace mirage;
using namespace mirage::python;

namespace {

void bindGrid(py::module_& m) {
    py::class_<PyGrid>(m, "Grid")
        .def(py::init<const py::array&, double, std::array<int32_t, 3>, std::array<double, 3>>(),
             py::arg("values"), py::arg("voxel_size"),
             py::arg("offset") = std::array<int32_t, 3>{0, 0, 0},
             py::arg("origin") = std::array<double, 3>{0.0, 0.0, 0.0},
             "A grid in memory: values[x][y][z] (or [x][y][z][3], a vector), values[0][0][0] at "
             "index `offset`, world position origin + voxel_size * index (metres)")
        .def_readonly("values", &PyGrid::values)
        .def_readonly("voxel_size", &PyGrid::voxelSize)
        .def_readonly("offset", &PyGrid::offset)
        .def_readonly("origin", &PyGrid::origin)
        .def("__repr__", [](const PyGrid& g) {
            std::string shape;
            for (py::ssize_t a = 0; a < g.values.ndim(); ++a)
                shape += (a ? "x" : "") + std::to_string(g.values.shape(a));
            return "<mirage.Grid " + shape + " voxel_size " + std::to_string(g.voxelSize) + ">";
        });
}

void bindScene(py::module_& m) {
    py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene")
        .def_static("from_dict", &PyScene::fromDict, py::arg("scene"), py::arg("set") = py::dict(),
                    py::arg("frame") = 1, py::arg("base_dir") = "", py::arg("ocio") = "",
                    "A scene from a dict of the scene file's keys (the same loader and errors)")
        .def("info", &PyScene::info, "The record `mirage info` prints, as a dict")
        .def_property_readonly("source", [](const PyScene& s) { return s.request().input; })
        .def_property_readonly("overrides", [](const PyScene& s) { return s.request().overrides; })
        .def_property_readonly("frame", [](const PyScene& s) { return s.request().frame; })
        .def_property_readonly(
            "grid_reads", [](PyScene& s) { return s.grids().reads(); },
            "Grid files read so far (a load served by the cache reads none)")
        .def("__repr__",
             [](const PyScene& s) { return "<mirage.Scene " + s.request().input + ">"; });
    m.def("load", &PyScene::load, py::arg("path"), py::arg("set") = py::dict(),
          py::arg("frame") = 1, py::arg("ocio") = "",
          "Loads a scene .toml (or a bare .vdb/.nvdb) with --set keys, as `mirage render` does");
}

void bindImage(py::module_& m) {
    py::class_<PyImage, std::shared_ptr<PyImage>>(m, "Image")
        .def_property_readonly("beauty", &PyImage::beauty)
        .def_property_readonly("aovs", &PyImage::aovs)
        .def_property_readonly("channels", &PyImage::channels)
        .def_property_readonly("metadata", &PyImage::metadata)
        .def_property_readonly("final", &PyImage::final)
        .def_property_readonly("generation", &PyImage::generation)
        .def_property_readonly("width", &PyImage::width)
        .def_property_readonly("height", &PyImage::height)
        .def("write", &PyImage::write, py::arg("path"),
             "Writes the EXR `mirage render` writes (a finished frame only)")
        .def("__repr__", [](const PyImage& i) {
            return "<mirage.Image " + std::to_string(i.width()) + "x" + std::to_string(i.height()) +
                   (i.final() ? "" : " (a pass)") + ">";
        });
    m.def(
        "read",
        [](const std::string& path) {
            std::map<std::string, std::string> metadata;
            Image image;
            {
                py::gil_scoped_release release;
                image = readExr(path, &metadata);
            }
            return std::make_shared<PyImage>(std::move(image), std::move(metadata), 0);
        },
        py::arg("path"), "Reads an EXR (its beauty, passes and header) as an Image");
    m.def("render", &mirage::python::render, py::arg("scene"),
          "Renders the scene; keyword arguments as `mirage render`'s options");
}

void bindSession(py::module_& m) {
    py::class_<PySession, std::shared_ptr<PySession>>(m, "Session")
        .def(py::init<std::shared_ptr<PyScene>, py::kwargs>(), py::arg("scene"))
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", &PySession::next)
        .def("__enter__", [](py::object self) { return self; })
        .def("__exit__",
             [](PySession& s, py::args) {
                 s.cancel();
                 return false;
             })
        .def("cancel", &PySession::cancel)
        .def("update", &PySession::update, py::arg("set"))
        .def_property_readonly("result", &PySession::result)
        .def_property_readonly("done", &PySession::done)
        .def_property_readonly("generation", &PySession::generation);
}

}  // namespace

PYBIND11_MODULE(_mirage, m) {
    m.doc() = "Mirage, a spectral volume renderer: scenes, renders and progressive sessions";
    m.attr("__version__") = MIRAGE_VERSION;
    py::register_exception<MirageError>(m, "Error");
    bindGrid(m);
    bindScene(m);
    bindImage(m);
    bindSession(m);
}
