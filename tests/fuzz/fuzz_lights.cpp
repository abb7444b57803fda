// libFuzzer target: arbitrary bytes through the light files Mirage parses itself, an IES LM-63
// profile's text and a Radiance RGBE sky map (light/ies_file.h, light/radiance_hdr.h). Built by
// -DMIRAGE_FUZZ=ON with clang; run by pipeline/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    mirage::fuzz::runLightFileInput(data, size);
    return 0;
}
