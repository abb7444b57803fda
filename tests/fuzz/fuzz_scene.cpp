// libFuzzer target: arbitrary bytes as a scene file (TOML parsing, key and type checks, shader
// binding, grid loading; no rendering). Built by -DMIRAGE_FUZZ=ON with clang; run by
// pipeline/fuzz.sh. A MirageError is the expected answer to bad input; anything else escaping
// reaches libFuzzer's handler and is reported as a crash.
#include <cstddef>
#include <cstdint>

#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    mirage::fuzz::runSceneInput(data, size);
    return 0;
}
