// How a grid of a VDB file is named to the user and in scenes: by its own name, or, when it
// has none, by "#N", its index in the file (0-based). Scene files may write either.
#pragma once

#include <cstddef>
#include <string>

namespace mirage {

// "#3" for the grid at index 3.
inline std::string gridIndexName(size_t index) { return "#" + std::to_string(index); }

// `name`, or gridIndexName(index) when `name` is empty.
inline std::string gridName(const std::string& name, size_t index) {
    return name.empty() ? gridIndexName(index) : name;
}

// For messages: 'name' in quotes, or the bare "#N" of an unnamed grid.
inline std::string quotedGridName(const std::string& name, size_t index) {
    return name.empty() ? gridIndexName(index) : "'" + name + "'";
}

}  // namespace mirage
