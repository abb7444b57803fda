// The speed↔accuracy trade of the Fermat path stepper, measured (figure 1 of Gutierrez
// et al. 2005: error and time of Dormand–Prince RK5(4)7M against tolerance, and against forward
// Euler). Linear profile n = 1 + k·y, k ∈ {±0.1, ±0.05, ±0.01}, three start directions, 10 m of
// arc length; the error is the distance of the end point from the exact catenary
// (medium/linear_profile_path.h). RK45 runs tolerances 1e−3 … 1e−14, Euler fixed steps
// 1e−1 … 1e−6 m. Times are per path, one thread, each the median of 5 timings of enough
// repeats to last ≥ 2 ms (one timing when a single trace lasts over 50 ms: Euler's finest steps).
//
//   bench_raypath [OUT_DIR]   (default out/bench)
// writes OUT_DIR/raypath.csv (one row per method, setting, k and direction),
// OUT_DIR/raypath_error_time.png (error against time, both methods) and
// OUT_DIR/raypath_tolerance.png (RK45 error and evaluations against tolerance), and prints the
// summary: per setting the worst error and mean time, and the time each method needs for a given
// error (interpolated log-log) with their ratio.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "tools/plot.h"
#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "transport/curved_path.h"

using namespace mirage;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

namespace {

constexpr double kLength = 10.0;
const double kKs[] = {-0.1, -0.05, -0.01, 0.01, 0.05, 0.1};
const Vec3d kDirections[] = {Vec3d(1, 0.2, 0), Vec3d(1, -0.3, 0.2), Vec3d(0.3, 1, 0)};
const Vec3d kOrigin(0, 0.5, 0);

struct Row {
    std::string method;
    double setting, k;
    int direction;
    double error, oplError, seconds;
    int64_t steps, evaluations;
};

// Per-path seconds: the median of 5 timings of `reps` traces, reps grown until one timing
// lasts ≥ 2 ms.
double timePath(const IndexField& field, const Vec3d& d, const CurvedPathSettings& set) {
    int reps = 1;
    std::vector<double> t;
    for (;;) {
        const auto t0 = Clock::now();
        for (int i = 0; i < reps; ++i) {
            const CurvedPathResult r = traceCurvedPath(field, kOrigin, d, 550, kLength, set);
            if (r.steps < 0) std::printf("?");  // keeps the trace from being optimised away
        }
        const double s = std::chrono::duration<double>(Clock::now() - t0).count();
        if (s < 2e-3 && reps < (1 << 20)) {
            reps *= 2;
            continue;
        }
        t.push_back(s / reps);
        if (t.size() == 5 || s > 0.05) break;  // a trace this long needs no repeats
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

struct Summary {
    double setting, worstError, meanSeconds, meanEvaluations;
};

std::vector<Summary> summarise(const std::vector<Row>& rows, const std::string& method) {
    std::vector<Summary> out;
    for (const Row& r : rows) {
        if (r.method != method) continue;
        if (out.empty() || out.back().setting != r.setting) out.push_back({r.setting, 0, 0, 0});
        Summary& s = out.back();
        s.worstError = std::max(s.worstError, r.error);
        s.meanSeconds += r.seconds;
        s.meanEvaluations += double(r.evaluations);
    }
    const double n = double(std::size(kKs) * std::size(kDirections));
    for (Summary& s : out) {
        s.meanSeconds /= n;
        s.meanEvaluations /= n;
    }
    return out;
}

// Time to reach `error` along a curve of (worst error, mean time), log-log interpolated; < 0
// when the curve does not span it.
double timeAtError(const std::vector<Summary>& curve, double error) {
    for (size_t i = 0; i + 1 < curve.size(); ++i) {
        const double e0 = curve[i].worstError, e1 = curve[i + 1].worstError;
        if (e0 <= 0 || e1 <= 0 || (error - e0) * (error - e1) > 0) continue;
        const double t = (std::log(error) - std::log(e0)) / (std::log(e1) - std::log(e0));
        return std::exp(std::log(curve[i].meanSeconds) +
                        t * (std::log(curve[i + 1].meanSeconds) - std::log(curve[i].meanSeconds)));
    }
    return -1;
}

}  // namespace

int main(int argc, char** argv) {
    const fs::path dir = argc > 1 ? argv[1] : "out/bench";
    fs::create_directories(dir);
    std::vector<Row> rows;

    auto run = [&](const std::string& method, double setting, const CurvedPathSettings& set) {
        for (double k : kKs) {
            const LinearIndexField field(1.0, k);
            for (int di = 0; di < int(std::size(kDirections)); ++di) {
                const Vec3d d = normalize(kDirections[di]);
                const LinearProfilePath ex =
                    exactLinearProfilePath(1.0, k, Vec3d(0, 1, 0), kOrigin, d, kLength);
                const CurvedPathResult r = traceCurvedPath(field, kOrigin, d, 550, kLength, set);
                rows.push_back({method, setting, k, di, length(r.end.r - ex.endPoint),
                                std::abs(r.end.opl - ex.opticalPathLength),
                                timePath(field, d, set), r.steps, r.evaluations});
            }
        }
    };
    for (int e = 3; e <= 14; ++e) {
        CurvedPathSettings set;
        set.tolerance = std::pow(10.0, -e);
        run("rk45", set.tolerance, set);
    }
    for (double h : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6}) {
        CurvedPathSettings set;
        set.method = PathMethod::Euler;
        set.eulerStep = h;
        run("euler", h, set);
    }

    // CSV, written through a temporary name and a rename.
    std::string csv =
        "method,tolerance_or_step_m,k,direction,end_point_error_m,opl_error_m,steps,"
        "evaluations,seconds_per_path\n";
    for (const Row& r : rows) {
        char line[256];
        std::snprintf(line, sizeof line, "%s,%.3g,%g,%d,%.6e,%.6e,%lld,%lld,%.6e\n",
                      r.method.c_str(), r.setting, r.k, r.direction, r.error, r.oplError,
                      (long long)r.steps, (long long)r.evaluations, r.seconds);
        csv += line;
    }
    try {
        writeTextFileAtomically((dir / "raypath.csv").string(), csv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_raypath: %s\n", e.what());
        return 1;
    }

    const std::vector<Summary> rk = summarise(rows, "rk45"), eu = summarise(rows, "euler");
    std::printf("Fermat paths in n = 1 + k·y, k in ±{0.01, 0.05, 0.1}, 3 directions, %g m\n",
                kLength);
    std::printf("  %-6s %-10s %-14s %-14s %-12s\n", "method", "setting", "worst error m",
                "time/path s", "evaluations");
    for (const auto* curve : {&rk, &eu})
        for (const Summary& s : *curve)
            std::printf("  %-6s %-10.0e %-14.3e %-14.3e %-12.0f\n", curve == &rk ? "rk45" : "euler",
                        s.setting, s.worstError, s.meanSeconds, s.meanEvaluations);
    std::printf("  at equal error (worst over k and directions):\n");
    for (double err : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7}) {
        const double tr = timeAtError(rk, err), te = timeAtError(eu, err);
        if (tr > 0 && te > 0)
            std::printf("    error %.0e m: rk45 %.3e s, euler %.3e s, euler/rk45 = %.0f\n", err, tr,
                        te, te / tr);
    }

    LogLogPlot timePlot;
    timePlot.title = "Fermat path, n = 1 + k y: end-point error against time";
    timePlot.xLabel = "time per 10 m path (s)";
    timePlot.yLabel = "worst end-point error (m)";
    LogLogPlot tolPlot;
    tolPlot.title = "Dormand-Prince RK5(4)7M: error and evaluations against tolerance";
    tolPlot.xLabel = "tolerance";
    tolPlot.yLabel = "worst error (m) / evaluations";
    PlotSeries rkTime{"RK5(4) Dormand-Prince, tolerance 1e-3 ... 1e-14", {}, {}};
    PlotSeries euTime{"forward Euler, step 0.1 ... 1e-6 m", {}, {}};
    PlotSeries rkErr{"worst end-point error (m)", {}, {}}, rkEval{"mean evaluations", {}, {}};
    PlotSeries ideal{"error = tolerance", {}, {}};
    for (const Summary& s : rk) {
        rkTime.x.push_back(s.meanSeconds);
        rkTime.y.push_back(s.worstError);
        rkErr.x.push_back(s.setting);
        rkErr.y.push_back(s.worstError);
        rkEval.x.push_back(s.setting);
        rkEval.y.push_back(s.meanEvaluations);
        ideal.x.push_back(s.setting);
        ideal.y.push_back(s.setting);
    }
    for (const Summary& s : eu) {
        euTime.x.push_back(s.meanSeconds);
        euTime.y.push_back(s.worstError);
    }
    timePlot.series = {rkTime, euTime};
    tolPlot.series = {rkErr, rkEval, ideal};
    writePlotPng((dir / "raypath_error_time.png").string(), drawLogLogPlot(timePlot));
    writePlotPng((dir / "raypath_tolerance.png").string(), drawLogLogPlot(tolPlot));
    std::printf("wrote %s, raypath_error_time.png, raypath_tolerance.png\n", csv.c_str());
    return 0;
}
