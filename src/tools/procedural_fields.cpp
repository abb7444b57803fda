// The procedural fields of `mirage make-asset` (procedural_fields.h).
#include "tools/procedural_fields.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/rng.h"
#include "core/text.h"

namespace mirage {

namespace {

// ---- Noise -------------------------------------------------------------------------------
// Gradient noise (Perlin 2002, "Improving noise": quintic fade, gradients towards the 12 cube
// edges) with the lattice hashed by mix64 instead of a permutation table, so that the seed
// selects an independent field. Only +, −, × and floor: bit-identical on every IEEE platform.

class GradientNoise {
public:
    explicit GradientNoise(uint64_t key = 0) : mKey(key) {}

    float operator()(float x, float y, float z) const {
        const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
        const int ix = int(fx), iy = int(fy), iz = int(fz);
        const float tx = x - fx, ty = y - fy, tz = z - fz;
        const float u = fade(tx), v = fade(ty), w = fade(tz);
        auto g = [&](int dx, int dy, int dz) {
            return grad(ix + dx, iy + dy, iz + dz, tx - float(dx), ty - float(dy), tz - float(dz));
        };
        return lerp(w, lerp(v, lerp(u, g(0, 0, 0), g(1, 0, 0)), lerp(u, g(0, 1, 0), g(1, 1, 0))),
                    lerp(v, lerp(u, g(0, 0, 1), g(1, 0, 1)), lerp(u, g(0, 1, 1), g(1, 1, 1))));
    }

private:
    static float fade(float t) { return t * t * t * (t * (t * 6.f - 15.f) + 10.f); }

    float grad(int ix, int iy, int iz, float x, float y, float z) const {
        uint64_t h = mix64(mKey ^ (uint64_t(uint32_t(ix)) * 0x9e3779b97f4a7c15ull) ^
                           (uint64_t(uint32_t(iy)) * 0xc2b2ae3d27d4eb4full) ^
                           (uint64_t(uint32_t(iz)) * 0x165667b19e3779f9ull));
        switch (h % 12) {
            case 0:
                return x + y;
            case 1:
                return -x + y;
            case 2:
                return x - y;
            case 3:
                return -x - y;
            case 4:
                return x + z;
            case 5:
                return -x + z;
            case 6:
                return x - z;
            case 7:
                return -x - z;
            case 8:
                return y + z;
            case 9:
                return -y + z;
            case 10:
                return y - z;
            default:
                return -y - z;
        }
    }

    uint64_t mKey;
};

// Fractional Brownian motion: octaves of gradient noise at doubling frequency and halving
// amplitude, normalised by the amplitude sum and clamped to [-1, 1]. With `absolute`, octaves of
// |noise| instead, in [0, 1]: Perlin's turbulence (Perlin 1985, "An image synthesizer"), whose
// creases at the noise's zeros make the cusped, cauliflower billows of smoke when it displaces
// a surface.
class Fbm {
public:
    Fbm(uint64_t seed, uint64_t stream, int octaves, bool absolute = false)
        : mOctaves(std::min(octaves, 6)), mAbsolute(absolute) {
        for (int o = 0; o < mOctaves; ++o)
            mNoise[o] = GradientNoise(hashCombine(hashCombine(mix64(seed), stream), uint64_t(o)));
    }
    float operator()(const Vec3& p) const {
        float sum = 0.f, amp = 1.f, norm = 0.f, f = 1.f;
        for (int o = 0; o < mOctaves; ++o) {
            const float n = mNoise[o](p.x * f, p.y * f, p.z * f);
            sum += amp * (mAbsolute ? std::fabs(n) : n);
            norm += amp;
            amp *= 0.5f;
            f *= 2.f;
        }
        return clamp(sum / norm, -1.f, 1.f);
    }

private:
    int mOctaves;
    bool mAbsolute;
    GradientNoise mNoise[6];
};

float smoothstep(float a, float b, float x) {
    float t = clamp((x - a) / (b - a), 0.f, 1.f);
    return t * t * (3.f - 2.f * t);
}

// ---- Asset fields ------------------------------------------------------------------------

// The flow of a rising plume whose radius grows linearly from rBase at yBase to rTop at 2 m:
// an updraft `rise` (m/s) slowing by `slow` per metre of height, the self-similar spreading
// that keeps the plume's profile (radial speed ∝ r · dR/dy · v_y / R), and a swirl about the
// axis, solid-body within the plume, `swirl` m/s at its edge.
std::function<Vec3(const Vec3&)> plumeFlow(float yBase, float rBase, float rTop, float rise,
                                           float slow, float swirl) {
    return [=](const Vec3& p) {
        const float vy = rise * std::max(0.2f, 1.f - slow * p.y);
        const float t = clamp((p.y - yBase) / (2.f - yBase), 0.f, 1.f);
        const float radius = rBase + (rTop - rBase) * t;
        const float spread = (rTop - rBase) / (2.f - yBase) * vy / radius;  // 1/s
        const float omega = swirl / radius;                                 // rad/s
        return Vec3(spread * p.x - omega * p.z, vy, spread * p.z + omega * p.x);
    };
}

// Squared distance from the y axis to the nearest point of the box [lo, hi], in the xz plane.
float horizontalDistance2(const Vec3& lo, const Vec3& hi) {
    const float dx = std::max({0.f, lo.x, -hi.x}), dz = std::max({0.f, lo.z, -hi.z});
    return dx * dx + dz * dz;
}

// A rising plume of radius growing from rBase at yBase to rTop at y = 2 m, billowing (its
// radius swells and shrinks by up to 30% with low-frequency noise), whose axis wanders with
// height and whose edge is domain-warped more the higher it rises. Returns the radial profile
// (1 − r²)² in [0, 1] and r² (0 on the axis, 1 at the edge) through *r2. The plume stays
// within rTop·1.3 + kWander + kWarpTop of the y axis.
class Plume {
public:
    Plume(uint64_t seed, float yBase, float rBase, float rTop)
        : mYBase(yBase),
          mRBase(rBase),
          mRTop(rTop),
          mWanderX(seed, 1, 3),
          mWanderZ(seed, 2, 3),
          mWarpX(seed, 3, 3),
          mWarpZ(seed, 4, 3),
          mBillow(seed, 8, 2) {}

    static constexpr float kWander = 0.1f, kWarpBase = 0.03f, kWarpTop = 0.12f;  // m

    float profile(const Vec3& p, float* r2) const {
        *r2 = 1.f;
        if (p.y <= mYBase) return 0.f;
        const float t = (p.y - mYBase) / (2.f - mYBase);
        const float warp = kWarpBase + (kWarpTop - kWarpBase) * t;
        float radius = mRBase + (mRTop - mRBase) * t;
        // Outside the plume even at its widest and after the largest warp: skip the noise.
        const float reach = 1.3f * radius + warp;
        // The same test before the axis's wander is known, with the wander's bound (√2 kWander
        // t off the y axis) and a margin for rounding: the noise is skipped for most voxels.
        const float farthest = reach + 1.415f * kWander * t + 1e-3f;
        if (p.x * p.x + p.z * p.z >= farthest * farthest) return 0.f;
        const float cx = kWander * t * mWanderX(Vec3(0.f, 0.7f * p.y, 0.f));
        const float cz = kWander * t * mWanderZ(Vec3(0.f, 0.7f * p.y, 3.1f));
        float dx = p.x - cx, dz = p.z - cz;
        if (dx * dx + dz * dz >= reach * reach) return 0.f;
        radius *= 1.f + 0.3f * mBillow(p * 1.8f);
        const Vec3 q = p * 2.5f;
        dx += warp * mWarpX(q);
        dz += warp * mWarpZ(q);
        *r2 = (dx * dx + dz * dz) / (radius * radius);
        if (*r2 >= 1.f) return 0.f;
        return (1.f - *r2) * (1.f - *r2);
    }

    // False when no point of the box [lo, hi] can be inside the plume: the box lies below the
    // base, or farther from the y axis than the plume's reach at the box's top plus the
    // largest wander of its axis (the Fbm's are clamped to [-1, 1]).
    bool mayCover(const Vec3& lo, const Vec3& hi) const {
        if (hi.y <= mYBase) return false;
        const float t = clamp((hi.y - mYBase) / (2.f - mYBase), 0.f, 1.f);
        // The axis wanders by up to kWander along x and z at once: √2 kWander off the y axis.
        const float reach = 1.3f * (mRBase + (mRTop - mRBase) * t) + kWarpBase +
                            (kWarpTop - kWarpBase) * t + 1.415f * kWander;
        return horizontalDistance2(lo, hi) <= reach * reach * 1.01f;
    }

private:
    float mYBase, mRBase, mRTop;
    Fbm mWanderX, mWanderZ, mWarpX, mWarpZ, mBillow;
};

// Flames: a cone over a disc of radius rBase on the ground whose height varies across the base
// (tongues, up to ±35 % of `height`) and whose surface is displaced by noise (flicker): by up
// to `lift` m along y and `edge` m outwards. Returns the reaction intensity in [0, 1], highest
// on the axis near the base. No flame above yMax (m) or beyond rBase + edge + 0.01 m.
class Flames {
public:
    struct Shape {
        float rBase, height, yMax, lift, edge;  // m
    };
    Flames(uint64_t seed, Shape shape)
        : mShape(shape), mTongues(seed, 6, 3), mFlicker(seed, 7, 4) {}

    float operator()(const Vec3& p) const {
        const Shape& s = mShape;
        const float base2 = p.x * p.x + p.z * p.z;
        const float reach = s.rBase + s.edge + 0.01f;
        if (p.y >= s.yMax || base2 >= reach * reach) return 0.f;
        const float height = s.height * (1.f + 0.35f * mTongues(Vec3(p.x * 3.f, 0.f, p.z * 3.f)));
        const float n = mFlicker(p * Vec3(4.f, 2.5f, 4.f));
        const float yw = p.y + s.lift * n;
        if (yw <= 0.f || yw >= height) return 0.f;
        const float radius = s.rBase * (1.f - yw / height);
        const float r = std::sqrt(base2) + s.edge * n;
        const float r2 = r * r / (radius * radius);
        if (r2 >= 1.f) return 0.f;
        return clamp((1.f - r2) * (1.f - 0.5f * yw / height) * (0.9f + 0.6f * n), 0.f, 1.f) *
               smoothstep(0.f, 0.04f, p.y);
    }

    // The reach of the flames: every flame lies below yMax within rBase + edge of the y axis.
    bool mayCover(const Vec3& lo, const Vec3& hi) const {
        const float reach = mShape.rBase + mShape.edge + 0.01f;
        return lo.y < mShape.yMax && horizontalDistance2(lo, hi) < reach * reach;
    }

private:
    Shape mShape;
    Fbm mTongues, mFlicker;
};

AssetField smokeField(uint64_t seed) {
    auto plume = std::make_shared<Plume>(seed, 0.f, 0.12f, 0.27f);
    auto detail = std::make_shared<Fbm>(seed, 5, 4);
    AssetField a;
    a.grids = {"density", "temperature"};
    a.units = {"unitless (a shader scales it into sigma, 1/m)", "K"};
    a.lo = Vec3(-0.6f, 0.f, -0.6f);
    a.hi = Vec3(0.6f, 2.f, 0.6f);
    a.eval = [plume, detail](const Vec3& p, float* out) {
        out[0] = out[1] = 0.f;
        float r2;
        const float shape = plume->profile(p, &r2);
        if (shape <= 0.f) return;
        const float n = (*detail)(p * 5.f);
        const float fade = smoothstep(0.f, 0.12f, p.y) * (1.f - smoothstep(1.3f, 1.98f, p.y));
        const float density = shape * clamp(0.5f + 1.5f * n, 0.f, 1.3f) * fade;
        if (density < 1e-3f) return;
        out[0] = density;
        // Hot core near the source cooling with height and towards the edge: 300–900 K.
        const float heat = (1.f - r2) * (1.f - r2) * (1.f - r2) * (1.f - 0.35f * p.y);
        out[1] = 300.f + 600.f * clamp(heat * (0.9f + 0.3f * n), 0.f, 1.f);
    };
    a.mayCover = [plume](const Vec3& lo, const Vec3& hi) { return plume->mayCover(lo, hi); };
    a.velocity = plumeFlow(0.f, 0.12f, 0.27f, 1.2f, 0.25f, 0.3f);
    return a;
}

// The smoke plume flowing past a ball of radius kBallRadius on its axis at kBallCentre (m). Each
// point outside the ball reads the plume where its streamline was before the ball deflected it:
// in potential flow past a sphere the Stokes stream function ψ = ½ U ρ² (1 − a³/r³) (Lamb 1932,
// §96; ρ the distance from the axis through the centre, r from the centre) is constant along a
// streamline, so the plume's lateral offset there was ρ∞ = ρ √(1 − a³/r³): the smoke parts about
// the ball, its axis sheet spread thin over the ball's surface, and closes behind it. Potential
// flow has no wake; smoke does: above the ball's equator, within the ball's radius widening by
// 0.3 per radius of height, the smoke is thinned by up to kWakeThinning, recovering over
// kWakeLength. Only the plume's lateral offset changes (each point keeps its height): the plume
// varies slowly with height. Still: no `vel`.
constexpr float kBallRadius = 0.1f, kWakeThinning = 0.85f, kWakeLength = 0.45f;  // m
const Vec3 kBallCentre(0.f, 0.75f, 0.f);

AssetField smokePastSphereField(uint64_t seed) {
    AssetField a = smokeField(seed);
    a.velocity = nullptr;
    a.eval = [plume = a.eval](const Vec3& p, float* out) {
        out[0] = out[1] = 0.f;
        const Vec3 d = p - kBallCentre;
        const float r = length(d), a3 = kBallRadius * kBallRadius * kBallRadius;
        if (r <= kBallRadius) return;
        const float shrink = std::sqrt(1.f - a3 / (r * r * r));
        plume(Vec3(kBallCentre.x + d.x * shrink, p.y, kBallCentre.z + d.z * shrink), out);
        if (d.y <= 0.f || out[0] <= 0.f) return;
        const float rho = std::sqrt(d.x * d.x + d.z * d.z);
        const float width = kBallRadius * (1.f + 0.3f * d.y / kBallRadius);
        out[0] *= 1.f - kWakeThinning * (1.f - smoothstep(0.6f * width, width, rho)) *
                            std::exp(-d.y / kWakeLength);
    };
    // ρ∞ ≤ ρ: smoke reaches farther from the axis near the ball than the plume does, by
    // 1/√(1 − a³/r³). Boxes within 5 radii of the ball may hold it; beyond, that factor is below
    // 1.004, inside the margin of the plume's own test.
    a.mayCover = [plumeCover = a.mayCover](const Vec3& lo, const Vec3& hi) {
        const Vec3 nearest(clamp(kBallCentre.x, lo.x, hi.x), clamp(kBallCentre.y, lo.y, hi.y),
                           clamp(kBallCentre.z, lo.z, hi.z));
        return length(nearest - kBallCentre) < 5.f * kBallRadius || plumeCover(lo, hi);
    };
    return a;
}

// A fire's grids over the box [lo, hi]: soot density, temperature (K) and reaction intensity.
AssetField fireGrids(const Vec3& lo, const Vec3& hi) {
    AssetField a;
    a.grids = {"density", "temperature", "flame"};
    a.units = {"unitless soot density (a shader scales it into sigma, 1/m)", "K",
               "unitless reaction intensity 0..1"};
    a.lo = lo;
    a.hi = hi;
    return a;
}

// One voxel of a fire's grids from its smoke density, its flame's reaction intensity and the
// smoke's own temperature (K). The flames hold a little soot (8 % of their intensity). 1800 K
// at full reaction: the luminous zone of a sooty flame is hot nearly throughout (soot at
// ~1300–1700 K), cooling only at its thin edge, so T rises as flame^0.3 (1520 K at half
// reaction), not linearly, or most of the flame would glow 10 stops dimmer than its core.
void writeFireVoxel(float smoke, float flame, float smokeKelvin, float* out) {
    const float density = std::max(smoke, 0.08f * flame);
    if (density < 1e-3f && flame < 1e-3f) return;
    out[0] = density >= 1e-3f ? density : 0.f;
    out[2] = flame >= 1e-3f ? flame : 0.f;
    out[1] = std::max(300.f + 1500.f * std::pow(flame, 0.3f), smokeKelvin);
}

AssetField fireField(uint64_t seed) {
    auto plume = std::make_shared<Plume>(seed, 0.45f, 0.15f, 0.21f);
    auto detail = std::make_shared<Fbm>(seed, 5, 4);
    auto flames = std::make_shared<Flames>(seed, Flames::Shape{0.3f, 0.9f, 1.3f, 0.12f, 0.05f});
    AssetField a = fireGrids(Vec3(-0.5f, 0.f, -0.5f), Vec3(0.5f, 2.f, 0.5f));
    a.eval = [plume, detail, flames](const Vec3& p, float* out) {
        out[0] = out[1] = out[2] = 0.f;
        const float flame = (*flames)(p);
        // Smoke above the flames.
        float r2;
        const float shape = plume->profile(p, &r2);
        float smoke = 0.f;
        if (shape > 0.f) {
            const float n = (*detail)(p * 5.f);
            smoke = shape * clamp(0.5f + 1.2f * n, 0.f, 1.f) * smoothstep(0.45f, 0.9f, p.y) *
                    (1.f - smoothstep(1.6f, 1.98f, p.y));
        }
        // The smoke cools from ~700 K above the flames to ambient.
        writeFireVoxel(smoke, flame, 300.f + 400.f * shape * clamp(1.6f - p.y, 0.f, 1.f), out);
    };
    // Flames rise faster than the smoke they feed (buoyancy of ~1800 K gas).
    const auto smokeFlow = plumeFlow(0.45f, 0.15f, 0.21f, 1.5f, 0.2f, 0.25f);
    // Flames only below 1.3 m within 0.36 m of the axis; smoke only inside the column.
    a.mayCover = [plume, flames](const Vec3& lo, const Vec3& hi) {
        return flames->mayCover(lo, hi) || plume->mayCover(lo, hi);
    };
    a.velocity = [smokeFlow](const Vec3& p) {
        const Vec3 v = smokeFlow(p);
        return p.y < 1.f ? Vec3(v.x, v.y * (2.f - p.y), v.z) : v;
    };
    return a;
}

// The demo's fire-and-smoke plume: flames licking up from a 0.44 m wide fire bed feed a column of
// smoke that widens as it rises and rolls into a rounded cap. Its surface is pyroclastic — the
// column's level set displaced by turbulence — so it breaks into the cusped billows of real
// smoke, which a density merely modulated by noise (`smoke`, `fire`) does not show.
//   `density`     unitless soot density ≤ 1, sharp-edged billows with softer wisps.
//   `temperature` K: 300 + 1500 K × flame^0.3 in the flames, the smoke ~700 K just above them.
//   `flame`       unitless reaction intensity 0..1.
AssetField plumeField(uint64_t seed) {
    struct Parts {
        Flames flames;
        Fbm wanderX, wanderZ, billow, wisps, turbulence;
    };
    auto parts = std::make_shared<Parts>(
        Parts{Flames(seed, Flames::Shape{0.22f, 0.8f, 1.3f, 0.25f, 0.1f}), Fbm(seed, 12, 3),
              Fbm(seed, 13, 3), Fbm(seed, 14, 2), Fbm(seed, 15, 4), Fbm(seed, 16, 5, true)});
    // The column's radius (m): 0.1 m above the flames, widening, swelling under the cap.
    const auto radius = [](float y) {
        return 0.08f + 0.12f * y + 0.1f * std::exp(-8.f * (y - 1.4f) * (y - 1.4f));
    };
    // The cap's centre height and half-height (m): its displaced top stays below
    // kTop + kReach · kCap = 1.94 m, inside the 2 m domain.
    constexpr float kTop = 1.45f, kCap = 0.3f;
    // The displaced edge's farthest, in radii: 1 + 0.55 × 0.8 + 0.18 (turbulence ≤ 1, billow ≤ 1);
    // a point farther out has s < 0 below.
    constexpr float kReach = 1.65f;
    constexpr float kWander = 0.08f;  // the axis's largest offset (m)
    AssetField a = fireGrids(Vec3(-0.8f, 0.f, -0.8f), Vec3(0.8f, 2.f, 0.8f));
    a.eval = [parts, radius](const Vec3& p, float* out) {
        out[0] = out[1] = out[2] = 0.f;
        const float flame = parts->flames(p);
        float smoke = 0.f;
        const float r = radius(p.y);
        const float reach = kReach * r + 1.415f * kWander;
        if (p.y > 0.4f && p.x * p.x + p.z * p.z < reach * reach) {
            const float t = p.y / 2.f;
            const float dx = p.x - kWander * t * parts->wanderX(Vec3(0.f, 0.8f * p.y, 0.f));
            const float dz = p.z - kWander * t * parts->wanderZ(Vec3(0.f, 0.8f * p.y, 3.1f));
            // Distance from the axis in radii, and above the cap's centre in half-heights: the
            // column's top is the upper half of an ellipsoid, not the box's lid.
            const float above = std::max(0.f, (p.y - kTop) / kCap);
            const float d = std::sqrt((dx * dx + dz * dz) / (r * r) + above * above);
            // The surface moves out by turbulence and by a slow billow of the whole column.
            const Vec3 q = p * Vec3(4.f, 3.f, 4.f);
            const float s =
                1.f - d + 0.55f * (parts->turbulence(q) - 0.2f) + 0.18f * parts->billow(p * 1.2f);
            const float body = smoothstep(0.f, 0.22f, s) * (0.75f + 0.25f * parts->wisps(p * 9.f));
            smoke = body * smoothstep(0.4f, 0.9f, p.y);
        }
        writeFireVoxel(smoke, flame, 300.f + 400.f * smoke * clamp(1.2f - p.y, 0.f, 1.f), out);
    };
    a.mayCover = [parts, radius](const Vec3& lo, const Vec3& hi) {
        // The radius grows with height but for the cap's swell, which adds at most 0.1 m.
        const float reach = kReach * (0.08f + 0.12f * hi.y + 0.1f) + 1.415f * kWander;
        return parts->flames.mayCover(lo, hi) ||
               (hi.y > 0.4f && horizontalDistance2(lo, hi) < reach * reach * 1.01f);
    };
    a.velocity = plumeFlow(0.4f, 0.13f, 0.42f, 1.5f, 0.2f, 0.25f);
    return a;
}

AssetField fogSphereField() {
    AssetField a;
    a.grids = {"density"};
    a.units = {"unitless (a shader scales it into sigma, 1/m)"};
    a.lo = Vec3(-1.f, 0.f, -1.f);
    a.hi = Vec3(1.f, 2.f, 1.f);
    a.eval = [](const Vec3& p, float* out) {
        const float r = length(p - Vec3(0.f, 1.f, 0.f));
        out[0] = 1.f - smoothstep(0.6f, 1.f, r);
    };
    return a;
}

// A phytoplankton plume in sea water: chlorophyll a (mg/m³) welling up from a patch on the
// floor and spreading as it rises, its edge and interior broken up by noise (blooms are
// patchy), over a clear-water background of 0 (the shader adds pure water everywhere). Peak
// ~10 mg/m³, bloom waters; the plume's rim is ~0.1–1 mg/m³, open-ocean values.
AssetField oceanField(uint64_t seed) {
    auto plume = std::make_shared<Plume>(seed, 0.f, 0.3f, 0.7f);
    auto patches = std::make_shared<Fbm>(seed, 9, 4);
    AssetField a;
    a.grids = {"chlorophyll"};
    a.units = {"mg/m^3 (chlorophyll a)"};
    a.lo = Vec3(-1.f, 0.f, -1.f);
    a.hi = Vec3(1.f, 2.f, 1.f);
    a.eval = [plume, patches](const Vec3& p, float* out) {
        out[0] = 0.f;
        float r2;
        const float shape = plume->profile(p, &r2);
        if (shape <= 0.f) return;
        const float n = (*patches)(p * 3.f);
        const float chl =
            10.f * shape * clamp(0.55f + 1.2f * n, 0.f, 1.f) * (1.f - smoothstep(1.6f, 1.98f, p.y));
        out[0] = chl >= 0.01f ? chl : 0.f;
    };
    a.mayCover = [plume](const Vec3& lo, const Vec3& hi) { return plume->mayCover(lo, hi); };
    return a;
}

// A production-sized pyro cache: a billowing column 0.6 m wide at its base and 1.2 m at its
// top, filling a quarter of its 1.6 × 2 × 1.6 m box, so that the voxel count reaches 10^9 at
// ~1800 voxels along the height. Five octaves of noise per voxel (a billow of 2 that moves the
// column's edge, a detail of 3 inside it) keep a billion voxels within minutes. Stored as
// half floats, with `vel` at twice the voxel size, like the caches of production pyro solvers.
//   `density`     unitless, ≤ 1.2, the column's profile broken up by the detail noise.
//   `temperature` K, 300–1200 K in the column's core (the inner ~70 % of its radius), 0
//                 outside it: a subset of the density's voxels.
//   `vel`         m/s: an updraft of 1.5 m/s slowing with height, spreading, a 0.4 m/s swirl.
AssetField pyroField(uint64_t seed) {
    auto billow = std::make_shared<Fbm>(seed, 10, 2);
    auto detail = std::make_shared<Fbm>(seed, 11, 3);
    const auto radius = [](float y) { return 0.3f + 0.15f * clamp(y, 0.f, 2.f); };
    constexpr float kBillow = 0.35f;  // the edge moves by up to ±35 % of the radius
    AssetField a;
    a.grids = {"density", "temperature"};
    a.units = {"unitless (a shader scales it into sigma, 1/m)", "K"};
    a.lo = Vec3(-0.8f, 0.f, -0.8f);
    a.hi = Vec3(0.8f, 2.f, 0.8f);
    a.eval = [billow, detail, radius](const Vec3& p, float* out) {
        out[0] = out[1] = 0.f;
        const float d2 = p.x * p.x + p.z * p.z;
        const float reach = (1.f + kBillow) * radius(p.y);
        if (d2 >= reach * reach) return;
        const float r = radius(p.y) * (1.f + kBillow * (*billow)(p * 2.f));
        const float r2 = d2 / (r * r);
        if (r2 >= 1.f) return;
        const float n = (*detail)(p * 7.f);
        const float fade = smoothstep(0.f, 0.1f, p.y) * (1.f - smoothstep(1.85f, 1.99f, p.y));
        const float density = fade * clamp((1.f - r2) * 1.5f * (0.55f + 0.9f * n), 0.f, 1.2f);
        if (density < 1e-3f) return;
        out[0] = density;
        if (r2 < 0.5f) {
            const float heat = (1.f - 2.f * r2) * (1.f - 0.3f * p.y) * (0.9f + 0.3f * n);
            out[1] = 300.f + 900.f * clamp(heat, 0.f, 1.f);
        }
    };
    a.mayCover = [radius](const Vec3& lo, const Vec3& hi) {
        const float reach = (1.f + kBillow) * radius(hi.y) * 1.01f;
        return hi.y > 0.f && horizontalDistance2(lo, hi) < reach * reach;
    };
    a.velocity = plumeFlow(0.f, 0.3f, 0.6f, 1.5f, 0.2f, 0.4f);
    a.velocityScale = 2;
    a.half = true;
    return a;
}

}  // namespace

const std::vector<std::string>& proceduralAssetKinds() {
    static const std::vector<std::string> kinds = {"smoke",      "smoke-sphere", "fire", "plume",
                                                   "fog-sphere", "ocean",        "pyro"};
    return kinds;
}

AssetField proceduralField(const std::string& kind, uint64_t seed) {
    if (kind == "smoke") return smokeField(seed);
    if (kind == "smoke-sphere") return smokePastSphereField(seed);
    if (kind == "fire") return fireField(seed);
    if (kind == "plume") return plumeField(seed);
    if (kind == "fog-sphere") return fogSphereField();
    if (kind == "ocean") return oceanField(seed);
    if (kind == "pyro") return pyroField(seed);
    throw MirageError("unknown asset kind '" + boundedMessage(kind, 60) +
                      "' (valid kinds: " + joinList(proceduralAssetKinds()) + ")");
}

}  // namespace mirage
