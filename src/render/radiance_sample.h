// What an integrator returns for one camera sample, and the one place where every
// contribution is added to it: the beauty, and when the render asks for them the render
// passes (film/aov.h: tagged with a light-path class and a light group) and the deep samples
// (film/deep.h: placed along the camera ray). Without passes and deep output, adding is
// `L += c` as it always was, and the beauty keeps its bits.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "core/light_path.h"
#include "core/math.h"
#include "core/spectral.h"
#include "film/aov.h"
#include "film/deep.h"
#include "transport/path_vertex.h"

namespace mirage {

// Where a camera path's contributions lie along the camera ray (deep output): at the distance
// of the event while the path has not scattered (past mirrors and glass the view goes on),
// then at its first scattering vertex, for everything the path gathers after it.
struct DeepView {
    float viewT = 0.f;  // distance along the camera's view to the current ray's origin
    DeepAt first{0.f, false};

    DeepAt at(const PathHistory& h, float t, bool surface) const {
        return h.vertices == 0 ? DeepAt{viewT + t, surface} : first;
    }
    // Call before the history records the vertex.
    void scatter(const PathHistory& h, float t, bool surface) {
        if (h.vertices == 0) first = {viewT + t, surface};
    }
    void specular(const PathHistory& h, float t) {
        if (h.vertices == 0) viewT += t;
    }
};

// Radiance gathered along the whole camera ray (a photon estimate): placed by the pixel.
constexpr DeepAt kUnplaced{std::numeric_limits<float>::quiet_NaN(), false};

struct RadianceSample {
    SampledSpectrum L;  // W·m⁻²·sr⁻¹·nm⁻¹
    float alpha = 0.f;  // 1 − transmittance of the ray (coverage)
    // Radiance already reduced to CIE XYZ in the film's normalisation (spectrumToXyz), added to
    // the pixel beside L: what a photon-map estimate gives, each photon at its own wavelength.
    Vec3 xyz;
    // The render passes and the deep record of this sample (ThreadState), or null.
    AovSample* aov = nullptr;
    DeepSample* deep = nullptr;

    // Every contribution enters here, once, with its light-path class (core/light_path.h),
    // light-group slot (film/aov.h) and place along the camera ray.
    void add(const SampledSpectrum& c, LightPath p, int group, DeepAt at) {
        L += c;
        if (deep) deep->radiance.push_back({at, c, Vec3(0.f)});
        if (!aov) return;
        aov->addPath(c, p);
        aov->addGroup(c, group);
    }
    // Next-event estimation's light `lit` reaching a vertex of throughput beta: its light
    // groups are the parts the estimate left in `split` (ThreadState::lightSplit).
    void addLit(const SampledSpectrum& beta, const SampledSpectrum& lit, LightPath p,
                const std::vector<SampledSpectrum>& split, DeepAt at) {
        const SampledSpectrum c = beta * lit;
        L += c;
        if (deep) deep->radiance.push_back({at, c, Vec3(0.f)});
        if (!aov) return;
        aov->addPath(c, p);
        aov->addGroups(beta, split);
    }
    // A photon estimate (XYZ); two of them at one surface, summed before they are added.
    // `groups`: the estimate split by light group (photon/photon_groups.h), when the render
    // asks for light groups (groupSlots() entries), else null.
    void addXyz(const Vec3& c, LightPath p, DeepAt at, const std::vector<Vec3>* groups) {
        xyz += c;
        if (deep) deep->radiance.push_back({at, SampledSpectrum(0.f), c});
        if (!aov) return;
        aov->addPathXyz(c, p);
        if (groups) aov->addGroupXyz(*groups);
    }
    void addXyz(const Vec3& a, LightPath pa, const Vec3& b, LightPath pb, DeepAt at,
                const std::vector<Vec3>* groups) {
        xyz += a + b;
        if (deep) deep->radiance.push_back({at, SampledSpectrum(0.f), a + b});
        if (!aov) return;
        aov->addPathXyz(a, pa);
        aov->addPathXyz(b, pb);
        if (groups) aov->addGroupXyz(*groups);
    }
    // The path's estimate from what it gathered (PathThroughput::estimate), for every part.
    void finish(const PathThroughput& path) {
        L = path.estimate(L);
        if (aov) aov->forEachRadiance([&](SampledSpectrum& s) { s = path.estimate(s); });
        if (deep)
            for (DeepSample::Radiance& r : deep->radiance) r.L = path.estimate(r.L);
    }
};

}  // namespace mirage
