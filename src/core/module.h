// Mirage's modules: shared objects built beside the command (libmirage_<name>.so, from
// src/modules/) that hold a library too heavy to load at every start, opened the first time a
// scene needs them (volume/ax_module.h says why for OpenVDB AX).
#pragma once

#include <string>

namespace mirage {

// The address of `entry` in the module file `file`, loaded once per process: looked for in the
// folder of the object that holds this code (the command, a test, the Python package) and then
// in the running program's. Throws MirageError naming the folders tried and the loader's
// message, `purpose` saying what needed it ("grid expressions").
void* moduleEntry(const std::string& file, const char* entry, const std::string& purpose);

}  // namespace mirage
