// `mirage tradeoff`: the speed↔accuracy instrument (docs/design.md, "Speed against accuracy").
//
//   mirage tradeoff SCENE.toml [--reference ref.exr] --vary photons=1e4,1e5,1e6
//                   [--vary estimate=beam,point] [--vary k=16,64,256] [--set key=value …]
//                   [--integrator NAME] [--resolution WxH] [--spp N] [--threads N]
//                   [--repeats R] [--reference-spp N] [-o prefix]
//
// Each --vary names a scene key and its values; several --vary form the Cartesian product.
// Short names: photons, estimate, k, max_radius ([render]), spp (film.spp), integrator
// (render.integrator); any dotted key is taken as a --set override. Every setting is rendered
// in-process by the same code as `mirage render` (frame/render_frame.h) and compared with the
// reference in scene-linear RGB (alpha ignored), over all N pixels × 3 channels:
//
//   RMSE      = sqrt( Σ (x − r)² / 3N )
//   relMSE    = Σ (x − r)² / (r² + ε) / 3N,   ε = 1e-3 · mean(r)²
//   mean bias = (mean x − mean r) / mean r
//
// ε keeps black pixels (empty sky) from dividing by zero: a pixel far darker than the image's
// mean counts as if it were 3 % of the mean. The time is the wall-clock time of integrator
// set-up, photon pass, render and develop (scene loading excluded: it is the same for every
// setting), the median over --repeats runs. Without --reference, one is rendered with the
// reference path tracer (volpath) at max(256, 4 × the sweep's highest spp) samples and a seed
// of its own, so that its noise is independent of the sweep's, and written as
// <prefix>reference.exr (32-bit float) for reuse. The noise left in the reference sets a floor
// under relMSE of about its own relMSE: use more reference samples than the best setting.
//
// Output: <prefix>tradeoff.csv (setting, seconds, rmse, relmse, mean_bias, one column per
// varied key, grid_bytes: the scalar grids as loaded, which `--vary volume.0.precision=float,fp8`
// trades), a table on stdout, and <prefix>tradeoff.png, relMSE against seconds on log-log
// axes with one polyline per value of the last varied key (in sweep order).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "core/thread_limit.h"
#include "film/color.h"
#include "film/image_io.h"
#include "frame/frame_settings.h"
#include "frame/render_frame.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"
#include "tools/plot.h"
#include "tools/tools.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

// How the values of a varied key are checked and written into the scene file.
enum class ValueKind { Count, Number, Estimate, Integrator, Raw };

struct KeyInfo {
    const char* name;  // short name on the command line
    const char* key;   // scene key
    ValueKind kind;
};

const KeyInfo kKeys[] = {
    {"photons", "render.photons", ValueKind::Count},
    {"estimate", "render.estimate", ValueKind::Estimate},
    {"k", "render.k", ValueKind::Count},
    {"max_radius", "render.max_radius", ValueKind::Number},
    {"spp", "film.spp", ValueKind::Count},
    {"integrator", "render.integrator", ValueKind::Integrator},
};

struct VariedKey {
    std::string name;                 // as given (the CSV column)
    std::string key;                  // scene key
    std::vector<std::string> values;  // TOML text of each value
};

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (;;) {
        size_t end = s.find(sep, start);
        parts.push_back(s.substr(start, end - start));
        if (end == std::string::npos) return parts;
        start = end + 1;
    }
}

// One value of --vary, checked and written as TOML ("1e4" → "10000" for a count, which the
// scene reader wants as an integer).
std::string checkedValue(const std::string& option, const KeyInfo& info, const std::string& v) {
    auto bad = [&](const std::string& why) {
        return MirageError("--vary '" + option + "': '" + v + "' " + why);
    };
    switch (info.kind) {
        case ValueKind::Count:
        case ValueKind::Number: {
            char* end = nullptr;
            double x = std::strtod(v.c_str(), &end);
            if (end == v.c_str() || *end != '\0' || !std::isfinite(x))
                throw bad("is not a number");
            if (info.kind == ValueKind::Number) {
                if (x < 0) throw bad("must not be negative");
                return v;
            }
            if (x < 1 || x != std::floor(x) || x > 1e15)
                throw bad("is not a whole number of at least 1 (e.g. 16 or 1e5)");
            char buf[32];
            std::snprintf(buf, sizeof buf, "%lld", (long long)x);
            return buf;
        }
        case ValueKind::Estimate:
            if (v != "beam" && v != "point") throw bad("is not an estimate; expected beam or point");
            return "\"" + v + "\"";
        case ValueKind::Integrator: {
            if (std::none_of(integratorInfos().begin(), integratorInfos().end(),
                             [&](const IntegratorInfo& i) { return i.name == v; }))
                throw bad("is not an integrator; expected one of " + integratorNameList());
            return "\"" + v + "\"";
        }
        case ValueKind::Raw: break;
    }
    return v;
}

VariedKey parseVary(const std::string& option) {
    size_t eq = option.find('=');
    if (eq == std::string::npos || eq == 0)
        throw MirageError("--vary '" + option + "': expected NAME=v1,v2,…, e.g. photons=1e4,1e5");
    VariedKey vk;
    vk.name = option.substr(0, eq);
    std::string list = option.substr(eq + 1);

    KeyInfo info{"", "", ValueKind::Raw};
    bool known = false;
    for (const auto& k : kKeys)
        if (vk.name == k.name || vk.name == k.key) {
            info = k;
            known = true;
        }
    if (!known && vk.name.find('.') == std::string::npos) {
        const std::string names = joinList(kKeys, [](const KeyInfo& k) { return std::string(k.name); });
        throw MirageError("--vary '" + option + "': unknown key '" + vk.name + "'; expected one of " +
                          names + ", or a dotted scene key such as volume.0.density_scale");
    }
    vk.key = known ? info.key : vk.name;
    if (list.empty()) throw MirageError("--vary '" + option + "': empty list of values");
    for (const auto& v : split(list, ',')) {
        if (v.empty())
            throw MirageError("--vary '" + option + "': empty value in the list");
        vk.values.push_back(checkedValue(option, info, v));
    }
    return vk;
}

// A value as the CSV and the table show it (strings without their TOML quotes).
std::string plain(const std::string& toml) {
    if (toml.size() >= 2 && toml.front() == '"' && toml.back() == '"')
        return toml.substr(1, toml.size() - 2);
    return toml;
}

struct Setting {
    std::vector<std::string> values;  // one per varied key (TOML text)
    std::string label;                // "photons=10000 k=16"
    double seconds = 0;
    uint64_t gridBytes = 0;  // the scalar grids as loaded (scene/memory_budget.h)
    int spp = 0;
    Image image;
    double rmse = 0, relMse = 0, meanBias = 0;
};

// The Cartesian product of the varied keys, the last key varying fastest.
std::vector<Setting> cartesian(const std::vector<VariedKey>& keys) {
    std::vector<Setting> out(1);
    for (const auto& k : keys) {
        std::vector<Setting> next;
        for (const auto& s : out)
            for (const auto& v : k.values) {
                Setting t = s;
                t.values.push_back(v);
                t.label += (t.label.empty() ? "" : " ") + k.name + "=" + plain(v);
                next.push_back(t);
            }
        out = std::move(next);
    }
    return out;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// RMSE, relMSE and mean bias of `x` against `r` (RGB, alpha ignored): see the file comment.
void compare(const Image& x, const Image& r, Setting* s) {
    const size_t n = size_t(r.width) * r.height;
    double sumR = 0, sumX = 0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            sumR += r.rgba[4 * i + c];
            sumX += x.rgba[4 * i + c];
        }
    const double meanR = sumR / double(3 * n), meanX = sumX / double(3 * n);
    const double eps = 1e-3 * meanR * meanR;
    double se = 0, rel = 0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            double rv = r.rgba[4 * i + c], d = x.rgba[4 * i + c] - rv;
            se += d * d;
            rel += d * d / (rv * rv + eps);
        }
    s->rmse = std::sqrt(se / double(3 * n));
    s->relMse = rel / double(3 * n);
    s->meanBias = (meanX - meanR) / meanR;
}

std::string format(const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::vector<VariedKey> parseVariedKeys(const TradeoffOptions& o) {
    std::vector<VariedKey> keys;
    for (const auto& v : o.vary) {
        keys.push_back(parseVary(v));
        for (size_t i = 0; i + 1 < keys.size(); ++i)
            if (keys[i].key == keys.back().key)
                throw MirageError("--vary '" + v + "': " + keys.back().key + " is varied twice");
    }
    if (keys.empty()) throw MirageError("tradeoff: give at least one --vary NAME=v1,v2,…");
    return keys;
}

// The scenes of the sweep: the scene file with the command line's settings, then the varied
// keys, as overrides.
struct Sweep {
    Sweep(const TradeoffOptions& options, const ColorPipeline& colorPipeline,
          std::vector<VariedKey> variedKeys)
        : o(options), color(colorPipeline), keys(std::move(variedKeys)) {
        // Command-line settings become overrides ahead of the varied keys, so a varied key wins.
        base = o.overrides;
        if (!o.integrator.empty()) base.push_back("render.integrator=\"" + o.integrator + "\"");
        if (o.spp > 0) base.push_back("film.spp=" + std::to_string(o.spp));
    }

    Scene load(const std::vector<std::string>& overrides) const {
        Scene scene = loadScene(o.input, LoadOptions{1, overrides}, color);
        FrameRequest settings;
        settings.input = o.input;
        settings.resolution = o.resolution;
        settings.seed = o.seed;
        settings.quiet = true;
        applyFrameSettings(scene, settings);
        return scene;
    }

    std::vector<std::string> overridesOf(const Setting& s) const {
        std::vector<std::string> ov = base;
        for (size_t i = 0; i < keys.size(); ++i) ov.push_back(keys[i].key + "=" + s.values[i]);
        return ov;
    }

    const TradeoffOptions& o;
    const ColorPipeline& color;
    std::vector<VariedKey> keys;
    std::vector<std::string> base;
};

void checkReferenceSize(const TradeoffOptions& o, const Image& reference, const Scene& scene) {
    if (reference.width != scene.settings.width || reference.height != scene.settings.height)
        throw MirageError(o.reference + ": the reference is " + std::to_string(reference.width) +
                          "x" + std::to_string(reference.height) + " but the renders are " +
                          std::to_string(scene.settings.width) + "x" +
                          std::to_string(scene.settings.height) +
                          "; render it at the same resolution or pass --resolution");
}

// Renders every setting --repeats times; keeps the first image and the median time.
void renderSweep(const Sweep& sweep, const Image* reference, std::vector<Setting>* settings) {
    for (size_t i = 0; i < settings->size(); ++i) {
        Setting& s = (*settings)[i];
        std::vector<double> seconds;
        for (int r = 0; r < sweep.o.repeats; ++r) {
            Scene scene = sweep.load(sweep.overridesOf(s));
            if (reference) checkReferenceSize(sweep.o, *reference, scene);
            s.spp = scene.settings.spp;
            s.gridBytes = loadedGrids(scene).bytes;
            RenderedFrame frame = renderFrame(scene, sweep.color);
            seconds.push_back(frame.seconds);
            if (r == 0) s.image = std::move(frame.image);
        }
        s.seconds = median(seconds);
        if (!sweep.o.quiet)
            std::fprintf(stderr, "tradeoff: [%zu/%zu] %s: %.3f s\n", i + 1, settings->size(),
                         s.label.c_str(), s.seconds);
    }
}

// The reference rendered by the path tracer at high samples and written to
// <prefix>reference.exr (its path goes to *path).
Image renderReference(const Sweep& sweep, const std::vector<Setting>& settings,
                      std::string* path) {
    const TradeoffOptions& o = sweep.o;
    int maxSpp = 0;
    for (const auto& s : settings) maxSpp = std::max(maxSpp, s.spp);
    int spp = o.referenceSpp > 0 ? o.referenceSpp : std::max(256, 4 * maxSpp);
    std::vector<std::string> ov = sweep.base;
    ov.push_back("render.integrator=\"volpath\"");
    ov.push_back("film.spp=" + std::to_string(spp));
    Scene scene = sweep.load(ov);
    // A seed of its own: the reference's noise must not correlate with the sweep's.
    scene.settings.seed += 0x9E3779B9u;
    if (!o.quiet)
        std::fprintf(stderr, "tradeoff: reference: volpath, %d spp, %dx%d …\n", spp,
                     scene.settings.width, scene.settings.height);
    RenderedFrame frame = renderFrame(scene, sweep.color);
    *path = o.prefix + "reference.exr";
    ExrOptions exr;
    exr.halfFloat = false;
    exr.colorSpace = sweep.color.workingSpace();
    exr.chromaticities = sweep.color.workingChromaticities();
    exr.metadata = {{"scene", scene.source},
                    {"integrator", "volpath"},
                    {"spp", std::to_string(spp)},
                    {"seed", std::to_string(scene.settings.seed)},
                    {"render_seconds", std::to_string(frame.seconds)},
                    {"version", MIRAGE_VERSION}};
    writeExr(*path, frame.image, exr);
    if (!o.quiet)
        std::fprintf(stderr, "tradeoff: reference: %.2f s, written to %s\n", frame.seconds,
                     path->c_str());
    return std::move(frame.image);
}

void checkReferenceLit(const Image& reference, const std::string& path) {
    double sumR = 0;
    for (size_t i = 0; i < reference.rgba.size(); ++i)
        if (i % 4 != 3) sumR += reference.rgba[i];
    if (!(sumR > 0))
        throw MirageError(path + ": the reference is black (or not finite): relative "
                                 "errors are undefined");
}

// The table on stdout and <prefix>tradeoff.csv; returns the CSV's path.
std::string writeTable(const TradeoffOptions& o, const std::vector<VariedKey>& keys,
                       const std::vector<Setting>& settings, const std::string& referencePath) {
    std::string csv = "setting,seconds,rmse,relmse,mean_bias";
    for (const auto& k : keys) csv += "," + k.name;
    csv += ",grid_bytes\n";
    size_t labelWidth = 7;
    for (const auto& s : settings) labelWidth = std::max(labelWidth, s.label.size());
    std::printf("reference: %s\n", referencePath.c_str());
    std::printf("%-*s %10s %12s %12s %11s %11s\n", int(labelWidth), "setting", "seconds", "rmse",
                "relmse", "mean_bias", "grids");
    for (const auto& s : settings) {
        csv += s.label + "," + format("%.4f", s.seconds) + "," + format("%.6g", s.rmse) + "," +
               format("%.6g", s.relMse) + "," + format("%.6g", s.meanBias);
        for (const auto& v : s.values) csv += "," + plain(v);
        csv += "," + std::to_string(s.gridBytes) + "\n";
        std::printf("%-*s %10.3f %12.5g %12.5g %+11.4f %11s\n", int(labelWidth), s.label.c_str(),
                    s.seconds, s.rmse, s.relMse, s.meanBias, formatBytes(s.gridBytes).c_str());
    }
    const std::string csvPath = o.prefix + "tradeoff.csv";
    createParentFolders(csvPath);
    writeTextFileAtomically(csvPath, csv);
    return csvPath;
}

// <prefix>tradeoff.png: one polyline per value of the last varied key, points in the sweep's
// order; returns its path.
std::string writePlot(const TradeoffOptions& o, const std::vector<VariedKey>& keys,
                      const std::vector<Setting>& settings) {
    LogLogPlot plot;
    plot.title = fs::path(o.input).filename().string();
    plot.xLabel = "render time (s)";
    plot.yLabel = "relMSE";
    auto series = [&](const std::string& label, const std::string* lastValue) {
        PlotSeries ps;
        ps.label = label;
        for (const auto& st : settings)
            if (!lastValue || st.values.back() == *lastValue) {
                ps.x.push_back(st.seconds);
                ps.y.push_back(st.relMse);
            }
        return ps;
    };
    if (keys.size() == 1) {
        plot.series.push_back(series("", nullptr));
    } else {
        for (const auto& v : keys.back().values)
            plot.series.push_back(series(keys.back().name + "=" + plain(v), &v));
    }
    const std::string pngPath = o.prefix + "tradeoff.png";
    writePlotPng(pngPath, drawLogLogPlot(plot));
    return pngPath;
}

}  // namespace

int runTradeoff(const TradeoffOptions& o) {
    if (isVolumeFile(o.input))
        throw MirageError(o.input + ": tradeoff needs a scene .toml (--vary sets scene keys); "
                                    "write a scene that names the .vdb");
    std::vector<VariedKey> keys = parseVariedKeys(o);
    const auto threads = limitThreads(o.threads);
    const ColorPipeline color(o.ocioConfig);
    const Sweep sweep(o, color, std::move(keys));

    std::vector<Setting> settings = cartesian(sweep.keys);
    std::string referencePath = o.reference;
    Image reference;
    if (!o.reference.empty()) reference = readExr(o.reference);
    renderSweep(sweep, o.reference.empty() ? nullptr : &reference, &settings);
    if (o.reference.empty()) reference = renderReference(sweep, settings, &referencePath);
    checkReferenceLit(reference, referencePath);
    for (auto& s : settings) compare(s.image, reference, &s);

    const std::string csvPath = writeTable(o, sweep.keys, settings, referencePath);
    const std::string pngPath = writePlot(o, sweep.keys, settings);
    std::printf("%s\n%s\n", csvPath.c_str(), pngPath.c_str());
    return 0;
}

Command addTradeoffCommand(CLI::App& app) {
    auto o = std::make_shared<TradeoffOptions>();
    auto* tradeoff = app.add_subcommand(
        "tradeoff", "Error against a reference versus render time over a sweep of settings");
    tradeoff->add_option("input", o->input, "Scene .toml")->required();
    tradeoff->add_option("--vary", o->vary,
                         "NAME=v1,v2,…: photons, estimate, k, max_radius, spp, integrator or "
                         "any dotted scene key; several form the Cartesian product")
        ->required();
    tradeoff->add_option("--reference", o->reference,
                         "Reference EXR (default: render one with volpath, write "
                         "<prefix>reference.exr)");
    tradeoff->add_option("--reference-spp", o->referenceSpp,
                         "Samples per pixel of a rendered reference (default: 4x the sweep's "
                         "highest, at least 256)")
        ->check(CLI::Range(1, 1 << 20));
    tradeoff->add_option("--set", o->overrides, "Override scene values before the varied keys: "
                                                "key.path=value …")
        ->take_all();
    tradeoff->add_option("--resolution", o->resolution, "Image size WxH (overrides "
                                                        "film.resolution)");
    tradeoff->add_option("--spp", o->spp, "Samples per pixel unless varied")
        ->check(CLI::Range(1, 1 << 20));
    tradeoff->add_option("--integrator", o->integrator,
                         integratorNameList() + " unless varied (default: the scene's)");
    tradeoff->add_option("--threads", o->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    tradeoff->add_option("--seed", o->seed, "Random seed (default: film.seed)")->check(CLI::Range(int64_t(0), INT64_MAX));
    tradeoff->add_option("--repeats", o->repeats, "Renders per setting; the median time is kept "
                                                  "(default 1)")
        ->check(CLI::Range(1, 1000));
    tradeoff->add_option("-o,--output", o->prefix,
                         "Prefix of the output files <prefix>tradeoff.csv, .png, reference.exr");
    tradeoff->add_option("--ocio", o->ocioConfig, "OCIO config file (default: $OCIO, else "
                                                  "built-in)");
    tradeoff->add_flag("-q,--quiet", o->quiet, "No progress output");
    return {tradeoff, [o] { return runTradeoff(*o); }};
}

}  // namespace mirage
