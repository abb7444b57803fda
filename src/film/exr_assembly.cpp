#include "film/exr_assembly.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "core/error.h"
#include "film/oiio_file.h"

namespace mirage {

namespace {

// The mirage:* keys that say which frame a region belongs to: regions that disagree on any of
// them are not parts of one frame.
const char* const kIdentityKeys[] = {"mirage:fingerprint", "mirage:scene",     "mirage:frame",
                                     "mirage:seed",        "mirage:spp",       "mirage:integrator",
                                     "mirage:version",     "mirage:colorSpace"};
// Keys that describe one region's run, not the frame: dropped or recomputed in the frame.
const char* const kPerRegionKeys[] = {"mirage:region", "mirage:resumed_tiles"};

struct Tile {
    std::string path;
    std::vector<OIIO::ImageSpec> specs;  // one per subimage
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // data window of subimage 0
};

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw MirageError(FileLoc{path, 0, 0}, message);
}

std::string attribute(const OIIO::ImageSpec& spec, const char* key) {
    const OIIO::ParamValue* p = spec.find_attribute(key);
    return p ? p->get_string() : std::string();
}

std::string rect(int x0, int y0, int x1, int y1) {
    return std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," +
           std::to_string(y1);
}

Tile openTile(const std::string& path) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) fail(path, "cannot read the region: " + OIIO::geterror());
    Tile t;
    t.path = path;
    for (int s = 0; in->seek_subimage(s, 0); ++s) {
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.deep) fail(path, "a deep image: mirage assemble joins flat regions only");
        t.specs.push_back(spec);
    }
    // Seeking past the last subimage leaves an error behind: clear it, it is how the loop ends.
    (void)in->geterror();
    (void)OIIO::geterror();
    in->close();
    const OIIO::ImageSpec& s0 = t.specs.at(0);
    t.x0 = s0.x;
    t.y0 = s0.y;
    t.x1 = s0.x + s0.width;
    t.y1 = s0.y + s0.height;
    if (attribute(s0, "mirage:complete") != "true")
        fail(path,
             "not a complete Mirage render (no mirage:complete = true): an interrupted "
             "or foreign region");
    if (attribute(s0, "mirage:fingerprint").empty())
        fail(path, "no mirage:fingerprint: not rendered by a Mirage that writes regions");
    if (t.x0 < s0.full_x || t.y0 < s0.full_y || t.x1 > s0.full_x + s0.full_width ||
        t.y1 > s0.full_y + s0.full_height)
        fail(path, "its data window " + rect(t.x0, t.y0, t.x1, t.y1) +
                       " reaches outside its display window");
    for (const OIIO::ImageSpec& spec : t.specs)
        if (spec.x != t.x0 || spec.y != t.y0 || spec.width != s0.width || spec.height != s0.height)
            fail(path, "its subimages have different data windows");
    return t;
}

// Every region must be a part of the same frame as the first, with the same subimages and
// channels.
void checkSameFrame(const Tile& first, const Tile& t) {
    if (t.specs.size() != first.specs.size())
        fail(t.path, std::to_string(t.specs.size()) + " subimages, but " + first.path + " has " +
                         std::to_string(first.specs.size()));
    for (size_t s = 0; s < t.specs.size(); ++s) {
        const OIIO::ImageSpec &a = first.specs[s], &b = t.specs[s];
        if (a.full_x != b.full_x || a.full_y != b.full_y || a.full_width != b.full_width ||
            a.full_height != b.full_height)
            fail(t.path, "a different frame size (display window) from " + first.path);
        if (a.channelnames != b.channelnames)
            fail(t.path,
                 "other channels than " + first.path + " (subimage " + std::to_string(s) + ")");
    }
    for (const char* key : kIdentityKeys) {
        const std::string a = attribute(first.specs[0], key), b = attribute(t.specs[0], key);
        if (a != b)
            fail(t.path, "not a region of the same frame as " + first.path + ": " + key + " is '" +
                             b + "' there '" + a + "'");
    }
}

// Each pixel of the frame in exactly one region: overlaps name both files, and a gap the
// pixels no region covers.
void checkCoverage(const std::vector<Tile>& tiles, int width, int height) {
    std::vector<int> owner(size_t(width) * size_t(height), -1);
    for (size_t i = 0; i < tiles.size(); ++i) {
        const Tile& t = tiles[i];
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                int& o = owner[size_t(y) * width + x];
                if (o >= 0) {
                    const Tile& u = tiles[size_t(o)];
                    fail(t.path, "overlaps " + u.path + " in pixels " +
                                     rect(std::max(t.x0, u.x0), std::max(t.y0, u.y0),
                                          std::min(t.x1, u.x1), std::min(t.y1, u.y1)) +
                                     ": each pixel must come from exactly one region");
                }
                o = int(i);
            }
    }
    uint64_t missing = 0;
    int mx0 = width, my0 = height, mx1 = 0, my1 = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (owner[size_t(y) * width + x] < 0) {
                ++missing;
                mx0 = std::min(mx0, x);
                my0 = std::min(my0, y);
                mx1 = std::max(mx1, x + 1);
                my1 = std::max(my1, y + 1);
            }
    if (missing > 0)
        throw MirageError("mirage assemble: the regions do not cover the " + std::to_string(width) +
                          "x" + std::to_string(height) + " frame: " + std::to_string(missing) +
                          " pixels within " + rect(mx0, my0, mx1, my1) +
                          " are in no region (a missing tile?)");
}

// The frame's spec for subimage s: the first region's channels, types and attributes over the
// whole display window, without what describes one region's run.
OIIO::ImageSpec frameSpec(const std::vector<Tile>& tiles, size_t s) {
    OIIO::ImageSpec spec = tiles[0].specs[s];
    spec.x = spec.full_x;
    spec.y = spec.full_y;
    spec.width = spec.full_width;
    spec.height = spec.full_height;
    spec.tile_width = spec.tile_height = spec.tile_depth = 0;  // scanlines, as a render writes
    for (const char* key : kPerRegionKeys) spec.erase_attribute(key);
    double seconds = 0;
    for (const Tile& t : tiles)
        seconds += std::atof(attribute(t.specs[0], "mirage:render_seconds").c_str());
    if (spec.find_attribute("mirage:render_seconds"))
        spec.attribute("mirage:render_seconds", std::to_string(seconds));
    spec.attribute("mirage:assembled_regions", std::to_string(tiles.size()));
    return spec;
}

// Subimage s of every region into one frame buffer (float, all channels interleaved).
std::vector<float> readFramePixels(const std::vector<Tile>& tiles, size_t s,
                                   const OIIO::ImageSpec& frame) {
    const int n = frame.nchannels;
    std::vector<float> pixels(size_t(frame.width) * frame.height * n, 0.f);
    std::vector<float> region;
    for (const Tile& t : tiles) {
        std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(t.path);
        if (!in || !in->seek_subimage(int(s), 0)) fail(t.path, "cannot read: " + OIIO::geterror());
        const int w = t.x1 - t.x0, h = t.y1 - t.y0;
        region.resize(size_t(w) * h * n);
        if (!in->read_image(int(s), 0, 0, n, OIIO::TypeFloat, region.data()))
            fail(t.path, "cannot read its pixels: " + in->geterror());
        in->close();
        for (int y = 0; y < h; ++y)
            std::copy_n(&region[size_t(y) * w * n], size_t(w) * n,
                        &pixels[(size_t(t.y0 - frame.y + y) * frame.width + (t.x0 - frame.x)) * n]);
    }
    return pixels;
}

}  // namespace

AssemblyReport assembleRegions(const std::vector<std::string>& paths, const std::string& out) {
    if (paths.empty()) throw MirageError("mirage assemble: no regions given");
    std::vector<Tile> tiles;
    for (const std::string& p : paths) tiles.push_back(openTile(p));
    for (const Tile& t : tiles) checkSameFrame(tiles[0], t);
    const OIIO::ImageSpec& s0 = tiles[0].specs[0];
    // Coverage in display-window coordinates (the frame's pixels start at full_x, full_y).
    std::vector<Tile> shifted = tiles;
    for (Tile& t : shifted) {
        t.x0 -= s0.full_x, t.x1 -= s0.full_x;
        t.y0 -= s0.full_y, t.y1 -= s0.full_y;
    }
    checkCoverage(shifted, s0.full_width, s0.full_height);

    std::vector<OIIO::ImageSpec> specs;
    std::vector<std::vector<float>> pixels;
    for (size_t s = 0; s < tiles[0].specs.size(); ++s) {
        specs.push_back(frameSpec(tiles, s));
        pixels.push_back(readFramePixels(tiles, s, specs.back()));
    }
    std::vector<const float*> data;
    for (const auto& p : pixels) data.push_back(p.data());
    writeSubimagesAtomically(out, specs, data);

    AssemblyReport report;
    report.width = s0.full_width;
    report.height = s0.full_height;
    report.subimages = int(specs.size());
    for (const std::string& c : s0.channelnames) report.channels.push_back(c);
    return report;
}

}  // namespace mirage
