// [refraction] → Refraction (refraction_loader.h documents the keys).
#include "scene/refraction_loader.h"

#include <cstdio>

#include "core/text.h"
#include "medium/air_index.h"
#include "medium/grid_index_field.h"

namespace mirage {

namespace {

// The temperature grid of volume `index` as a GridIndexField: T = max(ambient, offset +
// scale·value) per voxel (a fire cache's grid holds flame temperatures and 0 in the air around
// them; that air is at `ambient`), placed in the world by the volume's transform, which must be
// a uniform scale and a translation.
std::shared_ptr<const IndexField> gridField(const TableReader& t,
                                            const std::vector<std::unique_ptr<Medium>>& media,
                                            std::string* description) {
    const int64_t index = t.getInt("volume", 0, 0, 1 << 20);
    if (size_t(index) >= media.size())
        t.fail("volume", "expected the index of a [[volume]] (the scene has " +
                             std::to_string(media.size()) + ")");
    const Medium& m = *media[size_t(index)];
    const ShaderDesc& shader = m.shader();
    const EmissionSpec emission = shader.emission.value_or(EmissionSpec{});
    const std::string slot = t.getString("grid", emission.temperatureGrid.empty()
                                                     ? std::string("temperature")
                                                     : emission.temperatureGrid);
    const std::vector<std::string> slots = shader.gridSlots();
    size_t at = 0;
    while (at < slots.size() && slots[at] != slot) ++at;
    if (at >= slots.size() || at >= m.binding().grids().size()) {
        t.fail("grid", "volume " + std::to_string(index) + "'s shader '" + shader.name +
                           "' has no grid slot '" + slot + "'; its slots are: " + joinList(slots));
    }
    const double ambient = t.getNumber("ambient", air::kStamTp, 1.0, 1e5);
    const double scale = t.getNumber("temperature_scale", emission.temperatureScale, -1e6, 1e6);
    const double offset = t.getNumber("temperature_offset", emission.temperatureOffset, -1e6, 1e6);

    const Transform& xf = m.objectToWorld();
    const auto& L = xf.linear.m;
    const double s = L[0];
    if (!(s > 0) || L[4] != s || L[8] != s || L[1] != 0 || L[2] != 0 || L[3] != 0 || L[5] != 0 ||
        L[6] != 0 || L[7] != 0)
        t.fail("volume", "a temperature grid bends light only under a uniform scale and a "
                         "translation; volume " + std::to_string(index) +
                         " is rotated or scaled unevenly");
    DenseScalarGrid d = denseFromFloatGrid(m.binding().grids()[at], 0.f);
    for (float& v : d.values) v = float(std::max(ambient, offset + scale * double(v)));
    d.background = float(ambient);
    d.origin = Vec3d(xf.point(Vec3(d.origin)));
    d.voxelSize *= s;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "temperature grid '%s' of volume %lld (%dx%dx%d, ambient %g K): "
                  "n = 1 + (Tp/T)(n0 - 1), tricubic B-spline",
                  slot.c_str(), (long long)index, d.nx, d.ny, d.nz, ambient);
    *description = buf;
    return std::make_shared<GridIndexField>(std::move(d), GridIndexSettings{});
}

// The value of a key that names one of `choices` (its index), `def` when absent.
template <size_t N>
size_t readChoice(const TableReader& t, const std::string& key, const char* const (&choices)[N],
                  size_t def) {
    const std::string value = t.getString(key, choices[def]);
    std::string names;
    for (size_t i = 0; i < N; ++i) {
        if (value == choices[i]) return i;
        names += std::string(i ? ", " : "") + "\"" + choices[i] + "\"";
    }
    t.fail(key, "unknown value '" + value + "'; expected one of " + names);
}

// One [[refraction.inversion]] layer.
InversionLayer readInversion(const TableReader& l) {
    static const char* const kEdges[] = {"smooth", "fermi"};
    InversionLayer layer;
    layer.base = l.getNumber("base");
    layer.top = l.getNumber("top");
    layer.deltaT = l.getNumber("delta_t", 0.0, -200.0, 2000.0);
    layer.blend = l.getNumber("blend", 1.0, 1e-6, 1e6);
    layer.edge = LayerEdge(readChoice(l, "edge", kEdges, 0));
    if (!(layer.top > layer.base)) l.fail("top", "expected top > base");
    l.finish();
    return layer;
}

// profile = "atmosphere": the US Standard Atmosphere 1976, its layers, the Earth's shape and
// the air's dispersion.
AtmosphereSettings readAtmosphere(const TableReader& t) {
    static const char* const kEarths[] = {"flat", "round"};
    static const char* const kDispersions[] = {"cauchy", "edlen", "ciddor"};
    AtmosphereSettings a;
    a.groundHeight = t.getNumber("ground_height", 0.0, -1e7, 1e7);
    a.earth = EarthShape(readChoice(t, "earth", kEarths, 0));
    if (a.earth == EarthShape::Round) {
        a.earthRadius = t.getNumber("earth_radius", air::kMeanEarthRadius, 1e3, 1e9);
        a.shellDepth = t.getNumber("shell_depth", air::kShellDepth, 2 * air::kShellFade, 1e6);
    }
    a.dispersion = AirDispersion(readChoice(t, "dispersion", kDispersions, 0));
    for (const TableReader& l : t.tables("inversion")) a.inversions.push_back(readInversion(l));
    return a;
}

}  // namespace

std::shared_ptr<const Refraction> readRefraction(const TableReader& t,
                                                 const std::vector<std::unique_ptr<Medium>>& media) {
    auto r = std::make_shared<Refraction>();
    const std::string profile = t.getString("profile", "linear");
    char buf[200];
    if (profile == "linear") {
        const double n0 = t.getNumber("n0", 1.0, 1e-6, 100.0);
        const double k = t.getNumber("k", 0.0, -1e3, 1e3);
        r->field = std::make_shared<LinearIndexField>(n0, k);
        std::snprintf(buf, sizeof buf, "linear profile n = %g + %g·y", n0, k);
        r->description = buf;
    } else if (profile == "atmosphere") {
        const AtmosphereSettings a = readAtmosphere(t);
        // The defaults (flat, the paper's Cauchy) say nothing more.
        const bool cauchy = a.dispersion == AirDispersion::Cauchy;
        std::snprintf(
            buf, sizeof buf, "US Standard Atmosphere 1976 with %zu inversion layer(s)%s%s%s",
            a.inversions.size(), a.earth == EarthShape::Round ? " on a round Earth" : "",
            cauchy ? "" : ", dispersion of ", cauchy ? "" : airDispersionName(a.dispersion));
        r->description = buf;
        r->field = std::make_shared<AtmosphereIndexField>(a);
    } else if (profile == "grid") {
        r->field = gridField(t, media, &r->description);
    } else {
        t.fail("profile", "unknown profile '" + profile + "'; expected linear, atmosphere or grid");
    }
    r->path.tolerance = t.getNumber("tolerance", 1e-6, 1e-14, 1.0);
    const double maxStep = t.getNumber("max_step", 0.0, 0.0, 1e9);
    if (maxStep > 0) r->path.maxStep = maxStep;
    r->path.maxSteps = t.getInt("max_steps", r->path.maxSteps, 1, int64_t(1e12));
    r->path.capNearSurfaces = t.getBool("surface_step_cap", true);
    r->maxArc = float(t.getNumber("max_distance", 1000.0, 1e-6, 1e9));
    r->bendTransport = t.getBool("curved_transport", true);
    t.finish();
    return r;
}

}  // namespace mirage
