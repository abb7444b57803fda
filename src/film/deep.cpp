#include "film/deep.h"

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "film/oiio_file.h"
#include "spectrum/cie.h"

namespace mirage {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw MirageError(FileLoc{path, 0, 0}, message);
}

// A surface's events from different samples (pixel jitter) fall within this relative distance.
constexpr float kSurfaceMerge = 1e-3f;

}  // namespace

// The sample's coverage, scaled to its alpha; its radiance at the distance its integrator
// gave it, or (unplaced) where its coverage reaches one half. Nothing lies behind the nearest
// surface the walk met: light seen in a mirror or through glass belongs to that surface's
// sample, which takes all the coverage left.
void DeepPixel::addSample(const DeepSample& s, const SampledWavelengths& w, float alpha) {
    double walked = 0;
    float surfaceT = kInfinity;
    for (const DeepSample::Coverage& c : s.coverage) {
        walked += c.alpha;
        if (c.at.surface) surfaceT = std::min(surfaceT, c.at.t);
    }
    const float scale = walked > 0 ? float(alpha / walked) : 0.f;
    float halfT = s.coverage.empty() ? 0.f : s.coverage.back().at.t;
    double sum = 0;
    for (const DeepSample::Coverage& c : s.coverage) {
        sum += c.alpha;
        if (sum >= 0.5 * walked) {
            halfT = c.at.t;
            break;
        }
    }
    for (const DeepSample::Coverage& c : s.coverage)
        mEvents.push_back({c.at.t, c.at.surface, c.alpha * scale, Vec3(0.f)});
    // A sample the walk saw as empty keeps its alpha where its light is.
    const bool placeAlpha = walked <= 0 && alpha != 0.f;
    for (const DeepSample::Radiance& r : s.radiance) {
        DeepAt at = std::isnan(r.at.t) ? DeepAt{halfT, false} : r.at;
        if (at.t > surfaceT) at = {surfaceT, true};
        mEvents.push_back({at.t, at.surface, 0.f, spectrumToXyz(r.L, w) + r.xyz});
    }
    if (placeAlpha) {
        const float t =
            s.radiance.empty() || std::isnan(s.radiance[0].at.t) ? halfT : s.radiance[0].at.t;
        mEvents.push_back({t, false, alpha, Vec3(0.f)});
    }
}

std::vector<DeepPoint> DeepPixel::merge(const DeepSettings& settings, uint32_t samples) const {
    std::vector<DeepPoint> out;
    if (samples == 0 || mEvents.empty()) return out;
    std::vector<Event> events = mEvents;
    std::stable_sort(events.begin(), events.end(),
                     [](const Event& a, const Event& b) { return a.t < b.t; });
    const double inv = 1.0 / double(samples);
    double pixelY = 0;
    for (const Event& e : events) pixelY += e.xyz.y * inv;

    // Groups of events: the coverage and colour sums of each, and its extent.
    struct Group {
        float z0, z1;
        bool surface;
        double alpha = 0;
        Vec3d xyz{0.0, 0.0, 0.0};
    };
    std::vector<Group> groups;
    for (const Event& e : events) {
        const double a = e.alpha * inv;
        const Vec3d c = Vec3d(e.xyz) * inv;
        bool joins = false;
        if (!groups.empty()) {
            const Group& g = groups.back();
            if (e.surface)
                joins = g.surface && e.t - g.z0 <= kSurfaceMerge * std::max(1.f, g.z0);
            else
                joins = !g.surface && g.alpha + a <= settings.alphaTolerance &&
                        std::abs(g.xyz.y + c.y) <= settings.colorTolerance * std::abs(pixelY);
        }
        if (!joins) groups.push_back({e.t, e.t, e.surface});
        Group& g = groups.back();
        g.z1 = e.t;
        g.alpha += a;
        g.xyz = g.xyz + c;
    }

    // Each group's alpha and colour relative to what lies in front of it (the top of deep.h).
    // A group behind full coverage (light a sample placed past where the pixel's coverage
    // ended: its walk met a roulette the path did not) cannot be seen there: its colour joins
    // the last group that can, divided by that group's front, so the flattened sum keeps it.
    double front = 1.0, lastFront = 1.0;
    for (const Group& g : groups) {
        if (front <= 1e-6 && !out.empty()) {
            for (int c = 0; c < 3; ++c) out.back().rgba[c] += float(g.xyz[c] / lastFront);
            continue;
        }
        const double k = 1.0 / front;
        DeepPoint p;
        p.z = g.z0;
        p.zBack = g.surface ? g.z0 : g.z1;
        for (int c = 0; c < 3; ++c) p.rgba[c] = float(g.xyz[c] * k);
        p.rgba[3] = float(std::min(1.0, g.alpha * k));
        out.push_back(p);
        lastFront = front;
        front -= g.alpha;
    }
    return out;
}

double DeepFilm::meanSamples() const {
    double n = 0;
    for (const auto& p : mPixels) n += double(p.size());
    return mPixels.empty() ? 0.0 : n / double(mPixels.size());
}

void DeepFilm::develop(const Mat3& toWorking) {
    for (auto& points : mPixels)
        for (DeepPoint& p : points) {
            const Vec3 rgb = toWorking.apply(Vec3(p.rgba[0], p.rgba[1], p.rgba[2]));
            for (int c = 0; c < 3; ++c) p.rgba[c] = rgb[c];
        }
}

size_t DeepFilm::maxSamples() const {
    size_t m = 0;
    for (const auto& p : mPixels) m = std::max(m, p.size());
    return m;
}

void writeDeepExr(const std::string& path, const DeepFilm& film, bool halfFloat,
                  const std::string& colorSpace,
                  const std::map<std::string, std::string>& metadata) {
    const OIIO::TypeDesc colour = halfFloat ? OIIO::TypeHalf : OIIO::TypeFloat;
    OIIO::ImageSpec spec(film.width(), film.height(), 6, OIIO::TypeFloat);
    spec.channelnames = {"R", "G", "B", "A", "Z", "ZBack"};
    spec.channelformats = {colour, colour, colour, colour, OIIO::TypeFloat, OIIO::TypeFloat};
    spec.alpha_channel = 3;
    spec.z_channel = 4;
    spec.deep = true;
    // ZIPS: deep scanline files compress one scanline per block.
    spec.attribute("compression", "zips");
    if (!colorSpace.empty()) spec.attribute("mirage:colorSpace", colorSpace);
    for (const auto& [key, value] : metadata) spec.attribute("mirage:" + key, value);

    OIIO::DeepData deep;
    deep.init(spec);
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const int64_t pixel = int64_t(y) * film.width() + x;
            const std::vector<DeepPoint>& points = film.pixel(x, y);
            deep.set_samples(pixel, int(points.size()));
            for (size_t s = 0; s < points.size(); ++s) {
                const DeepPoint& p = points[s];
                for (int c = 0; c < 4; ++c) deep.set_deep_value(pixel, c, int(s), p.rgba[c]);
                deep.set_deep_value(pixel, 4, int(s), p.z);
                deep.set_deep_value(pixel, 5, int(s), p.zBack);
            }
        }
    writeImageAtomically(
        path, {spec}, [&](OIIO::ImageOutput& out, size_t) { return out.write_deep_image(deep); },
        "deep image");
}

DeepFilm readDeepExr(const std::string& path) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) fail(path, "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    if (!spec.deep) fail(path, "not a deep image");
    OIIO::DeepData deep;
    if (!in->read_native_deep_image(0, 0, deep)) fail(path, "cannot read: " + in->geterror());
    const int r = spec.channelindex("R"), g = spec.channelindex("G"), b = spec.channelindex("B"),
              a = spec.channelindex("A"), z = spec.channelindex("Z"),
              zb = spec.channelindex("ZBack");
    if (std::min({r, g, b, a, z}) < 0) fail(path, "a deep image needs R G B A Z");
    DeepFilm film(spec.width, spec.height);
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            const int64_t pixel = int64_t(y) * spec.width + x;
            std::vector<DeepPoint> points(size_t(deep.samples(pixel)));
            for (size_t s = 0; s < points.size(); ++s) {
                DeepPoint& p = points[s];
                const int i = int(s);
                p.rgba[0] = deep.deep_value(pixel, r, i);
                p.rgba[1] = deep.deep_value(pixel, g, i);
                p.rgba[2] = deep.deep_value(pixel, b, i);
                p.rgba[3] = deep.deep_value(pixel, a, i);
                p.z = deep.deep_value(pixel, z, i);
                p.zBack = zb >= 0 ? deep.deep_value(pixel, zb, i) : p.z;
            }
            film.setPixel(x, y, std::move(points));
        }
    return film;
}

}  // namespace mirage
