// Relative intensity by direction and photon directions drawn by it (emission_profile.h).
#include "light/emission_profile.h"

#include <algorithm>

#include "core/sampling.h"
#include "light/ies_file.h"

namespace mirage {

namespace {

// The table an IES profile is drawn by: cells uniform in φ and in cos γ (equal solid angle,
// 4π / (width × height) each), 2 × 2 points per cell. ~0.03 s to build at load.
constexpr int kPhiCells = 256, kCosCells = 128, kSub = 2;

// Every cell keeps this share of the peak in the table, so a direction the table's points
// missed (a sliver of light between them) still has a density and the estimate stays
// unbiased: there the photon's weight is large instead of the light being lost.
constexpr double kFloor = 1e-3;

float degrees(float rad) { return rad * (180.f / kPi); }

// The IES file's C = 0° direction about the axis: world +x made normal to it, or +z when the
// axis lies within ~25° of the x axis.
Vec3 referenceAzimuth(const Vec3& axis) {
    const Vec3 x = std::abs(axis.x) < 0.9f ? Vec3(1.f, 0.f, 0.f) : Vec3(0.f, 0.f, 1.f);
    return normalize(x - axis * dot(axis, x));
}

// The unit direction of the point (u, v) of the table: φ = 2π u, cos γ = 1 − 2v.
Vec3 tableDirection(const Frame& frame, float u, float v) {
    const float cosG = 1.f - 2.f * v, sinG = safeSqrt(1.f - cosG * cosG);
    return frame.toWorld(sphericalDirection(sinG, cosG, 2.f * kPi * u));
}

}  // namespace

EmissionProfile::EmissionProfile(const ProfileDesc& d)
    : mAxis(normalize(d.axis)), mSpot(d.spot), mIes(d.ies) {
    if (mSpot) {
        const float outer = clamp(d.outerDeg, 0.01f, 180.f);
        const float inner = clamp(d.innerDeg, 0.f, outer);
        mCosOuter = std::cos(radians(outer));
        mCosInner = std::cos(radians(inner));
        // Ω_f = ∫ f dω. The falloff is a smoothstep in cos θ, and ∫₀¹ (3t² − 2t³) dt = 1/2, so
        // the ramp counts for half its width in cos θ: Ω_f = 2π(1 − (cos θi + cos θo)/2).
        mSolidAngle = 2.f * kPi * (1.f - 0.5f * (mCosInner + mCosOuter));
    }
    mFrame.n = mAxis;
    mFrame.s = referenceAzimuth(mAxis);
    mFrame.t = cross(mAxis, mFrame.s);
    if (mIes) tabulate();
}

// Type C angles of w: γ from the axis (the nadir), C about it from the frame's s (C = 90° along
// axis × s).
float EmissionProfile::iesValue(const Vec3& w, float cosT) const {
    const float gamma = degrees(std::acos(clamp(cosT, -1.f, 1.f)));
    const float c = degrees(std::atan2(dot(w, mFrame.t), dot(w, mFrame.s)));
    return mIes->candela(gamma, c) / mIes->peak();
}

// Ω_f by the midpoint rule over the table's points (each 4π / points of solid angle), and the
// table of cell weights: each cell's largest f, over the floor.
void EmissionProfile::tabulate() {
    std::vector<double> cells(size_t(kPhiCells) * kCosCells);
    double sum = 0.0;
    const int n = kSub * kSub;
    for (int v = 0; v < kCosCells; ++v)
        for (int u = 0; u < kPhiCells; ++u) {
            double largest = 0.0;
            for (int k = 0; k < n; ++k) {
                const float pu = (u + (k % kSub + 0.5f) / kSub) / kPhiCells;
                const float pv = (v + (k / kSub + 0.5f) / kSub) / kCosCells;
                const double f = eval(tableDirection(mFrame, pu, pv));
                sum += f;
                largest = std::max(largest, f);
            }
            cells[size_t(v) * kPhiCells + u] = largest + kFloor;
        }
    mSolidAngle = float(4.0 * kPi * sum / (double(n) * kPhiCells * kCosCells));
    mTable = std::make_shared<Distribution2D>(cells, kPhiCells, kCosCells);
}

float EmissionProfile::aimedShare(const AimCone& aim) const {
    const bool isotropic = !mSpot && !mIes;
    return isotropic && aim.valid ? 0.5f * (1.f - aim.cosMax) : 1.f;
}

// Isotropic: uniform in the aim cone (or the sphere), weight 1. A spot: uniform in the
// narrower of its own cone and the aim cone, of solid angle Ω_C, weight f Ω_C / Ω_f — mean 1
// over its own cone, the share of the power that can reach the scene over the aim cone. An
// IES profile: by its table, pdf_ω = pdf_uv / 4π, weight f / (pdf_ω Ω_f); not aimed.
bool EmissionProfile::sample(const AimCone& aim, float u1, float u2, Vec3* w, float* weight) const {
    if (mIes) {
        float u, v, pdf;
        mTable->sample(u1, u2, &u, &v, &pdf);
        *w = tableDirection(mFrame, u, v);
        *weight = pdf > 0.f ? eval(*w) * 4.f * kPi / (pdf * mSolidAngle) : 0.f;
    } else if (!mSpot) {
        *w = aim.valid ? sampleUniformCone(aim.axis, aim.cosMax, u1, u2)
                       : sampleUniformSphere(u1, u2);
        *weight = 1.f;
    } else if (aim.valid && aim.cosMax > mCosOuter) {
        *w = sampleUniformCone(aim.axis, aim.cosMax, u1, u2);
        *weight =
            falloff(dot(*w, mAxis)) * (1.f - aim.cosMax) / (1.f - 0.5f * (mCosInner + mCosOuter));
    } else {
        *w = sampleUniformCone(mAxis, mCosOuter, u1, u2);
        *weight =
            falloff(dot(*w, mAxis)) * (1.f - mCosOuter) / (1.f - 0.5f * (mCosInner + mCosOuter));
    }
    return *weight > 0.f;
}

}  // namespace mirage
