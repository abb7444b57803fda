// Procedural assets → OpenVDB files, and the one OpenVDB file writer (tools/vdb_writer.h) that
// the test grids share. The tools' only translation unit that includes OpenVDB.
#include "tools/asset_writer.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/text.h"
#include "tools/dense_vdb.h"
#include "tools/vdb_writer.h"
#include "volume/vdb_format.h"

namespace mirage {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

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
// amplitude, normalised by the amplitude sum and clamped to [-1, 1].
class Fbm {
public:
    Fbm(uint64_t seed, uint64_t stream, int octaves) : mOctaves(std::min(octaves, 6)) {
        for (int o = 0; o < mOctaves; ++o)
            mNoise[o] = GradientNoise(hashCombine(hashCombine(mix64(seed), stream), uint64_t(o)));
    }
    float operator()(const Vec3& p) const {
        float sum = 0.f, amp = 1.f, norm = 0.f, f = 1.f;
        for (int o = 0; o < mOctaves; ++o) {
            sum += amp * mNoise[o](p.x * f, p.y * f, p.z * f);
            norm += amp;
            amp *= 0.5f;
            f *= 2.f;
        }
        return clamp(sum / norm, -1.f, 1.f);
    }

private:
    int mOctaves;
    GradientNoise mNoise[6];
};

float smoothstep(float a, float b, float x) {
    float t = clamp((x - a) / (b - a), 0.f, 1.f);
    return t * t * (3.f - 2.f * t);
}

// ---- Asset fields ------------------------------------------------------------------------

struct AssetField {
    std::vector<std::string> grids;  // names, in output order
    std::vector<std::string> units;
    Vec3 lo, hi;                                    // object-space domain (m)
    std::function<void(const Vec3&, float*)> eval;  // writes one value per grid
    // The flow (m/s) where the first grid is non-zero, written as the collocated vec3s grid
    // `vel` (Houdini's convention) for motion blur; empty for a still asset.
    std::function<Vec3(const Vec3&)> velocity;
};

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
        const float cx = kWander * t * mWanderX(Vec3(0.f, 0.7f * p.y, 0.f));
        const float cz = kWander * t * mWanderZ(Vec3(0.f, 0.7f * p.y, 3.1f));
        float dx = p.x - cx, dz = p.z - cz;
        const float warp = kWarpBase + (kWarpTop - kWarpBase) * t;
        float radius = mRBase + (mRTop - mRBase) * t;
        // Outside the plume even at its widest and after the largest warp: skip the noise.
        const float reach = 1.3f * radius + warp;
        if (dx * dx + dz * dz >= reach * reach) return 0.f;
        radius *= 1.f + 0.3f * mBillow(p * 1.8f);
        const Vec3 q = p * 2.5f;
        dx += warp * mWarpX(q);
        dz += warp * mWarpZ(q);
        *r2 = (dx * dx + dz * dz) / (radius * radius);
        if (*r2 >= 1.f) return 0.f;
        return (1.f - *r2) * (1.f - *r2);
    }

private:
    float mYBase, mRBase, mRTop;
    Fbm mWanderX, mWanderZ, mWarpX, mWarpZ, mBillow;
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
    a.velocity = plumeFlow(0.f, 0.12f, 0.27f, 1.2f, 0.25f, 0.3f);
    return a;
}

AssetField fireField(uint64_t seed) {
    auto plume = std::make_shared<Plume>(seed, 0.45f, 0.15f, 0.21f);
    auto detail = std::make_shared<Fbm>(seed, 5, 4);
    auto tongues = std::make_shared<Fbm>(seed, 6, 3);
    auto flicker = std::make_shared<Fbm>(seed, 7, 4);
    AssetField a;
    a.grids = {"density", "temperature", "flame"};
    a.units = {"unitless soot density (a shader scales it into sigma, 1/m)", "K",
               "unitless reaction intensity 0..1"};
    a.lo = Vec3(-0.5f, 0.f, -0.5f);
    a.hi = Vec3(0.5f, 2.f, 0.5f);
    a.eval = [plume, detail, tongues, flicker](const Vec3& p, float* out) {
        out[0] = out[1] = out[2] = 0.f;
        // Flames: a cone over a 0.3 m radius base whose height varies across the base
        // (tongues) and whose surface is displaced by noise (flicker).
        float flame = 0.f;
        const float rBase = 0.3f;
        const float base2 = p.x * p.x + p.z * p.z;
        if (p.y < 1.3f && base2 < (rBase + 0.06f) * (rBase + 0.06f)) {
            const float height = 0.9f * (1.f + 0.35f * (*tongues)(Vec3(p.x * 3.f, 0.f, p.z * 3.f)));
            const float n = (*flicker)(p * Vec3(4.f, 2.5f, 4.f));
            const float yw = p.y + 0.12f * n;
            if (yw > 0.f && yw < height) {
                const float radius = rBase * (1.f - yw / height);
                const float r = std::sqrt(base2) + 0.05f * n;
                const float r2 = r * r / (radius * radius);
                if (r2 < 1.f)
                    flame = clamp((1.f - r2) * (1.f - 0.5f * yw / height) * (0.9f + 0.6f * n), 0.f,
                                  1.f) *
                            smoothstep(0.f, 0.04f, p.y);
            }
        }
        // Smoke above the flames.
        float r2;
        const float shape = plume->profile(p, &r2);
        float smoke = 0.f;
        if (shape > 0.f) {
            const float n = (*detail)(p * 5.f);
            smoke = shape * clamp(0.5f + 1.2f * n, 0.f, 1.f) * smoothstep(0.45f, 0.9f, p.y) *
                    (1.f - smoothstep(1.6f, 1.98f, p.y));
        }
        const float density = std::max(smoke, 0.08f * flame);
        if (density < 1e-3f && flame < 1e-3f) return;
        out[0] = density >= 1e-3f ? density : 0.f;
        out[2] = flame >= 1e-3f ? flame : 0.f;
        // 1800 K at full reaction. The luminous zone of a sooty flame is hot nearly throughout
        // (soot at ~1300–1700 K), cooling only at its thin edge: T rises as flame^0.3 (1520 K
        // at half reaction), not linearly, or most of the flame would glow 10 stops dimmer
        // than its core. The smoke cools from ~700 K above the flames to ambient.
        const float tSmoke = 300.f + 400.f * shape * clamp(1.6f - p.y, 0.f, 1.f);
        out[1] = std::max(300.f + 1500.f * std::pow(flame, 0.3f), tSmoke);
    };
    // Flames rise faster than the smoke they feed (buoyancy of ~1800 K gas).
    const auto smokeFlow = plumeFlow(0.45f, 0.15f, 0.21f, 1.5f, 0.2f, 0.25f);
    a.velocity = [smokeFlow](const Vec3& p) {
        const Vec3 v = smokeFlow(p);
        return p.y < 1.f ? Vec3(v.x, v.y * (2.f - p.y), v.z) : v;
    };
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
    return a;
}

}  // namespace

// ---- Writing -----------------------------------------------------------------------------

void initOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

uint32_t vdbCompressionFlags(const std::string& name, const std::string& path) {
    if (name == "blosc")
        // Without Blosc, zip: but OpenVDB never zips fog volumes (Archive::setGridCompression),
        // so those are then stored with the active-mask encoding only.
        return (openvdb::io::Archive::hasBloscCompression() ? openvdb::io::COMPRESS_BLOSC
                                                            : openvdb::io::COMPRESS_ZIP) |
               openvdb::io::COMPRESS_ACTIVE_MASK;
    if (name == "zip") return openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK;
    if (name == "none") return openvdb::io::COMPRESS_NONE;
    fail(path, "unknown compression '" + name + "' (valid: blosc, zip, none)");
}

void writeVdbFile(const std::string& path, const openvdb::GridPtrVec& grids,
                  const openvdb::MetaMap& meta, const std::string& compressionName) {
    const uint32_t compression = vdbCompressionFlags(compressionName, path);
    namespace fs = std::filesystem;
    const fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path() && !fs::is_directory(target.parent_path(), ec))
        fail(path, "cannot write: folder " + target.parent_path().string() + " does not exist");
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            try {
                openvdb::io::File file(tmp);
                file.setCompression(compression);
                file.write(grids, meta);
                file.close();
                vdbformat::scanFile(tmp);
            } catch (const std::exception& e) {
                fail(path, "cannot write: " + boundedMessage(e.what()));
            }
        },
        "cannot write");
}

openvdb::math::Transform::Ptr linearVdbTransform(double voxelSize, const Vec3d& origin) {
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
    return xform;
}

const std::vector<std::string>& proceduralAssetKinds() {
    static const std::vector<std::string> kinds = {"smoke", "fire", "fog-sphere", "ocean"};
    return kinds;
}

void writeProceduralAsset(const std::string& kind, const std::string& path, int resolution,
                          uint64_t seed) {
    AssetField field;
    if (kind == "smoke") {
        field = smokeField(seed);
    } else if (kind == "fire") {
        field = fireField(seed);
    } else if (kind == "fog-sphere") {
        field = fogSphereField();
    } else if (kind == "ocean") {
        field = oceanField(seed);
    } else {
        throw MirageError("unknown asset kind '" + boundedMessage(kind, 60) +
                          "' (valid kinds: " + joinList(proceduralAssetKinds()) + ")");
    }
    if (resolution < 8 || resolution > 1024)
        throw MirageError("asset resolution " + std::to_string(resolution) +
                          " is out of range (8 to 1024 voxels along the 2 m height)");
    initOpenVdb();

    // Voxel centres at lo + (i + ½) h: the voxels tile the domain exactly along y.
    const float h = 2.f / float(resolution);
    int n[3];
    for (int a = 0; a < 3; ++a)
        n[a] = std::max(1, int(std::lround((field.hi[a] - field.lo[a]) / h)));
    const Vec3 first = field.lo + Vec3(0.5f * h);
    auto xform = linearVdbTransform(h, Vec3d(first));
    const size_t numGrids = field.grids.size();
    std::vector<openvdb::FloatGrid::Ptr> grids;
    for (size_t g = 0; g < numGrids; ++g) {
        auto grid = openvdb::FloatGrid::create(0.f);
        grid->setName(field.grids[g]);
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        grid->setTransform(xform->copy());
        grid->insertMeta("units", openvdb::StringMetadata(field.units[g]));
        grids.push_back(grid);
    }

    openvdb::Vec3SGrid::Ptr vel;
    if (field.velocity) {
        vel = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
        vel->setName("vel");
        vel->setGridClass(openvdb::GRID_UNKNOWN);
        vel->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
        vel->setTransform(xform->copy());
        vel->insertMeta("units", openvdb::StringMetadata("m/s"));
    }

    // Slabs of z-slices evaluated in parallel, then inserted serially: the memory stays
    // bounded and the voxel values do not depend on the thread count or scheduling.
    constexpr int kSlab = 8;
    const size_t slice = size_t(n[0]) * n[1];
    std::vector<float> values(kSlab * slice * numGrids);
    std::vector<openvdb::FloatGrid::Accessor> accessors;
    for (auto& g : grids) accessors.push_back(g->getAccessor());
    std::optional<openvdb::Vec3SGrid::Accessor> velAcc;
    if (vel) velAcc.emplace(vel->getAccessor());
    for (int k0 = 0; k0 < n[2]; k0 += kSlab) {
        const int k1 = std::min(n[2], k0 + kSlab);
        tbb::parallel_for(tbb::blocked_range<int>(k0, k1), [&](const tbb::blocked_range<int>& r) {
            for (int k = r.begin(); k != r.end(); ++k)
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i) {
                        Vec3 p = first + Vec3(float(i), float(j), float(k)) * h;
                        float* out = &values[((size_t(k - k0) * n[1] + j) * n[0] + i) * numGrids];
                        field.eval(p, out);
                    }
        });
        for (int k = k0; k < k1; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const float* v = &values[((size_t(k - k0) * n[1] + j) * n[0] + i) * numGrids];
                    for (size_t g = 0; g < numGrids; ++g)
                        if (v[g] > 0.f) accessors[g].setValue(openvdb::Coord(i, j, k), v[g]);
                    // The flow where there is something to move (cheap: no noise).
                    if (vel && v[0] > 0.f) {
                        const Vec3 u =
                            field.velocity(first + Vec3(float(i), float(j), float(k)) * h);
                        velAcc->setValue(openvdb::Coord(i, j, k), openvdb::Vec3s(u.x, u.y, u.z));
                    }
                }
    }

    // Blocks whose voxels are all equal (the fog sphere's core) become single tiles.
    for (auto& g : grids) openvdb::tools::prune(g->tree());

    openvdb::MetaMap meta;
    meta.insertMeta("creator", openvdb::StringMetadata("Mirage " MIRAGE_VERSION " make-asset"));
    meta.insertMeta("mirage_asset_kind", openvdb::StringMetadata(kind));
    meta.insertMeta("mirage_asset_seed", openvdb::StringMetadata(std::to_string(seed)));
    meta.insertMeta("mirage_asset_resolution", openvdb::Int32Metadata(resolution));
    openvdb::GridPtrVec out(grids.begin(), grids.end());
    if (vel) out.push_back(vel);
    writeVdbFile(path, out, meta, "blosc");
}

// ---- Dense arrays (dense_vdb.h) ------------------------------------------------------------

namespace {

std::string numberText(double v) {
    std::ostringstream text;
    text << v;
    return text.str();
}

// The grid's shape and values, checked before OpenVDB sees them: the message names the grid.
void checkDenseGrid(const DenseGrid& g, const std::string& path) {
    const std::string what = "grid '" + g.name + "'";
    if (g.name.empty()) fail(path, "a dense grid has no name");
    if (!(g.voxelSize > 0.0) || !std::isfinite(g.voxelSize))
        fail(path, what + ": voxel size " + numberText(g.voxelSize) +
                       " is not a positive finite number of metres");
    if (g.components != 1 && g.components != 3)
        fail(path, what + ": " + std::to_string(g.components) +
                       " values per voxel; a grid holds 1 (a scalar) or 3 (a vector)");
    for (int a = 0; a < 3; ++a)
        if (g.dims[size_t(a)] < 1 ||
            int64_t(g.offset[size_t(a)]) + g.dims[size_t(a)] - 1 > int64_t(INT32_MAX))
            fail(path, what + ": its voxels along axis " + std::to_string(a) + " (" +
                           std::to_string(g.dims[size_t(a)]) + " from index " +
                           std::to_string(g.offset[size_t(a)]) +
                           ") are empty or leave OpenVDB's 32-bit index range");
    const int64_t n = g.dims[0] * g.dims[1] * g.dims[2] * g.components;
    for (int64_t i = 0; i < n; ++i)
        if (!std::isfinite(g.values[i])) {
            const int64_t voxel = i / g.components, z = voxel % g.dims[2],
                          y = voxel / g.dims[2] % g.dims[1], x = voxel / g.dims[2] / g.dims[1];
            fail(path, what + ": value " + numberText(double(g.values[i])) + " at [" +
                           std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
                           "] of the array is not finite");
        }
}

// The OpenVDB grid of one dense array: Dense's default layout (LayoutZYX) is z fastest, the
// array's C order; copyFromDense activates only the voxels that differ from the background 0.
template <typename GridT>
typename GridT::Ptr gridFromDense(const DenseGrid& g) {
    using Value = typename GridT::ValueType;
    const openvdb::Coord lo(g.offset[0], g.offset[1], g.offset[2]);
    const openvdb::Coord hi =
        lo + openvdb::Coord(int32_t(g.dims[0] - 1), int32_t(g.dims[1] - 1), int32_t(g.dims[2] - 1));
    // Dense reads through a non-const pointer but copyFromDense only reads.
    openvdb::tools::Dense<Value> dense(openvdb::CoordBBox(lo, hi),
                                       reinterpret_cast<Value*>(const_cast<float*>(g.values)));
    auto grid = GridT::create(openvdb::zeroVal<Value>());
    openvdb::tools::copyFromDense(dense, *grid, openvdb::zeroVal<Value>());
    grid->setName(g.name);
    grid->setTransform(linearVdbTransform(g.voxelSize, g.origin));
    if (g.components == 1)
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    else
        grid->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    return grid;
}

}  // namespace

void writeDenseVdbFile(const std::string& path, const std::vector<DenseGrid>& grids) {
    initOpenVdb();
    openvdb::GridPtrVec out;
    for (const DenseGrid& g : grids) {
        checkDenseGrid(g, path);
        if (g.components == 1)
            out.push_back(gridFromDense<openvdb::FloatGrid>(g));
        else
            out.push_back(gridFromDense<openvdb::Vec3SGrid>(g));
    }
    writeVdbFile(path, out, openvdb::MetaMap(), "blosc");
}

}  // namespace mirage
