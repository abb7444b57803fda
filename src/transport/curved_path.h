// Light paths in a refractive-index field: Fermat's principle d/dl (n dr/dl) = ∇n, written as
// the first-order system of Gutierrez et al. 2005 (eq. 9–11) in the state r and v = n·dr/dl:
//     dr/dl = v / n,   dv/dl = ∇n,   (and dO/dl = n for the optical path length O)
// over arc length l. Solved by the embedded Dormand–Prince RK5(4)7M pair (Dormand & Prince
// 1980; coefficients as in Hairer, Nørsett & Wanner, Solving ODEs I, table II.5.2): seven
// stages, the last one reused as the first of the next step (FSAL), fifth-order solution kept,
// the fourth-order companion used only for the error estimate that adapts the step. Forward
// Euler is there for comparison (figure 1 of Gutierrez et al. 2005). Where the field promises a
// straight stretch (∇n = 0, IndexField::straightDistance) the stretch is one exact chord.
//
// Every accepted step is handed to a visitor as a chord (from → to): the renderer tests chords
// against surfaces and accumulates optical depth along them; `mirage raypath` only counts.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>

#include "core/math.h"
#include "medium/index_field.h"

namespace mirage {

enum class PathMethod { RK45, Euler };

struct CurvedPathSettings {
    PathMethod method = PathMethod::RK45;
    // RK45: the largest error estimate accepted per step, absolute, in metres for r and in
    // index units for v = n·dr/dl (|v| = n ≈ 1, so relative there), metres for O.
    double tolerance = 1e-6;
    double minStep = 1e-9;   // m; a step this short is accepted whatever its error (counted)
    double maxStep = std::numeric_limits<double>::infinity();  // m
    double eulerStep = 1e-2;  // m, the fixed step of forward Euler
    // Step-size controller (Hairer et al. II.4): h ← h·clamp(safety·err^(−1/5), shrink, grow);
    // no growth right after a rejected step.
    double safety = 0.9, maxShrink = 0.2, maxGrowth = 5.0;
    // Hard cap on steps (accepted + rejected); a path that reaches it ends there, reported.
    int64_t maxSteps = 10'000'000;
    // Optional cap on the next step from r along the unit direction (e.g. the distance to the
    // nearest surface, so that a chord does not jump through a thin object). ≤ 0: no cap.
    std::function<double(const Vec3d& r, const Vec3d& direction)> stepCap;
    // For the renderer: where the scene has surfaces, set stepCap by the rule of
    // surface_step_cap.h (the scene's [refraction] surface_step_cap). The stepper ignores it.
    bool capNearSurfaces = true;
};

struct PathState {
    Vec3d r;              // position, m
    Vec3d v;              // n·dr/dl (|v| = n)
    double opl = 0;       // optical path length ∫ n dl so far, m
    double arc = 0;       // arc length l so far, m
    Vec3d direction() const { return normalize(v); }
};

// Called for every accepted step; returning false ends the path there (the result says so).
// `straight` marks an exact chord through constant n.
using ChordVisitor = std::function<bool(const PathState& from, const PathState& to, bool straight)>;

struct CurvedPathResult {
    PathState end;
    int64_t steps = 0;          // accepted steps (chords), straight ones included
    int64_t straightChords = 0; // of which exact straight stretches
    int64_t rejected = 0;       // RK45 trial steps whose error estimate exceeded the tolerance
    int64_t forcedSteps = 0;    // accepted at minStep despite the error estimate
    int64_t evaluations = 0;    // calls of IndexField::eval
    bool capped = false;        // maxSteps reached (or the field went non-finite) first
    bool stopped = false;       // the visitor ended the path
};

// Traces from `origin` along the unit `direction` for arc length `length` (m) at wavelength
// lambdaNm.
CurvedPathResult traceCurvedPath(const IndexField& field, const Vec3d& origin,
                                 const Vec3d& direction, double lambdaNm, double length,
                                 const CurvedPathSettings& settings,
                                 const ChordVisitor& visit = ChordVisitor());

}  // namespace mirage
