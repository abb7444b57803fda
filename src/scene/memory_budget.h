// `--max-memory SIZE`: an estimate of what a frame will need, checked before the heavy work
// (photon pass, render), so a scene that will not fit fails at once with the estimate and what
// dominates it, instead of being killed by the system halfway through.
//
// It is checked twice. Before each grid is read, with the grid's size from the file's metadata
// (a grid that cannot fit is refused before it is loaded). Then once the grids are loaded (they
// are what the process holds so far, read from the resident set), adding what is still to come: the
// photon maps (photon integrator: stored photons per emitted photon from a pilot pass of a few
// thousand photons, times the bytes per stored photon measured on the whole photon pipeline), and
// the film and its copies.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "volume/grid_precision.h"

namespace mirage {

struct GridInfo;
class AovLayout;
struct Scene;

// "4G", "512M", "1.5G", "64k", "2T" (binary multiples: k = 1024) or plain bytes. Throws
// MirageError naming `what` (e.g. "--max-memory") for anything else or a size of 0.
uint64_t parseMemorySize(const std::string& text, const std::string& what = "--max-memory");

struct MemoryItem {
    std::string what;
    uint64_t bytes = 0;
};

struct MemoryEstimate {
    std::vector<MemoryItem> items;
    uint64_t total() const;
    // "1.2 GiB: photon maps 1.1 GiB (…), grids 50 MiB, …", largest first.
    std::string describe() const;
};

// Bytes per stored volume photon over the whole photon pipeline (pass with its per-block lists,
// kd-tree, per-photon XYZ/phase/radius, beam disc BVH), measured as peak resident memory
// against photon count (docs/hostile-input.md, "Killed renders, sequences and memory").
constexpr uint64_t kBytesPerStoredPhoton = 112;
// Per pixel: the film's sums (Film::Pixel, 40 B), the developed image (16 B), the output copy
// (16 B), the partial file's staging record (56 B) and a resumed film's copy (40 B).
constexpr uint64_t kBytesPerPixel = 168;
// Render passes (docs/aovs.md), per pixel: per double of the passes' sums (AovLayout::stride)
// the film's sum, its staging record in the partial file (two floats) and a resumed film's
// copy; per channel of a developed pass (a Cryptomatte's rank tables: 12) the float layer and
// its output copy.
constexpr uint64_t kBytesPerPassSum = 24;
constexpr uint64_t kBytesPerPassChannel = 8;
// Deep output, per pixel: the deep film's list (24 B) and its samples (film/deep.h DeepPoint,
// 24 B each), whose number only the render knows: planned at 32 (a dense smoke gives tens).
constexpr uint64_t kDeepSamplesPlanned = 32;
constexpr uint64_t kDeepBytesPerPixel = 24 + kDeepSamplesPlanned * 24;
// The bytes per pixel of the passes `layout` holds.
uint64_t passBytesPerPixel(const AovLayout& layout);

// The scalar grids a loaded scene holds: their NanoVDB buffers and dense copies, bytes (a grid
// shared by two media counted once), and how many.
struct LoadedGrids {
    uint64_t bytes = 0;
    size_t count = 0;
};
LoadedGrids loadedGrids(const Scene& scene);

// Estimates the memory of rendering `scene` with `integrator` (its grids already loaded).
// Runs a pilot photon pass for the photon integrator (a few thousand photons, well under 1 s).
MemoryEstimate estimateFrameMemory(const Scene& scene, const std::string& integrator);

// A grid's in-core bytes at `precision` from its file's metadata, before it is read: as float,
// the larger of the size OpenVDB recorded and 4 bytes per active voxel; at a quantised
// precision, that less what the leaves its active voxels need at the least (one 8³ leaf per 512)
// save (volume/grid_precision.h). An upper bound for sparse leaves, which save more.
uint64_t gridBytesBeforeLoad(const GridInfo& grid, GridPrecision precision);

// Before a grid is read (LoadOptions::beforeGridLoad): what is resident now, the grid's in-core
// size at its precision from its file's metadata, and a width × height film. The photon maps
// are not known yet.
MemoryEstimate estimateBeforeGrid(const std::string& file, const std::string& grid,
                                  GridPrecision precision, uint64_t gridBytes, int width,
                                  int height);

// Throws MirageError when estimate.total() > budget, with the estimate and what dominates it:
// "<where>: <what> an estimated <total> = <items>, more than --max-memory <budget>; …".
void checkMemoryBudget(const MemoryEstimate& estimate, uint64_t budget, const std::string& where,
                       const std::string& what = "the frame needs");

// Resident memory of this process now, bytes (Linux /proc/self/statm; 0 if unavailable).
uint64_t currentMemoryBytes();

// Memory the system can give without swapping, bytes (Linux /proc/meminfo's MemAvailable; 0 if
// unavailable).
uint64_t availableMemoryBytes();

}  // namespace mirage
