// Scene::physics: the physics terms a scene switches on, each with the reason `mirage info`
// gives. A scene pays only for what it uses (docs/design.md), and this is where it says which.
#include <cmath>
#include <cstdio>

#include "core/text.h"
#include "medium/ocean_components.h"
#include "render/achromatic_film.h"
#include "render/lamp_sampling.h"
#include "render/light_lobes.h"
#include "render/sun_shade.h"
#include "scene/scene.h"
#include "volume/grid_expression.h"

namespace mirage {

namespace {

// What the scene's media switch on, each with the reason `mirage info` gives (the first
// shader that switches it on).
struct MediaPhysics {
    bool scatter = false, spectral = false, emission = false;
    std::string emitWhy, spectralWhy, fluorescenceWhy;
};

std::string spectralReason(const ShaderDesc& s) {
    std::string why = "shader '" + s.name + "' has wavelength-dependent σ";
    for (const auto& c : s.components)
        if (c.kind != ComponentKind::Linear)
            return why + " (component '" + c.name + "' is of kind " + componentKindName(c.kind) +
                   ")";
    return why;
}

std::string fluorescenceReason(const ShaderDesc& s, const MediumComponent& c) {
    char buf[160];
    if (c.emissionMatrix)
        std::snprintf(buf, sizeof buf,
                      "' re-emits with Γ = %g by an excitation–emission matrix (%zu rows%s)",
                      c.quantumEfficiency, c.emissionMatrix->rows.size(),
                      c.antiStokes ? ", anti-Stokes allowed" : "");
    else
        std::snprintf(buf, sizeof buf, "' re-emits with Γ = %g at %g nm (FWHM %g nm%s)",
                      c.quantumEfficiency, c.emissionPeakNm, c.emissionFwhmNm,
                      c.antiStokes ? ", anti-Stokes allowed" : "");
    return "shader '" + s.name + "' component '" + c.name + buf +
           ": Γ roulette after absorption, re-emissions stored as isotropic photons, spectral "
           "transport";
}

MediaPhysics mediaPhysics(const RenderScene& render) {
    MediaPhysics m;
    for (const auto& medium : render.media) {
        const ShaderDesc& s = medium->shader();
        for (const auto& c : s.components) m.scatter |= c.sigmaS.maxValue() > 0;
        if (s.spectralCoefficients() && m.spectralWhy.empty()) m.spectralWhy = spectralReason(s);
        m.spectral |= s.spectralCoefficients();
        for (const auto& c : s.components)
            if (c.fluorescent() && m.fluorescenceWhy.empty())
                m.fluorescenceWhy = fluorescenceReason(s, c);
        if (!m.fluorescenceWhy.empty() && m.spectralWhy.empty())
            m.spectralWhy = "fluorescence changes wavelengths (" + s.name + ")";
        m.spectral |= s.fluorescent();
        if (s.emission) {
            m.emission = true;
            m.emitWhy = "shader '" + s.name + "' emits as a blackbody at grid slot '" +
                        s.emission->temperatureGrid + "'";
        }
    }
    return m;
}

// How volpath's camera rays find a dome (render/lamp_sampling.h).
std::string skyPointsReason(const RenderScene& render, const std::string& integrator) {
    if (integrator != "volpath" || !samplesSky(render)) return "";
    return skyPointsFork(render)
               ? "; camera rays draw 4 points per medium for the dome by a march of their optical "
                 "depth, weighed against delta tracking's, each lit one on a thin ray starting a "
                 "path of its own (guided where paths are)"
               : "; camera rays draw 4 points per medium for the dome by a march of their optical "
                 "depth, weighed against delta tracking's";
}

PhysicsTerm singleScatteringTerm(const RenderScene& render, const std::string& integrator,
                                 const MediaPhysics& m) {
    return {"single scattering", m.scatter && !render.lights.empty(),
            !m.scatter              ? "no component scatters (σs = 0)"
            : render.lights.empty() ? "no lights"
                                    : "σs > 0 and " + std::to_string(render.lights.size()) +
                                          " light(s): shadow rays by ratio tracking" +
                                          skyPointsReason(render, integrator)};
}

// Where volpath's continuations head towards lamps inside the media (render/light_lobes.h).
std::string lampLobesReason(const RenderScene& render, const std::string& integrator) {
    if (integrator != "volpath") return "";
    const size_t lamps = lampsInMedia(render).size();
    if (lamps == 0) return "";
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "; %.0f %% of the continuations from medium vertices drawn towards the %zu "
                  "lamp(s) inside the media (angle to the lamp uniform), weighed with the phase "
                  "function's",
                  100.f * kLampLobeShare, lamps);
    return buf;
}

// Where volpath's paths are guided by lobe walks towards lights of a narrow lobe
// (render/light_lobes.h): a forward medium and a lamp, a sun, or a sky map with a sun. Walks are
// straight: a [refraction] field turns them off.
std::string lobeWalksReason(const Scene& scene, const std::string& integrator) {
    if (integrator != "volpath" || scene.refraction || !guidesPaths(scene.render)) return "";
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "; paths guided (a forward phase function): %.0f %% of medium vertices "
                  "start a straight walk towards the lamps and suns",
                  100.f * lobeWalkStart(scene.render));
    return buf;
}

// Where volpath's vertices draw a sky's samples at a rate from the sun's shade
// (render/sun_shade.h).
std::string sunShadeReason(const RenderScene& render, const std::string& integrator) {
    if (integrator != "volpath" || !SunShade::sunOf(render)) return "";
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "; medium vertices draw the sky's own samples at a rate from the sun's optical "
                  "depth over the media (a %d³ grid: every vertex where it is lit, %.0f %% past "
                  "depth %.1f)",
                  SunShade::kResolution, 100.f * SunShade::kLeastRate,
                  std::log(SunShade::kRateScale / SunShade::kLeastRate));
    return buf;
}

// Emissive media light the scene too: their light scatters like a light's (photons from the
// medium in the photon pass, emission at every collision in volpath).
PhysicsTerm multipleScatteringTerm(const Scene& scene, const std::string& integrator,
                                   const MediaPhysics& m) {
    const bool follows = integratorInfo(integrator).multipleScattering;
    bool multiple = follows && m.scatter && (!scene.render.lights.empty() || m.emission);
    return {"multiple scattering", multiple,
            !follows   ? "integrator '" + integrator + "' computes single scattering only"
            : multiple ? "integrator '" + integrator + "' follows paths of up to " +
                             std::to_string(scene.maxDepth) + " scattering events" +
                             (m.emission ? ", emitted light included" : "") +
                             lampLobesReason(scene.render, integrator) +
                             lobeWalksReason(scene, integrator) +
                             sunShadeReason(scene.render, integrator)
                       : "nothing scatters or nothing lights the scene"};
}

PhysicsTerm surfacesTerm(const RenderScene& render) {
    if (!render.hasSurfaces()) return {"surfaces", false, "no [[shape]]"};
    const GeometryScene& g = *render.geometry;
    size_t triangles = 0;
    for (size_t i = 0; i < g.shapeCount(); ++i) triangles += g.shape(int(i)).triangles;
    return {"surfaces", true,
            std::to_string(g.shapeCount()) + " shape(s), " + std::to_string(triangles) +
                " triangle(s), " + std::to_string(g.materialCount()) + " material(s): Embree BVH"};
}

PhysicsTerm expressionsTerm(const std::vector<VolumeRecord>& volumes) {
    std::vector<std::string> runs;
    for (size_t i = 0; i < volumes.size(); ++i)
        for (const ExpressionRecord& e : volumes[i].expressions)
            runs.push_back("volume " + std::to_string(i) + " (" + e.origin + ", " +
                           e.expression.where.str() + ") " + describeAccess(e.access));
    if (runs.empty()) return {"grid expressions", false, "no expression: grids are used as stored"};
    return {"grid expressions", true,
            "OpenVDB AX on the grids before NanoVDB conversion, active voxels only: " +
                joinList(runs, "; ")};
}

// Which paths bend: camera rays always; photons when the photon integrator runs and the field
// curves within the scene's bounds (photonsCurve), which then drops shadow rays.
PhysicsTerm curvedPathsTerm(const Scene& scene, const std::string& integrator) {
    if (!scene.refraction)
        return {"curved paths", false, "no refractive-index field: straight-line tracking"};
    const Refraction& refraction = *scene.refraction;
    const Bounds3 b = scene.render.bounds();
    char bound[96] = "";
    if (!b.empty())
        std::snprintf(bound, sizeof bound, "; |grad n| <= %.3g /m over the scene's bounds",
                      refraction.field->gradientBound(Vec3d(b.lo), Vec3d(b.hi)));
    const bool photonPass = integratorInfo(integrator).photonPass;
    const bool photons = photonPass && photonsCurve(refraction.field.get(), b);
    return {
        "curved paths", true,
        "[refraction]: " + refraction.description + bound +
            ". Camera rays bend (Dormand-Prince RK5(4)), straight beyond " +
            std::to_string(int(refraction.maxArc)) + " m of path; " +
            (photons      ? "photons follow curved paths too, and direct light comes from the "
                            "photon maps (no shadow rays)"
             : photonPass ? "photons straight (the field is flat within the scene)"
             : !refraction.bendTransport ? "shadow rays and scattered paths straight ([refraction] "
                                           "curved_transport = false)"
             : integrator == "volpath"
                 ? "scattered paths and shadow rays to lights at infinity bend too (shadow "
                   "rays to lamps stay straight)"
                 : "shadow rays to lights at infinity bend too (shadow rays to lamps stay "
                   "straight)")};
}

// Emission, and how the integrator finds it: the photon pass emits from it; volpath's scattering
// vertices sample it as a light by line integration (render/line_emission.h) and its flights
// draw a point towards it that shares their collisions' score (render/flight_emission.h),
// unless the scene says `[render] emission_sampling = "flight"`.
PhysicsTerm emissionTerm(const RenderScene& render, const std::string& integrator,
                         const MediaPhysics& m) {
    if (!m.emission) return {"emission", false, "no shader has an [emission] table"};
    std::string why = m.emitWhy;
    if (integratorInfo(integrator).photonPass) why += "; the photon pass emits from it ∝ 4π σa·Le";
    if (integrator == "volpath" && render.emissionSampling)
        why += std::string(m.scatter ? "; sampled as a light at every scattering vertex (line "
                                       "integration) and"
                                     : ";") +
               " by a point drawn along every flight, weighed against its collisions ([render] "
               "emission_sampling = \"line\")";
    else if (integrator == "volpath")
        why += "; found by the paths' flights alone ([render] emission_sampling = \"flight\")";
    return {"emission", true, why};
}

}  // namespace

std::vector<PhysicsTerm> Scene::physics() const {
    const MediaPhysics m = mediaPhysics(render);
    // A scene built in code may still say "auto"; a loaded one has been resolved.
    const std::string name = integrator == "auto" ? chooseIntegrator(*this).name : integrator;
    std::vector<PhysicsTerm> terms;
    terms.push_back(
        {"absorption", !render.media.empty(),
         render.media.empty() ? "no volumes" : std::to_string(render.media.size()) + " volume(s)"});
    terms.push_back(singleScatteringTerm(render, name, m));
    terms.push_back(multipleScatteringTerm(*this, name, m));
    terms.push_back(emissionTerm(render, name, m));
    terms.push_back({"spectral coefficients", m.spectral,
                     m.spectral ? m.spectralWhy
                                : "every σ is wavelength-independent: grey path (σ set once "
                                  "per medium, one grid lookup and one coefficient per "
                                  "component serve all 4 wavelengths; only light and emission "
                                  "spectra are sampled)"});
    std::string colourWhy;
    const bool colourSampled = sampledColour(render, integratorInfo(name), &colourWhy);
    terms.push_back({"sampled colour", colourSampled, colourWhy});
    terms.push_back(surfacesTerm(render));
    terms.push_back({"fluorescence", !m.fluorescenceWhy.empty(),
                     m.fluorescenceWhy.empty() ? "no shader declares a quantum efficiency"
                                               : m.fluorescenceWhy});
    terms.push_back(expressionsTerm(volumes));
    terms.push_back(curvedPathsTerm(*this, name));
    return terms;
}

}  // namespace mirage
