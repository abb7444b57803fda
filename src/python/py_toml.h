// Python values as the scene file's TOML: a dict is a scene file's document (Scene.from_dict)
// and `set={"key.path": value}` the command line's --set key.path=value. Both then go through
// the one loader (scene/scene_loader.cpp), so a dict takes exactly the file's keys and gets its
// errors.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace mirage::python {

// The TOML text of `scene`: dicts are tables, lists of dicts arrays of tables, lists arrays;
// bool, int, float and str values (numpy scalars as their Python values). Throws MirageError
// naming the key of a value TOML cannot hold (None, an object).
std::string sceneToml(const pybind11::dict& scene);

// `set` as --set assignments, "key.path=value", each value in TOML (a str quoted, so that
// "1" stays a string). Throws MirageError naming the key of a value that is not a bool, int,
// float, str or list of them.
std::vector<std::string> overrideAssignments(const pybind11::dict& set);

}  // namespace mirage::python
