// A frame's photon maps saved to a file (`mirage photons`), so that every region of the frame
// rendered on a farm reads the same photons instead of tracing its own: the pass is paid once
// per frame, and tiles agree at their seams because their estimates query one map.
//
// Layout (little-endian; format version 1):
//   magic "MIRAGEPH" (8 bytes) · u32 format version · u32 frame · 16 bytes fingerprint (the
//   hex FNV-1a of the scene and the settings that decide the pass, app/render_checkpoint.h) ·
//   u64 counts of volume, global-surface and caustic-surface photons · the pass's figures
//   (u64 emitted, stored, capped paths, non-finite, from media; f64 medium power, emitted
//   power, seconds) · the photons, each 10 × f32 (position, direction, λ, power, λin, time),
//   volume then global then caustic · u64 FNV-1a of every byte before it.
// The counts give the exact file size, so a truncated file is refused before anything is read;
// the checksum refuses a corrupt one; the fingerprint one made from another scene or settings.
#pragma once

#include <cstdint>
#include <string>

#include "photon/photon_pass.h"

namespace mirage {

// 2: every photon carries the light it left (Photon::light).
constexpr uint32_t kPhotonFileVersion = 2;

struct PhotonFileHeader {
    uint32_t version = kPhotonFileVersion;
    uint32_t frame = 0;
    std::string fingerprint;  // 16 hex digits
    uint64_t volume = 0, global = 0, caustic = 0;
};

// Writes atomically (core/atomic_file.h); throws MirageError naming `path`.
void writePhotonFile(const std::string& path, const PhotonFileHeader& header,
                     const PhotonPassResult& pass);

// Reads the file whole and checks magic, version, size and checksum; throws MirageError
// naming `path` and what is wrong. The caller compares the fingerprint and frame.
PhotonPassResult readPhotonFile(const std::string& path, PhotonFileHeader* header);

// The header alone, or false when `path` is missing or not an intact photon file (its size and
// checksum are checked): what --skip-existing trusts.
bool readPhotonFileHeader(const std::string& path, PhotonFileHeader* header);

}  // namespace mirage
