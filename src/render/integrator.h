// The integrator interface: radiance along a camera ray at a path's wavelengths. The single-
// scattering integrator lives beside it; the photon mapper and the reference volumetric path
// tracer implement the same interface.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/spectral.h"
#include "film/aov.h"
#include "film/deep.h"
#include "photon/view_weight.h"
#include "render/render_scene.h"
#include "transport/scatter_point.h"
#include "transport/tracking.h"

namespace mirage {

class CameraRayData;
class CurvedTransport;
struct PhotonIntegratorSettings;

// What an integrator returns for one camera sample. Its passes and deep record go to the
// thread's (ThreadState::aov, deep), each contribution added once through the path's recorder
// (render/path_recorder.h).
struct RadianceSample {
    SampledSpectrum L;  // W·m⁻²·sr⁻¹·nm⁻¹
    float alpha = 0.f;  // 1 − transmittance of the ray (coverage)
    // Radiance already reduced to CIE XYZ in the film's normalisation (spectrumToXyz), added to
    // the pixel beside L: what a photon-map estimate gives, each photon at its own wavelength.
    Vec3 xyz;
};

// Per-thread state an integrator may use (allocated once per tile, reused per sample).
struct ThreadState {
    explicit ThreadState(const RenderScene& scene)
        : tracking(scene.mediaPointers()), holdouts(&scene.mediumHoldouts) {}
    TrackingContext tracking;
    // Per medium of `tracking`, whether the render holds it out (RenderScene::mediumHoldouts).
    const std::vector<bool>* holdouts;
    // What lies in front of the ray an integrator is handed, at any wavelength, for the
    // estimates made at the photons' own wavelengths (photon/view_weight.h): the curved
    // camera's earlier chords. One (nothing) for a camera ray.
    ViewWeight photonView;
    // The render passes of the sample being rendered; null when the render has none, and then
    // nothing below is touched.
    AovSample* aov = nullptr;
    DeepSample* deep = nullptr;       // the sample's deep record; null without deep output
    AovSample nestedAov;  // scratch: the passes of a nested estimate (PathRecorder::nested)
    // The data passes' record of the camera ray (render/camera_ray_data.h), null when no data
    // pass or deep output asks for it: an integrator hands it the collisions of its walk of the
    // camera ray and says how that walk ended.
    CameraRayData* cameraData = nullptr;
    std::vector<EmissionAt> emitted;  // scratch: a flight's emission per collision
    // Next-event estimation's parts per light-group slot (render/direct_light.h), when the
    // passes split light groups: the last estimate's, overwritten by the next.
    std::vector<SampledSpectrum> lightSplit;
    // A photon estimate's parts per light-group slot (XYZ, photon/photon_groups.h), likewise.
    std::vector<Vec3> lightSplitXyz;
    // Where a [refraction] field bends light: the field and walks the wrapped integrator bends
    // its shadow rays and scattered segments with (render/curved_transport.h), set by the curved
    // camera for each sample; null where light is straight.
    const CurvedTransport* curved = nullptr;
    // Zeroes the parts for the estimate about to be made; null when the render does not split.
    // Blackbody emission is filmed in its exact colour (render/achromatic_film.h): the recorder
    // adds each emission event's XYZ instead of its radiance at the sample's wavelengths.
    bool exactEmission = false;
    SampledSpectrum* startLightSplit() {
        if (!aov || aov->group.empty()) return nullptr;
        std::fill(lightSplit.begin(), lightSplit.end(), SampledSpectrum(0.f));
        return lightSplit.data();
    }
};

// What an integrator is. The scene loader (its check of [render] integrator, `mirage info`),
// the memory estimate and the quality presets ask this instead of comparing names.
struct IntegratorInfo {
    std::string name;
    std::string description;  // one line, for the command-line help and `mirage info`
    bool multipleScattering;  // follows light scattered more than once
    bool photonPass;          // traces photons first: the [render] photon keys apply, the memory
                              // estimate counts the maps, the presets set photons and k
    // Records each medium emission event with its temperature (PathRecorder::emittedInMedium),
    // so that a grey medium's blackbody is filmed in its exact colour (render/achromatic_film.h).
    bool exactEmission = false;
};
const std::vector<IntegratorInfo>& integratorInfos();
// The descriptor of `name`; throws MirageError naming the integrators for any other.
const IntegratorInfo& integratorInfo(const std::string& name);
std::string integratorNameList();  // "single, volpath, photon"

// What an integrator reports once it has rendered, for the summary and the EXR header.
struct IntegratorStats {
    uint64_t cappedPaths = 0;        // camera paths cut at a cap: a bias, however rare
    uint64_t cappedPhotonPaths = 0;  // photon paths cut at the bounce or collision cap
    uint64_t nonFinitePhotons = 0;   // photons dropped for a non-finite power or position
    std::string summary;             // one line of integrator-specific figures ("" for none)
    std::vector<std::pair<std::string, std::string>> metadata;  // EXR keys (mirage:<key>)
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual const IntegratorInfo& info() const = 0;
    virtual std::string name() const { return info().name; }
    // Called once before rendering (a photon mapper traces its photons here). frameSamples: the
    // frame's camera samples (pixels × samples per pixel), which a cache built per frame is
    // sized to (single scattering's light guide); 0 when unknown, and then none is built.
    virtual void preprocess(const RenderScene&, uint64_t /*frameSamples*/) {}
    void preprocess(const RenderScene& scene) { preprocess(scene, 0); }
    // A render in passes (render/passes.h) calls this before pass p = 0, 1, …, after
    // preprocess. What an integrator does here must depend on p alone (not on earlier passes
    // or the time), so that N passes give the same bits however they were reached; the
    // progressive photon mapper traces pass p's photon map with pass p's radii here.
    virtual void beginPass(const RenderScene&, int /*pass*/) {}
    virtual RadianceSample Li(const RenderScene& scene, const Ray& ray,
                              const SampledWavelengths& w, Sampler& sampler,
                              ThreadState& ts) const = 0;
    virtual IntegratorStats stats() const { return {}; }
    // Whether Li's radiance is a light's spectrum times what the scene does to it: no λ
    // dependence of the integrator's own (no photons at their own wavelengths, no dispersive
    // curved rays). Then a scene with nothing spectral in it is filmed without colour noise
    // (render/achromatic_film.h).
    virtual bool lightShapedRadiance() const { return false; }
};

// Single scattering plus emission: delta tracking along the camera ray, next-event estimation
// to every light with ratio-tracked shadow rays at the real scattering event. Unbiased for the
// single-scattered and emitted radiance. directLight = false leaves out the shadow rays (media
// and diffuse surfaces): emission alone, for a photon map that holds the direct light too.
std::unique_ptr<Integrator> makeSingleScatterIntegrator(bool directLight = true);

// The reference spectral volumetric path tracer (volpath.cpp); paths longer than maxDepth
// scattering events are cut and counted.
std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth = 10000);

// By name (integratorInfos()); throws MirageError listing the names for anything else.
// `photon` (render/photon_integrator.h) configures the photon integrator and is ignored by the
// others; without it, the photon integrator takes the default settings.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth = 10000);
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth,
                                           const PhotonIntegratorSettings& photon);

}  // namespace mirage
