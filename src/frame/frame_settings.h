// The settings a frame request lays over a loaded scene (frame_request.h): resolution, samples,
// seed and passes from the command line, the quality presets, and the render in passes asked
// for by --passes, --time-limit and --noise-threshold. loadFrame (frame_load.h) applies them
// in that order; `mirage farm` and `mirage tradeoff` apply the first alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frame/frame_request.h"
#include "scene/scene.h"

namespace mirage {

// Applies the request's resolution, spp, seed, progress mode and passes (--aov) to `scene` (a
// bare VDB keeps its automatic camera framed for a new aspect ratio). Throws MirageError for a
// malformed --resolution or an unknown pass.
void applyFrameSettings(Scene& scene, const FrameRequest& request);

// `--quality draft|preview|final`: points on the measured speed↔accuracy curves
// (docs/performance.md, "Quality presets"). The photon integrator takes spp, photons and k; the
// others spp only.
struct QualityPreset {
    std::string name;
    int spp = 0;            // photon integrator: samples per pixel
    uint64_t photons = 0;   // photon integrator: photons emitted
    int k = 0;              // photon integrator: photons per estimate
    int pathSpp = 0;        // single / volpath: samples per pixel
    double sceneScale = 1;  // × the samples and photons a scene states (Scene::statedSpp)
    // × the passes `auto` made of film.spp on dense smoke (Scene::autoSet): measured on the
    // race scene, where one pass in 16 is the draft's error.
    double autoPassScale = 1;
};
const std::vector<QualityPreset>& qualityPresets();
// Throws MirageError naming the presets for an unknown name.
const QualityPreset& qualityPreset(const std::string& name);
// Sets the preset's values on `scene` for `integrator`, except the keys that an explicit
// --set in `overrides` names (film.spp, render.photons, render.k): those win, and so does a k
// the scene file states (the bandwidth its author chose). Where the scene file states
// film.spp or render.photons, that is what the scene needs for a clean picture
// (the preview preset) and the preset scales it (draft ¼, preview 1, final 4: the final
// preset is the 4× render the noise checks compare against); elsewhere the preset's own
// measured values apply. A curved-camera scene that asks for 16 samples gets 4, 16 or 64. A
// stated render.k is kept at every preset. A scene in passes (stated, or made by `auto` on
// dense smoke) has its passes scaled, each keeping its photon map's photons; auto's passes
// by their own measured scale (draft 1/16, preview 1, final 4).
void applyQualityPreset(Scene& scene, const QualityPreset& preset, const std::string& integrator,
                        const std::vector<std::string>& overrides);

// --passes, --time-limit, --noise-threshold, --coarse: a render in passes (render/passes.h). An
// explicit --spp then caps the samples per pixel (whole passes: the count rounds up to a pass;
// fewer samples than a pass make one pass of that many). Any of the three replaces the passes a
// scene states ([render] passes): a time or noise target is not also cut at the scene's count.
void applyPassOptions(const FrameRequest& request, PassSettings* passes);

}  // namespace mirage
