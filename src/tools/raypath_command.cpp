// `mirage raypath`: the validation instrument for curved light. Traces one path through a
// refractive-index profile with the path stepper the renderer uses (transport/curved_path.h)
// and prints where it ends.
//
//   mirage raypath --profile linear --n0 N0 --k K --origin x,y,z --direction x,y,z
//                  --length L [--tolerance TOL] [--method rk45|euler] [--step H]
//                  [--max-step H] [--max-steps N] [--wavelength NM] [--json]
//   mirage raypath --profile atmosphere [--inversion BASE,TOP,DT[,BLEND]]… (y = height, m)
//
// Output: end_point [x,y,z] (m), end_direction (unit), optical_path_length ∫n dl (m),
// arc_length, steps (accepted), rejected, straight_chords, evaluations (of n and ∇n), capped
// (the step cap was reached first), seconds (the trace alone). For the linear profile the exact
// answer (medium/linear_profile_path.h) and the distance to it are printed as well.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "core/clock.h"
#include "core/error.h"
#include "medium/air_index.h"
#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "tools/json_report.h"
#include "tools/tools.h"
#include "transport/curved_path.h"

namespace mirage {

namespace {

std::vector<double> parseNumbers(const std::string& option, const std::string& text,
                                 size_t minCount, size_t maxCount, const char* expected) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(x))
            throw MirageError(option + ": expected " + expected + ", got '" + text + "'");
        v.push_back(x);
    }
    if (v.size() < minCount || v.size() > maxCount)
        throw MirageError(option + ": expected " + expected + ", got '" + text + "'");
    return v;
}

Vec3d parseVec(const std::string& option, const std::string& text) {
    const std::vector<double> v =
        parseNumbers(option, text, 3, 3, "three comma-separated numbers x,y,z");
    return Vec3d(v[0], v[1], v[2]);
}

std::unique_ptr<IndexField> makeProfile(const RaypathOptions& o) {
    if (o.profile == "linear") return std::make_unique<LinearIndexField>(o.n0, o.k);
    AtmosphereSettings atm;
    for (const std::string& text : o.inversions) {
        const std::vector<double> v = parseNumbers(
            "--inversion", text, 3, 4, "BASE,TOP,DT[,BLEND] (m, m, K, m) with BASE < TOP");
        InversionLayer layer;
        layer.base = v[0];
        layer.top = v[1];
        layer.deltaT = v[2];
        if (v.size() == 4) layer.blend = v[3];
        if (!(layer.base < layer.top) || !(layer.blend > 0))
            throw MirageError("--inversion: expected BASE < TOP and BLEND > 0, got '" + text +
                              "'");
        atm.inversions.push_back(layer);
    }
    return std::make_unique<AtmosphereIndexField>(atm);
}

// Full double precision: a validation instrument reports the path to the last bit.
JsonReport exact(double v) { return jsonNumber(v, 17); }
JsonReport exact(const Vec3d& v) { return {exact(v.x), exact(v.y), exact(v.z)}; }

void printRaypathJson(const RaypathOptions& o, const Vec3d& origin, const Vec3d& direction,
                      const CurvedPathResult& r, double seconds) {
    JsonReport j;
    j["profile"] = o.profile;
    j["method"] = o.method;
    j["end_point"] = exact(r.end.r);
    j["end_direction"] = exact(r.end.direction());
    j["optical_path_length"] = exact(r.end.opl);
    j["arc_length"] = exact(r.end.arc);
    j["steps"] = r.steps;
    j["rejected"] = r.rejected;
    j["straight_chords"] = r.straightChords;
    j["evaluations"] = r.evaluations;
    j["capped"] = r.capped;
    if (o.profile == "linear") {
        const LinearProfilePath ex =
            exactLinearProfilePath(o.n0, o.k, Vec3d(0, 1, 0), origin, direction, r.end.arc);
        j["exact_end_point"] = exact(ex.endPoint);
        j["exact_optical_path_length"] = exact(ex.opticalPathLength);
        j["end_point_error"] = jsonNumber(length(r.end.r - ex.endPoint), 6);
    }
    j["seconds"] = jsonNumber(seconds, 6);
    std::fputs(formatJsonReport(j).c_str(), stdout);
}

void printRaypathTable(const RaypathOptions& o, const CurvedPathResult& r, double seconds) {
    const Vec3d endDir = r.end.direction();
    std::printf("raypath: %s profile, %s, %g m at %g nm\n", o.profile.c_str(),
                o.method.c_str(), o.length, o.wavelength);
    std::printf("  end point      %.12g %.12g %.12g\n", r.end.r.x, r.end.r.y, r.end.r.z);
    std::printf("  end direction  %.12g %.12g %.12g\n", endDir.x, endDir.y, endDir.z);
    std::printf("  optical path   %.15g m over %.15g m\n", r.end.opl, r.end.arc);
    std::printf("  %lld steps (%lld rejected, %lld straight), %lld evaluations, %.3g s%s\n",
                (long long)r.steps, (long long)r.rejected, (long long)r.straightChords,
                (long long)r.evaluations, seconds,
                r.capped ? "; STEP CAP REACHED before the length was covered" : "");
}

}  // namespace

int runRaypath(const RaypathOptions& o) {
    const Vec3d origin = parseVec("--origin", o.origin);
    const Vec3d direction = parseVec("--direction", o.direction);
    if (!(length(direction) > 0))
        throw MirageError("--direction: expected a non-zero vector, got '" + o.direction + "'");
    const std::unique_ptr<IndexField> field = makeProfile(o);
    if (!(field->index(origin, o.wavelength) > 0))
        throw MirageError("--origin: the refractive index there is not positive (n = " +
                          std::to_string(field->index(origin, o.wavelength)) + ")");

    CurvedPathSettings set;
    set.method = o.method == "euler" ? PathMethod::Euler : PathMethod::RK45;
    set.tolerance = o.tolerance;
    set.eulerStep = o.step;
    if (o.maxStep > 0) set.maxStep = o.maxStep;
    set.maxSteps = o.maxSteps;

    const auto t0 = Clock::now();
    const CurvedPathResult r =
        traceCurvedPath(*field, origin, direction, o.wavelength, o.length, set);
    const double seconds = secondsSince(t0);
    if (o.json)
        printRaypathJson(o, origin, direction, r, seconds);
    else
        printRaypathTable(o, r, seconds);
    if (r.capped) {
        std::fprintf(stderr,
                     "mirage: error: raypath: the path reached the step cap (%lld steps) after "
                     "%.9g of %.9g m; raise --max-steps or --tolerance/--step\n",
                     (long long)set.maxSteps, r.end.arc, o.length);
        return 1;
    }
    return 0;
}

Command addRaypathCommand(CLI::App& app) {
    auto o = std::make_shared<RaypathOptions>();
    auto* raypath = app.add_subcommand(
        "raypath", "Trace one curved light path through a refractive-index profile");
    raypath->add_option("--profile", o->profile, "linear (n = n0 + k·y, the default) or "
                                                 "atmosphere (US Standard Atmosphere 1976, y = "
                                                 "height above sea level)")
        ->check(CLI::IsMember({"linear", "atmosphere"}));
    raypath->add_option("--n0", o->n0, "linear: index at y = 0 (default 1)")->check(CLI::PositiveNumber);
    raypath->add_option("--k", o->k, "linear: dn/dy in 1/m (default 0)");
    raypath->add_option("--origin", o->origin, "Start point x,y,z in metres (default 0,0,0)");
    raypath->add_option("--direction", o->direction, "Start direction x,y,z, any length (default "
                                                     "1,0,0)");
    raypath->add_option("--length", o->length, "Arc length to trace, m (default 1)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--tolerance", o->tolerance, "rk45: largest accepted error estimate per "
                                                     "step, absolute (default 1e-6)")
        ->check(CLI::Range(1e-16, 1.0));
    raypath->add_option("--method", o->method, "rk45 (Dormand-Prince 5(4), the default) or euler "
                                               "(fixed step)")
        ->check(CLI::IsMember({"rk45", "euler"}));
    raypath->add_option("--step", o->step, "euler: fixed step, m (default 0.01)")->check(CLI::PositiveNumber);
    raypath->add_option("--max-step", o->maxStep, "rk45: largest step, m (default unlimited)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--max-steps", o->maxSteps, "Cap on accepted + rejected steps (default "
                                                    "10000000); reaching it is an error")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--wavelength", o->wavelength, "Wavelength, nm (default 550; matters for "
                                                       "dispersive fields)")
        ->check(CLI::Range(360.0, 830.0));
    raypath->add_option("--inversion", o->inversions,
                        "atmosphere: a layer BASE,TOP,DT[,BLEND] (m, m, K, m) warmer by DT "
                        "between BASE and TOP, edges blended over BLEND (default 1 m); "
                        "repeatable");
    raypath->add_flag("--json", o->json, "Print the result as JSON");
    return {raypath, [o] { return runRaypath(*o); }};
}

}  // namespace mirage
