// The entry points that the libFuzzer targets (fuzz_scene.cpp, fuzz_vdb.cpp, fuzz_lights.cpp,
// clang only) and
// the corpus replay test (tests/unit/fuzz_corpus_test.cpp, every build) share, so a crash the
// fuzzer found stays caught by ctest once its input joins tests/fuzz/corpus/.
//
// Contract under test (docs/design.md, "Conventions"): arbitrary bytes given as a scene file, a
// VDB file or a light's file (IES profile, RGBE sky map) either load or raise MirageError; anything else escaping (another exception type, a
// crash, undefined behaviour under the sanitizers) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace mirage::fuzz {

// Writes `data` as scene.toml into a private temporary folder that also holds tiny generated
// VDB caches under the names the shipped scenes use, then runs loadScene on it: TOML parsing,
// overrides-free key checking, shader binding and grid loading, but no rendering.
// Returns true if the scene loaded, false if it was rejected with a MirageError.
bool runSceneInput(const uint8_t* data, size_t size);

// Writes `data` as a .vdb file and runs the VDB path Mirage uses on user files:
// validateVdbFile (header and offset scan), inspectVdbFile, and loadFloatGrid on each listed
// grid (at most a few). Returns true if at least one grid loaded.
bool runVdbInput(const uint8_t* data, size_t size);

// Runs `data` through the light files Mirage parses itself: as the text of an IES LM-63
// profile (IesProfile::parse) and as a Radiance RGBE sky map (readRadianceHdr). Returns true if
// either read it.
bool runLightFileInput(const uint8_t* data, size_t size);

// The private folder the entry points write to (created on first use, removed at exit).
const std::string& scratchFolder();

}  // namespace mirage::fuzz
