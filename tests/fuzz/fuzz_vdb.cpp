// libFuzzer target: arbitrary bytes as a .vdb/.nvdb file through Mirage's VDB path (header and
// offset scan, grid listing, grid loading with conversion to NanoVDB). Built by -DMIRAGE_FUZZ=ON
// with clang; run by pipeline/fuzz.sh with a memory limit, because OpenVDB allocates what a
// corrupt compressed block claims (see docs/hostile-input.md, "Hostile input and sanitizers").
#include <cstddef>
#include <cstdint>

#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    mirage::fuzz::runVdbInput(data, size);
    return 0;
}
