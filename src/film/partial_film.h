// The partial file of a frame being rendered: `<out>.partial`, a tiled OpenEXR (one EXR tile per
// render tile) holding the finished tiles of a killed or running render, so that `--resume`
// continues it exactly.
//
// Channels: R, G, B, A (float) are the finished tiles developed to the working space, for a
// look at how far a render got (unfinished tiles are transparent black); the `acc.*` channels
// (32-bit unsigned) are the film's running sums bit for bit — each double split into its high
// and low words (acc.Xhi, acc.Xlo, … for X, Y, Z, alpha and the squared sums acc.XXhi … of the
// variance estimate, film/film_error.h), the valid sample count acc.N and
// the dropped non-finite count acc.bad — because a developed half or float pixel cannot be
// summed on from. Metadata: mirage:partial = "true", mirage:tile_size, mirage:tiles_done (one
// hex digit per 4 tiles, bit t%4 of digit t/4) and whatever the caller adds (the scene
// fingerprint the resume check compares; a render in passes, the passes done and their time).
//
// The file is written to a temporary name and renamed, like every output: a render killed
// while writing it keeps the previous partial file.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/matrix.h"
#include "film/film.h"

namespace mirage {

constexpr const char* kPartialCompression = "none";

struct PartialFilm {
    std::unique_ptr<Film> film;
    int tileSize = 0;
    std::vector<uint8_t> done;                    // per tile, row-major: 1 = finished
    std::map<std::string, std::string> metadata;  // "mirage:" keys without the prefix
};

// `<out>.partial` for an output path.
std::string partialPathFor(const std::string& outputPath);

// Writes the finished tiles of `film` (only those: other tiles may be in progress). `toWorking`
// converts XYZ to the working space for the preview channels. Throws MirageError naming `path`.
// `compression` is an OpenEXR compression name (tests/bench/bench_partial_write measures them).
void writePartialFilm(const std::string& path, const Film& film, int tileSize,
                      const std::vector<uint8_t>& done, const Mat3& toWorking,
                      const std::map<std::string, std::string>& metadata,
                      const std::string& compression = kPartialCompression);
// Reads a partial file back; throws MirageError naming `path` when it is not one.
PartialFilm readPartialFilm(const std::string& path);

// Decides when to write: after a tile finishes, a write happens only when at least
// max(minSeconds, costFactor × the last write's duration) have passed since the last one, so
// that checkpointing costs at most about 1/costFactor of the render time.
class PartialFilmWriter {
public:
    PartialFilmWriter(std::string path, int tileSize, const Mat3& toWorking,
                      std::map<std::string, std::string> metadata, double minSeconds = 2.0,
                      double costFactor = 30.0);
    // After a tile: writes if due.
    void tileFinished(const Film& film, const std::vector<uint8_t>& done);
    // Writes now (an interrupted render flushes what it finished).
    void write(const Film& film, const std::vector<uint8_t>& done);
    // Sets a metadata key ("mirage:" added) for the writes that follow.
    void setMetadata(const std::string& key, const std::string& value) { mMetadata[key] = value; }

    int writes() const { return mWrites; }
    double writeSeconds() const { return mWriteSeconds; }  // total time spent writing
    const std::string& path() const { return mPath; }

private:
    std::string mPath;
    int mTileSize;
    Mat3 mToWorking;
    std::map<std::string, std::string> mMetadata;
    double mMinSeconds, mCostFactor;
    double mLastWrite = 0;  // seconds since construction, at the end of the last write
    double mLastCost = 0;   // duration of the last write
    int mWrites = 0;
    double mWriteSeconds = 0;
    double mStart;
};

}  // namespace mirage
