// The integrator interface: radiance along a camera ray at a path's wavelengths. The single-
// scattering integrator lives beside it; the photon mapper and the reference volumetric path
// tracer implement the same interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/rng.h"
#include "render/render_scene.h"
#include "transport/tracking.h"

namespace mirage {

// Per-thread state an integrator may use (allocated once per tile, reused per sample).
struct ThreadState {
    explicit ThreadState(const RenderScene& scene) : tracking(scene.mediaPointers()) {}
    TrackingContext tracking;
};

struct RadianceSample {
    SampledSpectrum L;   // W·m⁻²·sr⁻¹·nm⁻¹
    float alpha = 0.f;   // 1 − transmittance of the ray (coverage)
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    // Called once before rendering (a photon mapper traces its photons here).
    virtual void preprocess(const RenderScene&) {}
    virtual RadianceSample Li(const RenderScene& scene, const Ray& ray,
                              const SampledWavelengths& w, Sampler& sampler,
                              ThreadState& ts) const = 0;
    // Paths cut at the depth cap so far (a bias, reported in the summary).
    virtual uint64_t cappedPaths() const { return 0; }
};

// Single scattering plus emission: delta tracking along the camera ray, next-event estimation
// to every light with ratio-tracked shadow rays at the real scattering event. Unbiased for the
// single-scattered and emitted radiance.
std::unique_ptr<Integrator> makeSingleScatterIntegrator();

// The reference spectral volumetric path tracer (volpath.cpp); paths longer than maxDepth
// scattering events are cut and counted.
std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth = 10000);

// By name ("single", "volpath"); throws MirageError listing the names for anything else.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth = 10000);
std::vector<std::string> integratorNames();

}  // namespace mirage
