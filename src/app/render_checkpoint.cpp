#include "app/render_checkpoint.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"
#include "core/text.h"
#include "scene/scene.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

// FNV-1a, 64-bit (Fowler, Noll, Vo): enough to tell scenes apart, not a security hash.
struct Fnv1a {
    uint64_t h = 0xcbf29ce484222325ull;
    void add(const std::string& s) {
        for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
        h = (h ^ 0xff) * 0x100000001b3ull;  // separator: "ab"+"c" differs from "a"+"bc"
    }
};

std::string fileStamp(const std::string& path) {
    std::error_code ec;
    auto size = fs::file_size(path, ec);
    if (ec) return path + ": missing";
    auto time = fs::last_write_time(path, ec).time_since_epoch().count();
    return path + ": " + std::to_string(size) + " bytes, mtime " + std::to_string(time);
}

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

FrameFingerprint frameFingerprint(const Scene& scene, const std::string& input,
                                  const std::string& integrator, int frame,
                                  const std::vector<std::string>& overrides) {
    const RenderSettings& s = scene.settings;
    const CameraDesc& c = scene.render.camera;
    std::map<std::string, std::string> m;
    auto vec = [](const Vec3& v) {
        char b[96];
        std::snprintf(b, sizeof b, "%.9g,%.9g,%.9g", v.x, v.y, v.z);
        return std::string(b);
    };
    m["camera"] =
        vec(c.position) + ";" + vec(c.lookAt) + ";" + vec(c.up) + ";" + std::to_string(c.fovDeg);
    m["frame"] = std::to_string(frame);
    m["integrator"] = integrator;
    m["max_depth"] = std::to_string(scene.maxDepth);
    m["photons"] = std::to_string(scene.photon.photons);
    m["estimate"] = scene.photon.estimate == PhotonEstimate::Beam ? "beam" : "point";
    m["k"] = std::to_string(scene.photon.k);
    m["max_radius"] = std::to_string(scene.photon.maxRadius);
    m["resolution"] = std::to_string(s.width) + "x" + std::to_string(s.height);
    m["seed"] = std::to_string(s.seed);
    m["spp"] = std::to_string(s.spp);
    m["tile_size"] = std::to_string(s.tileSize);
    m["version"] = MIRAGE_VERSION;
    if (!s.aovs.empty()) m["aovs"] = joinList(s.aovs);
    std::string sets;
    for (const auto& o : overrides) sets += (sets.empty() ? "" : " ") + o;
    m["set"] = sets;

    FrameFingerprint fp;
    for (const auto& [k, v] : m) fp.settings += k + "=" + v + "\n";
    Fnv1a h;
    h.add(fp.settings);
    // The scene's own text (a bare VDB: its size and time), then every grid file it read.
    if (isVolumeFile(input)) {
        h.add(fileStamp(input));
    } else {
        std::ifstream f(input, std::ios::binary);
        h.add(std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()));
    }
    for (const VolumeRecord& v : scene.volumes) h.add(fileStamp(v.file));
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h.h);
    fp.hash = hex;
    return fp;
}

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

bool isCompleteFrame(const std::string& exrPath) {
    std::error_code ec;
    if (!fs::is_regular_file(exrPath, ec)) return false;
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(exrPath);
    if (!in) {
        OIIO::geterror();  // clear OIIO's pending error: an unreadable file is just not complete
        return false;
    }
    const OIIO::ParamValue* p = in->spec().find_attribute("mirage:complete");
    bool complete = p && p->get_string() == "true";
    in->close();
    return complete;
}

int64_t testStopAfterTiles() {
    const char* v = std::getenv("MIRAGE_TEST_STOP_AFTER_TILES");
    return v && *v ? std::atoll(v) : -1;
}

double partialWriteInterval() {
    const char* v = std::getenv("MIRAGE_PARTIAL_INTERVAL");
    return v && *v ? std::atof(v) : 2.0;
}

}  // namespace mirage
