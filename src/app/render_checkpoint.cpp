#include "app/render_checkpoint.h"

#include <cstdlib>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace mirage {

namespace {

std::map<std::string, std::string> parseLines(const std::string& text) {
    std::map<std::string, std::string> m;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        size_t eq = line.find('=');
        if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return m;
}

}  // namespace

PartialFilm loadPartialForResume(const std::string& partialPath, const FrameFingerprint& expected,
                                 int width, int height, int tileSize) {
    PartialFilm p = readPartialFilm(partialPath);
    const std::string refuse = "--resume refused: this partial file was written by a different ";
    if (p.metadata["fingerprint"] != expected.hash) {
        auto was = parseLines(p.metadata["settings"]), now = parseLines(expected.settings);
        std::vector<std::string> changes;
        for (const auto& [k, v] : now) {
            auto it = was.find(k);
            std::string old = it == was.end() ? "(absent)" : it->second;
            if (old != v) changes.push_back(k + " was '" + old + "', now '" + v + "'");
        }
        const std::string diff = joinList(changes);
        if (!diff.empty())
            throw MirageError(FileLoc{partialPath, 0, 0}, refuse + "render: " + diff +
                                                              ". Render without --resume to start "
                                                              "afresh, or restore the settings.");
        throw MirageError(FileLoc{partialPath, 0, 0},
                          refuse +
                              "scene: the scene file or one of its grid files changed since "
                              "(fingerprint " +
                              p.metadata["fingerprint"] + ", now " + expected.hash +
                              "). Render without --resume to start afresh.");
    }
    if (p.film->width() != width || p.film->height() != height || p.tileSize != tileSize)
        throw MirageError(FileLoc{partialPath, 0, 0},
                          refuse + "frame size or tile size (" + std::to_string(p.film->width()) +
                              "x" + std::to_string(p.film->height()) + ", tiles of " +
                              std::to_string(p.tileSize) + ")");
    return p;
}

int64_t testStopAfterTiles() {
    const char* v = std::getenv("MIRAGE_TEST_STOP_AFTER_TILES");
    return v && *v ? std::atoll(v) : -1;
}

int64_t testStopAfterPasses() {
    const char* v = std::getenv("MIRAGE_TEST_STOP_AFTER_PASSES");
    return v && *v ? std::atoll(v) : -1;
}

double partialWriteInterval() {
    const char* v = std::getenv("MIRAGE_PARTIAL_INTERVAL");
    return v && *v ? std::atof(v) : 2.0;
}

}  // namespace mirage
