// [refraction] → Refraction (refraction_loader.h documents the keys).
#include "scene/refraction_loader.h"

#include <cstdio>

#include "medium/air_index.h"

namespace mirage {

std::shared_ptr<const Refraction> readRefraction(const TableReader& t) {
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
        AtmosphereSettings a;
        a.groundHeight = t.getNumber("ground_height", 0.0, -1e7, 1e7);
        for (const TableReader& l : t.tables("inversion")) {
            InversionLayer layer;
            layer.base = l.getNumber("base");
            layer.top = l.getNumber("top");
            layer.deltaT = l.getNumber("delta_t", 0.0, -200.0, 2000.0);
            layer.blend = l.getNumber("blend", 1.0, 1e-6, 1e6);
            if (!(layer.top > layer.base)) l.fail("top", "expected top > base");
            l.finish();
            a.inversions.push_back(layer);
        }
        std::snprintf(buf, sizeof buf, "US Standard Atmosphere 1976 with %zu inversion layer(s)",
                      a.inversions.size());
        r->description = buf;
        r->field = std::make_shared<AtmosphereIndexField>(a);
    } else {
        t.fail("profile", "unknown profile '" + profile + "'; expected linear or atmosphere");
    }
    r->path.tolerance = t.getNumber("tolerance", 1e-6, 1e-14, 1.0);
    const double maxStep = t.getNumber("max_step", 0.0, 0.0, 1e9);
    if (maxStep > 0) r->path.maxStep = maxStep;
    r->maxArc = float(t.getNumber("max_distance", 1000.0, 1e-6, 1e9));
    t.finish();
    return r;
}

}  // namespace mirage
