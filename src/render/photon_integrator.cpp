// Volumetric photon mapping (Jensen & Christensen 1998) with the beam radiance estimate
// (Jarosz, Zwicker & Jensen 2008).
//
// Two passes. preprocess() traces photons from the lights (photon/photon_pass.h), builds the
// kd-tree, and for the beam estimate the per-photon radii and the disc BVH. Li() then splits
// the radiance along a camera ray by the number of scattering events the light has undergone:
//  - emission and single scattering (light → one scattering on the camera ray → camera) come
//    from the single-scatter integrator, unchanged: delta tracking to a real scattering event
//    and next-event estimation with ratio-tracked shadow rays. It is spectral (4 hero
//    wavelengths) and unbiased, and it is where a photon map would be blurriest: direct light
//    has sharp shadows.
//  - multiple scattering (light that has scattered at least once before it scatters on the
//    camera ray) comes from the photons. The pass does not store a photon's first
//    interaction (storeFirstInteraction = false), so the map holds exactly the light that has
//    already scattered once, and nothing is counted twice.
// The photon part is CIE XYZ (volume_estimate.h), returned in RadianceSample::xyz; it is
// computed for every camera sample, so pixel filtering and the spectral noise of the single-
// scattered part average together.
//
// Curved light (docs/curved-light.md): where a [refraction] field bends paths inside the scene
// (photonsCurve), a straight shadow ray is no path of light. The photons then follow Fermat
// paths (photon_pass.h), the maps hold every interaction, the first included, and light that
// reaches a diffuse surface straight from a light; the single-scatter part keeps only emission.
//
// Progressive photon mapping (Knaus & Zwicker 2011; for beams, Jarosz et al. 2011): in a render
// in passes (render/passes.h) every pass p traces a photon map of its own (seed derived from the
// render seed and p) and the beam estimate's k-nearest disc radii shrink by the alpha rule,
// r²_{i+1} = r²_i (i + α)/(i + 1) for the 2-D kernel of a disc, i = p + 1, so the radii of pass p
// are those of one map times radiusScale(p). The film averages the passes (each adds the same
// samples per pixel), which is Knaus & Zwicker's estimator: the average of independent
// estimates whose bias (∝ r²) falls as N^-(1-α) while the variance of the average falls as
// N^-α; α = 2/3 balances the two, and the mean squared error falls as N^(-2/3) in the passes N.
// Pass 0 is the one-map render, so a render that is not in passes is unchanged. A later pass
// does not search its own k nearest photons for its radii: each photon takes the radius of the
// nearest photon of the first full pass (PhotonMap::radiiFrom), times radiusScale(p). The
// k-nearest search cost as much as tracing the pass's photons on dense smoke
// (docs/performance-history.md, "Renders that converge"), and that pass's radii are as good a
// bandwidth for a pass of as many photons; being independent of pass p's photons, they make each
// pass a kernel estimate of fixed bandwidth, whose blur the alpha rule shrinks as before.
//
// The first pass may trace fewer photons than the others ([render] first_pass_photons: `auto`
// makes it a fifth on dense smoke, so that a render of one pass costs about half as much for a
// little more error, docs/performance-history.md, "A smaller first pass"). It then searches its own
// k nearest photons, and so does pass 1, the first full pass, whose radii the passes after it read:
// a long render keeps the bandwidth it had. (Radii read off the sparser first map, scaled by the
// cube root of the photon counts, measured the same error at 16 passes within the seeds' spread,
// but they are smoothed over 5k of a full pass's photons.)
//
// The point estimate and the surface maps are averaged over passes too but keep their
// k-nearest radii (and the point estimate its pass-0 march step): their noise falls with
// the passes, their blur does not.
//
// Transmittance from the camera to each photon is the deterministic march of
// transport/ray_optical_depth.h at the photon's wavelength, done once per camera ray.
//
// Colour. Where nothing in the scene is spectral (render/achromatic_film.h: grey media, no
// surfaces or emission, up to 3 light colours) and no refraction field bends paths by
// wavelength, nothing a photon meets depends on its wavelength: each photon's flux is then its
// light's exact XYZ times its power (AchromaticFilm::xyzPerWatt, the expectation of its
// wavelength's colour), and the single-scattered part is filmed exactly by the renderer, so the
// image has no colour noise. The photons still draw their wavelength, so every other number of a
// photon's walk, and its power, are the spectral map's.
//
// Light emitted by the media themselves (fire) reaches the camera directly through the single-
// scatter integrator; the photon pass emits it too (photon/medium_emitter.h) and stores every
// scattering of it, the first included, so its scattered part comes from the photons.
//
// Surfaces. The single-scatter part follows mirrors and glass to the first diffuse surface or
// medium event and adds direct light there (NEE). The photon part walks the same kind of
// specular chain: along each segment the volume estimate (beam or point) up to the surface,
// and at the first diffuse surface x the surface estimates of photon/surface_estimate.h. Which
// light each map holds (photon/photon_pass.cpp, straight paths): the caustic map L S+ x; the
// global map every other path into x except L x (direct light, NEE's): its last vertex y a
// diffuse surface, a medium or a mirror behind one, or fire; the volume map every medium event
// but the first of light straight from a light. So at x (Jensen 2001, §9.1)
//     L(x) = L_direct (NEE) + L_caustic (caustic map at x) + L_indirect,
// and L_indirect, the global map's light, is either read straight from it at x
// (final_gather = 0: cheap, blotchy: its k-nearest disc shows) or gathered (final gather,
// Jensen 2001, §9.3.3): N rays drawn by x's BSDF (cosine-distributed, weight ρ/N each), each
// followed through mirrors and glass to the diffuse surface y it lands on, bringing back
//     T(x, y) [L_direct(y) (NEE) + caustic map(y) + global map(y)]
//     + along its flights: emission and single scattering (NEE, the single-scatter estimators)
//       and the volume estimate,
// the global map's set of paths one vertex further from x: nothing counted twice. A gather ray
// counts emission only where NEE does not sample the emitter, and never the lights at infinity
// (NEE at x has them). Where photons curve the global map holds direct light at x too, which
// no gather ray brings back: the gather is off.
// Each photon is weighted at its own wavelength by everything the chain puts in front of it
// (photon/view_weight.h): the transmittance of the segments before, a tinted mirror's
// reflectance, and, behind a dispersive glass, a kernel that keeps only light near the hero
// wavelength whose direction the chain follows. A curved camera ray's earlier chords reach the
// estimate the same way (ThreadState::photonView). Emissive meshes and quads are lights
// (light/surface_light.h): NEE samples them and they emit photons.
#include "render/photon_integrator.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/clock.h"
#include "core/error.h"
#include "film/exr_header.h"
#include "photon/beam_estimate.h"
#include "photon/photon_pass.h"
#include "photon/surface_estimate.h"
#include "render/achromatic_film.h"
#include "render/camera_path.h"
#include "transport/path_vertex.h"

namespace mirage {

namespace {

// Progressive photon mapping's α (see the top of the file).
constexpr double kProgressiveAlpha = 2.0 / 3.0;

// Pass p's disc radii over pass 0's: ∏_{i=1..p} ((i + α)/(i + 1))^(1/2).
float radiusScale(int pass) {
    double r2 = 1.0;
    for (int i = 1; i <= pass; ++i) r2 *= (double(i) + kProgressiveAlpha) / double(i + 1);
    return float(std::sqrt(r2));
}

// The photon pass p of a render in passes (p = 0: the one of a render not in passes). Its seed
// is derived from the render seed so that photon i and pixel i (both keyed (seed, index, 0) in
// the counter-based sampler) do not share numbers; pass p > 0 derives its own from that. Where
// paths curve (photonsCurve) photons follow Fermat paths and every interaction is stored, the
// first included (see preprocess()).
PhotonPassSettings passSettings(const PhotonIntegratorSettings& s, const RenderScene& scene,
                                int p) {
    PhotonPassSettings pass = s;  // the tracing settings as the user set them
    pass.photons = s.photonsOfPass(p);
    pass.seed = hashCombine(s.seed, 0x70686f746f6eull);  // "photon"
    if (p > 0) pass.seed = hashCombine(pass.seed, uint64_t(p));
    pass.storeFirstInteraction = false;
    if (photonsCurve(s.field.get(), scene.bounds())) {
        // A photon's flight needs no more path than a few crossings of the scene: an
        // escaping photon otherwise walks the whole max_distance in chords.
        const Vec3 diag = scene.bounds().diagonal();
        pass.curvedMaxArc = std::min(s.curvedMaxArc, 2.f * length(diag));
        pass.storeFirstInteraction = true;
    } else {
        pass.field = nullptr;
    }
    // One progress bar, the first pass's: a render in passes reports each pass instead.
    pass.progress = p == 0 ? s.progress : Progress::Mode::Quiet;
    pass.shutterOpen = scene.camera.shutterOpen;  // photons sample times too (motion blur)
    pass.shutterClose = scene.camera.shutterClose;
    return pass;
}

// Scratch of one render thread, reused for every camera sample.
struct PhotonThreadState {
    explicit PhotonThreadState(const std::vector<const Medium*>& media)
        : depth(media), probe(media) {}
    RayOpticalDepth depth;
    ScatteringProbe probe;
    std::vector<BeamHit> hits;
    std::vector<PhotonNeighbour> neighbours;
    double estimateSeconds = 0;
    uint64_t estimates = 0;
};

class PhotonMapIntegrator : public Integrator {
public:
    explicit PhotonMapIntegrator(const PhotonIntegratorSettings& s)
        : mSettings(s), mSingle(makeSingleScatterIntegrator()) {}
    const IntegratorInfo& info() const override { return integratorInfo("photon"); }

    using Integrator::preprocess;
    void preprocess(const RenderScene& scene, uint64_t frameSamples) override {
        // A photon estimate gathers from every medium at a point alike: it cannot leave out a
        // holdout medium's in-scattering on the camera ray.
        for (size_t i = 0; i < scene.media.size(); ++i)
            if (scene.holdout(i))
                throw MirageError(
                    "a [[volume]] with holdout = true needs the single or volpath "
                    "integrator: photon estimates do not tell media apart");
        mMedia = scene.mediaPointers();
        mSlotOfLight.clear();
        for (size_t i = 0; i < scene.lights.size(); ++i)
            mSlotOfLight.push_back(scene.lightGroupSlot(i));
        mCurved = photonsCurve(mSettings.field.get(), scene.bounds());
        mXyzPerWatt.clear();
        if (const auto achromatic = AchromaticFilm::forScene(scene, *this))
            mXyzPerWatt = achromatic->xyzPerWattOfLights();
        // Curved light: where paths curve there are no (straight) shadow rays, so the maps hold
        // the first interaction and the light arriving straight at diffuse surfaces too, and the
        // single-scatter part keeps only emission (Gutierrez et al. 2005). Nothing is counted
        // twice: each scattering of light is in exactly one of the two parts.
        if (mCurved) mSingle = makeSingleScatterIntegrator(false);
        mSingle->preprocess(scene, frameSamples);
        Vec3 diag = scene.bounds().empty() ? Vec3(1.f) : scene.bounds().diagonal();
        mMaxRadius = mSettings.maxRadius > 0.f ? mSettings.maxRadius : 0.1f * length(diag);
        mThreads = std::make_unique<tbb::enumerable_thread_specific<PhotonThreadState>>(
            [this] { return PhotonThreadState(mMedia); });
        buildPass(scene, 0);
    }

    // The radiance is the light's spectrum times what the scene does to it (the renderer may
    // film it exactly, and the photons carry the light's colour: the top of the file), unless
    // a refraction field bends photons or camera chords by wavelength.
    bool lightShapedRadiance() const override {
        return !mSettings.field && mSingle->lightShapedRadiance();
    }

    // Pass p of a render in passes: its own photon map and radii (see the top of the file).
    void beginPass(const RenderScene& scene, int pass) override {
        if (pass != mPass) buildPass(scene, pass);
    }

    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out = mSingle->Li(scene, ray, w, sampler, ts);
        if (mThreads) mThreads->local().depth.setTimeOffset(ts.tracking.timeOffset());
        PathRecorder rec(&out, ts);
        if (scene.hasSurfaces()) {
            photonsAlongSpecularChain(scene, CameraPath(ray, w), sampler, ts, rec);
            return out;
        }
        if (!mPhotons || mPhotons->size() == 0) return out;

        const float u = sampler.get1D();  // the march's jitter, drawn whichever estimate is used
        PhotonThreadState& pt = mThreads->local();
        auto t0 = Clock::now();
        pt.depth.march(ray, ray.tMax);
        const PhotonGroups groups = rec.photonGroups(mSlotOfLight);
        rec.photonsInMedium(volumeEstimate(ray, ray.tMax, u, pt, ts.photonView, groups));
        pt.estimateSeconds += secondsSince(t0);
        ++pt.estimates;
        return out;
    }

    // The photon pass's counts, the summary line and the EXR keys; the render threads'
    // estimate time is summed now (call after rendering).
    IntegratorStats stats() const override {
        IntegratorStats s;
        s.cappedPaths = mSingle->stats().cappedPaths;
        s.cappedPhotonPaths = mStats.traced.cappedPaths;
        s.nonFinitePhotons = mStats.traced.nonFinite;
        uint64_t estimates = 0;
        PhotonStats p = mStats;
        if (mThreads)
            for (const PhotonThreadState& pt : *mThreads) {
                p.estimateSeconds += pt.estimateSeconds;
                estimates += pt.estimates;
            }
        s.metadata = p.metadata();
        s.summary = summaryLine(p, estimates);
        return s;
    }

private:
    // Traces pass p's photons and builds its maps and the estimate's structures, each step
    // timed (summed over passes) for the summary and the EXR header.
    void buildPass(const RenderScene& scene, int p) {
        // Pass 0 may come saved (--photons-file: the same photons, so the same bits); later
        // passes of a render in passes always trace their own.
        PhotonPassResult traced = p == 0 && mSettings.savedPass
                                      ? *mSettings.savedPass
                                      : tracePhotonIntegratorPass(scene, mSettings, p);
        PhotonMapLists& lists = traced.maps;
        mStats.traced.add(traced.stats);
        mPass = p;
        mRadiusScale = radiusScale(p);

        // The maps (kd-trees, per-photon XYZ and phase), then the estimate's own structures
        // (the beam estimator reads the volume map: dropped first). The first full pass's
        // volume map stays as the later passes' source of radii.
        mBeam.reset();
        if (mPhotonsAreSource) {
            mSourcePhotons = std::move(mPhotons);
            mPhotonsAreSource = false;
        }
        auto t0 = Clock::now();
        mGlobal = std::make_unique<SurfacePhotons>(std::move(lists.surfaceGlobal));
        mCaustic = std::make_unique<SurfacePhotons>(std::move(lists.surfaceCaustic));
        mPhotons = std::make_unique<VolumePhotons>(std::move(lists.volume), mMedia, mXyzPerWatt);
        mStats.photonMapBuildSeconds += secondsSince(t0);
        // Coincident photons must not get a zero disc (PhotonMap::photonRadii).
        const float minRadius = 1e-4f * mMaxRadius;
        const int k = mSettings.kOrDefault();
        if (mSettings.estimate == PhotonEstimate::Beam) {
            t0 = Clock::now();
            std::vector<float> radii =
                mSourcePhotons
                    ? mPhotons->map().radiiFrom(mSourcePhotons->map(), mSourceRadii, mMaxRadius)
                    : mPhotons->map().photonRadii(k, minRadius, mMaxRadius);
            if (!mSourcePhotons && mSettings.photonsOfPass(p) == mSettings.photons) {
                mSourceRadii = radii;
                mPhotonsAreSource = true;
            }
            for (float& r : radii) r *= mRadiusScale;
            mStats.photonRadiiSeconds += secondsSince(t0);
            t0 = Clock::now();
            mBeam = std::make_unique<BeamEstimator>(*mPhotons, std::move(radii));
            mStats.discBvhBuildSeconds += secondsSince(t0);
        } else if (p == 0) {
            mStep = mSettings.marchStep;
            if (!(mStep > 0.f)) {
                // Half the typical search radius: the estimate is a blur of that radius, so
                // steps of half of it sample it without aliasing (jittered per camera sample).
                t0 = Clock::now();
                std::vector<float> r = mPhotons->map().photonRadii(k, minRadius, mMaxRadius);
                mStats.photonRadiiSeconds += secondsSince(t0);
                if (r.empty()) {
                    mStep = mMaxRadius;
                } else {
                    std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
                    mStep = 0.5f * r[r.size() / 2];
                }
            }
        }
    }

    std::string summaryLine(const PhotonStats& p, uint64_t estimates) const {
        char buf[640];
        std::snprintf(
            buf, sizeof buf,
            "photons: %llu traced, %llu stored | photon pass %.2fs (%.2f M photons/s) "
            "| photon map build %.3fs, disc radii %.3fs, disc BVH build %.3fs | %s "
            "estimate %.2fs thread time (%.1f µs/ray, k %d, max radius %.3g m) | "
            "photon paths cut at max_depth %llu | from emissive media %llu (%.3g W)",
            (unsigned long long)p.traced.emitted, (unsigned long long)p.traced.stored,
            p.traced.seconds, p.photonsPerSecond() / 1e6, p.photonMapBuildSeconds,
            p.photonRadiiSeconds, p.discBvhBuildSeconds, mBeam ? "beam" : "point",
            p.estimateSeconds, estimates ? p.estimateSeconds / double(estimates) * 1e6 : 0.0,
            mSettings.kOrDefault(), double(mMaxRadius), (unsigned long long)p.traced.cappedPaths,
            (unsigned long long)p.traced.fromMedia, p.traced.mediumPower);
        std::string line = buf;
        if (mCurved) line += " | photons on curved paths (direct light from the photon maps)";
        if (!mXyzPerWatt.empty()) line += " | photons carry the light's XYZ (grey scene)";
        if (mPass > 0) {
            char progressive[160];
            std::snprintf(progressive, sizeof progressive,
                          " | progressive: %d photon maps, last disc radii × %.3g (alpha %.3g)",
                          mPass + 1, double(mRadiusScale), kProgressiveAlpha);
            line += progressive;
        }
        if (mGlobal && mCaustic && (mGlobal->size() + mCaustic->size()) > 0) {
            line += " | surface photons: " + std::to_string(mGlobal->size()) + " global, " +
                    std::to_string(mCaustic->size()) + " caustic";
            line += gatherRays() > 0 ? ", final gather " + std::to_string(gatherRays()) + " rays"
                                     : ", global map read directly";
        }
        return line;
    }

    bool hasVolumePhotons() const { return mPhotons && mPhotons->size() > 0; }
    int surfaceK() const { return mSettings.k > 0 ? mSettings.k : 32; }
    // Final gather rays per camera path (0: the global map read at the first diffuse surface).
    // Where photons curve the global map holds the direct light too, which no gather ray
    // brings back: the top of the file.
    int gatherRays() const { return mCurved ? 0 : mSettings.finalGather; }

    // The volume photons' in-scattered radiance along `ray` over (0, tEnd), XYZ: beam or point
    // estimate; pt.depth has been marched along the ray.
    Vec3 volumeEstimate(const Ray& ray, float tEnd, float u, PhotonThreadState& pt,
                        const ViewWeight& view, const PhotonGroups& groups) const {
        if (mBeam) return mBeam->estimate(ray, tEnd, pt.depth, &pt.hits, view, groups);
        const int k = mSettings.kOrDefault();
        pt.neighbours.resize(size_t(k));
        return pointEstimateAlongRay(*mPhotons, ray, pt.depth,
                                     PhotonSearch{k, mMaxRadius, pt.neighbours.data()},
                                     PointMarch{mStep, u, &pt.probe}, view, groups);
    }

    // The photon part with surfaces (see the top of the file), XYZ, into the sample: the
    // volume estimates along each segment of the specular chain the camera ray starts, then at
    // the first diffuse surface the surface maps' (or the final gather). Each photon is seen
    // through the chain before it (its view weight), the curved camera's chords included
    // (ts.photonView); β, the chain's throughput at the sample's wavelengths with its media's
    // transmittance, is what the final gather's spectral part is seen through.
    void photonsAlongSpecularChain(const RenderScene& scene, CameraPath chain, Sampler& sampler,
                                   ThreadState& ts, PathRecorder& rec) const {
        const float u = sampler.get1D();  // the point estimate's march jitter
        PhotonThreadState& pt = mThreads->local();
        auto t0 = Clock::now();
        ViewWeight view = ts.photonView;
        for (; chain.depth <= kMaxSpecularBounces; ++chain.depth) {
            const SurfaceAhead ahead = surfaceAhead(scene, chain.ray);
            pt.depth.march(chain.ray, ahead.tEnd);
            if (hasVolumePhotons()) {
                const PhotonGroups groups = rec.photonGroups(mSlotOfLight);
                rec.photonsInMedium(volumeEstimate(chain.ray, ahead.tEnd, u, pt, view, groups));
            }
            // A holdout: nothing behind it.
            if (!ahead.hit || rec.holdout(*scene.geometry, *ahead.hit)) break;
            const SurfaceHit& hit = *ahead.hit;
            const Material& mat = scene.geometry->materialAt(hit);
            if (!mat.specular()) {
                if (gatherRays() > 0)
                    finalGather(scene, chain, hit, mat, view, u, sampler, ts, pt, rec);
                else
                    photonsAtSurface(hit, -chain.ray.d, mat, view, pt, rec);
                break;
            }
            if (gatherRays() > 0) attenuateBeta(pt.depth, ahead.tEnd, &chain);
            attenuateView(pt.depth, ahead.tEnd, &view);
            BsdfSample bs;
            if (!continueAtSurface(mat, hit, chain.wavelengths, TransportMode::Radiance, sampler,
                                   &chain, &bs))
                break;
            weighSpecularVertex(mat, bs, chain.wavelengths, &view);
            if (view.zero()) break;
            rec.passedSpecular(hit.t);
        }
        pt.estimateSeconds += secondsSince(t0);
        ++pt.estimates;
    }

    // The surface maps' estimates at a diffuse surface the chain reached, seen along wo:
    // caustics from the caustic map, indirect light from the global map, each photon through
    // the chain (view) and the media of the chain's last segment (pt.depth).
    void photonsAtSurface(const SurfaceHit& hit, const Vec3& wo, const Material& mat,
                          const ViewWeight& view, PhotonThreadState& pt, PathRecorder& rec) const {
        const int k = surfaceK();
        pt.neighbours.resize(size_t(k));
        auto T = [&](float lambda) { return pt.depth.transmittance(hit.t, lambda) * view(lambda); };
        const PhotonGroups groups = rec.photonGroups(mSlotOfLight);
        const Vec3 caustic = mCaustic->estimate(hit.p, hit.ng, wo, mat, k, mMaxRadius,
                                                pt.neighbours.data(), T, groups);
        const Vec3 global = mGlobal->estimate(hit.p, hit.ng, wo, mat, k, mMaxRadius,
                                              pt.neighbours.data(), T, groups);
        rec.photonsAtSurface(caustic, global, hit.t);
    }

    // Final gather at the first diffuse surface x (the top of the file): the caustic map at x,
    // then N rays by x's BSDF, weight ρ(λ)/N each; their photons recorded as the global map's
    // would be, their spectral part by a branch of the path that scattered at x.
    void finalGather(const RenderScene& scene, const CameraPath& chain, const SurfaceHit& x,
                     const Material& mat, ViewWeight view, float u, Sampler& sampler,
                     ThreadState& ts, PhotonThreadState& pt, PathRecorder& rec) const {
        const int k = surfaceK();
        pt.neighbours.resize(size_t(k));
        const PhotonGroups groups = rec.photonGroups(mSlotOfLight);
        attenuateView(pt.depth, x.t, &view);
        CameraPath atX = chain;
        attenuateBeta(pt.depth, x.t, &atX);
        estimateInBeta(false, &atX.throughput);
        const Vec3 caustic = mCaustic->estimate(x.p, x.ng, -chain.ray.d, mat, k, mMaxRadius,
                                                pt.neighbours.data(), view, groups);
        const float perRay = 1.f / float(gatherRays());
        view.scale(perRay);
        view.multiply([&](float lambda) { return mat.albedo(lambda); });
        PathRecorder branch = rec.branch();
        branch.scatteredAtSurface(x.t);
        Vec3 gathered(0.f);
        for (int j = 0; j < gatherRays(); ++j) {
            CameraPath g = atX;
            if (!continueAtSurface(mat, x, g.wavelengths, TransportMode::Radiance, sampler, &g))
                continue;
            g.throughput.beta *= perRay;
            g.specularChain = false;
            PathRecorder rayRec = branch.branch();
            gathered += gatherRay(scene, g, view, u, sampler, ts, pt, rayRec, groups);
        }
        rec.photonsAtSurface(caustic, gathered, x.t);
    }

    // One gather ray, through media, mirrors and glass to a diffuse surface y: the light it
    // brings to x (the top of the file). Spectral, recorded through g's throughput by rec
    // (render/camera_path.h's estimators); photons, returned in XYZ through `view`.
    Vec3 gatherRay(const RenderScene& scene, CameraPath g, ViewWeight view, float u,
                   Sampler& sampler, ThreadState& ts, PhotonThreadState& pt, PathRecorder& rec,
                   const PhotonGroups& groups) const {
        Vec3 xyz(0.f);
        for (++g.depth; g.depth <= kMaxSpecularBounces; ++g.depth) {
            const SurfaceAhead ahead = surfaceAhead(scene, g.ray);
            if (!scatterAlongFlight(scene, ahead, nullptr, true, sampler, ts, g, rec)) break;
            pt.depth.march(g.ray, ahead.tEnd);
            if (hasVolumePhotons()) xyz += volumeEstimate(g.ray, ahead.tEnd, u, pt, view, groups);
            if (!ahead.hit) break;  // the lights at infinity: next-event estimation's at x
            const SurfaceHit& y = *ahead.hit;
            const Material& mat = gatherAtSurface(scene, y, true, sampler, ts, g, rec);
            attenuateView(pt.depth, y.t, &view);
            if (!mat.specular()) {
                const int k = surfaceK();
                pt.neighbours.resize(size_t(k));
                for (const SurfacePhotons* map : {mCaustic.get(), mGlobal.get()})
                    xyz += map->estimate(y.p, y.ng, -g.ray.d, mat, k, mMaxRadius,
                                         pt.neighbours.data(), view, groups);
                break;
            }
            const bool heroBefore = g.throughput.heroOnly;
            BsdfSample bs;
            if (!continueAtSurface(mat, y, g.wavelengths, TransportMode::Radiance, sampler, &g,
                                   &bs))
                break;
            estimateInBeta(heroBefore, &g.throughput);
            weighSpecularVertex(mat, bs, g.wavelengths, &view);
            if (view.zero()) break;
        }
        return xyz;
    }

    // The media of a segment the chain leaves: their transmittance at every wavelength.
    static void attenuateView(const RayOpticalDepth& depth, float tEnd, ViewWeight* view) {
        if (depth.grey()) {
            view->scale(depth.transmittance(tEnd, 550.f));
            return;
        }
        view->multiply([&](float lambda) { return depth.transmittance(tEnd, lambda); });
    }

    // The same at the sample's wavelengths, into the chain's β (the final gather's spectral
    // part).
    static void attenuateBeta(const RayOpticalDepth& depth, float tEnd, CameraPath* chain) {
        SampledSpectrum& beta = chain->throughput.beta;
        for (int i = 0; i < kSpectrumSamples; ++i)
            beta[i] *= depth.transmittance(tEnd, chain->wavelengths.lambda[i]);
    }

    // The gather records after the camera path's estimate was taken (rec.finish): a path that
    // came to keep its hero wavelength alone carries that estimate's factor in β instead.
    static void estimateInBeta(bool heroBefore, PathThroughput* t) {
        if (t->heroOnly && !heroBefore) t->beta = t->estimate(t->beta);
    }

    // A mirror's reflectance at every wavelength; a glass's weight (1, or 1/η² for radiance
    // refracted into it), which depends on λ only where the glass disperses, and there the
    // chain keeps the hero wavelength alone.
    static void weighSpecularVertex(const Material& mat, const BsdfSample& bs,
                                    const SampledWavelengths& w, ViewWeight* view) {
        if (mat.type() == MaterialType::Mirror && !mat.reflectance().isConstant()) {
            view->multiply([&](float lambda) { return mat.reflectance()(lambda); });
            return;
        }
        view->scale(bs.weight[0]);
        if (bs.dispersed) view->keepHero(w.lambda[0], w.pdf[0]);
    }

    PhotonIntegratorSettings mSettings;
    std::unique_ptr<Integrator> mSingle;
    bool mCurved = false;  // photons on curved paths, direct light from the maps
    // Each light's XYZ per watt on an achromatic scene (the top of the file), else empty.
    std::vector<Vec3> mXyzPerWatt;
    int mPass = 0;             // the pass whose maps are built
    float mRadiusScale = 1.f;  // its disc radii over pass 0's
    std::vector<const Medium*> mMedia;
    std::vector<int> mSlotOfLight;  // each light's group slot (Photon::light → film/aov.h)
    std::unique_ptr<VolumePhotons> mPhotons;
    // The first full pass's volume map and beam radii (unscaled), the later passes' source of
    // radii; mPhotons is that map until the next pass (mPhotonsAreSource).
    std::unique_ptr<VolumePhotons> mSourcePhotons;
    std::vector<float> mSourceRadii;
    bool mPhotonsAreSource = false;
    std::unique_ptr<BeamEstimator> mBeam;
    std::unique_ptr<SurfacePhotons> mGlobal, mCaustic;  // surface photon maps
    float mMaxRadius = 0.f, mStep = 0.f;
    // Of the passes (summed) and the maps; the estimate time is summed by stats().
    PhotonStats mStats;
    std::unique_ptr<tbb::enumerable_thread_specific<PhotonThreadState>> mThreads;
};

}  // namespace

std::vector<std::pair<std::string, std::string>> PhotonStats::metadata() const {
    const auto num = headerNumber;
    return {{"photons_traced", std::to_string(traced.emitted)},
            {"photons_stored", std::to_string(traced.stored)},
            {"photon_pass_seconds", num(traced.seconds)},
            {"photons_per_second", num(photonsPerSecond())},
            {"photon_map_build_seconds", num(photonMapBuildSeconds)},
            {"photon_radii_seconds", num(photonRadiiSeconds)},
            {"disc_bvh_build_seconds", num(discBvhBuildSeconds)},
            {"estimate_seconds", num(estimateSeconds)}};
}

bool photonsCurve(const IndexField* field, const Bounds3& b) {
    if (!field || b.empty()) return false;
    const Vec3 pad = b.diagonal() * 0.1f;
    return field->gradientBound(Vec3d(b.lo - pad), Vec3d(b.hi + pad)) > 0.0;
}

PhotonPassResult tracePhotonIntegratorPass(const RenderScene& scene,
                                           const PhotonIntegratorSettings& settings, int pass) {
    std::vector<const Light*> lights;
    for (const auto& l : scene.lights) lights.push_back(l.get());
    PhotonPassResult result;
    result.maps = tracePhotonMaps(lights, scene.mediaPointers(),
                                  scene.hasSurfaces() ? scene.geometry.get() : nullptr,
                                  passSettings(settings, scene, pass), &result.stats);
    return result;
}

std::unique_ptr<Integrator> makePhotonIntegrator(const PhotonIntegratorSettings& settings) {
    // The scene loader refuses k = 1 with its location; callers of the library get the same
    // message instead of the estimators' internal check.
    if (settings.k == 1)
        throw MirageError(
            "photon integrator: k = 1: expected 0 (the default for the estimate) "
            "or at least 2 photons per estimate");
    return std::make_unique<PhotonMapIntegrator>(settings);
}

}  // namespace mirage
