// The emission a straight flight of `volpath` scores along its ray where the scene's glowing
// media are a light (render/emission_light.h): two estimators of one integral,
//     L_e = ∫_0^{t_s} T(0, t) σa(t) Le(t) dt   (t_s the surface ahead, or where the media end),
// combined by the power heuristic.
//
// Collisions. The flight's tentative collisions in medium i are a Poisson process of rate σ̄_i
// (its majorant) along the ray, and each scores β σa Le / σ̄_i (volpath.cpp): expectation L_e.
// A flame is hot where little absorbs, so a flight crosses it with σ̄ d ≪ 1 (d its width): a
// fraction σ̄ d of the flights collide there and score 1/(σ̄ d) of the mean. On the fire regime
// (pipeline/race.sh fire) these were its fireflies: smoke pixels of 2.5e-5 (the reference's)
// rendered 0.014 at 16 samples, from one depth-2 flight's collision in a 1690 K flame of
// σa 0.06/m scoring 0.33.
//
// A point. Before the flight, t* is drawn along the ray ∝ the emission grid's power per volume,
// no floor (EmissionLight::sampleDistance, density p(t): only the cells that glow; the
// collisions keep all the weight where p = 0), and scored when the flight gets
// past it with the β it carries there: the track-length estimator, whose weight is right
// because weighted delta tracking (transport/path_vertex.h: real events scale β by σs/(σ̄ P_real),
// null ones by σn/(σ̄ P_null)) keeps E[β 1{still flying at t}] = β_0 T(0, t) at every t.
//
// Combined by the power heuristic (Veach 1997, §9.2.1; for a one-sample point against a
// Poisson process of rate σ̄_i the weights need only sum to 1 at every t):
//     a collision in medium i at t:   β σa Le / σ̄_i  ×  σ̄_i² / (σ̄_i² + p²)
//     the point t*:                   Σ_i β σa,i Le_i / p  ×  p² / (σ̄_i² + p²)   (emissive i)
// whose expectations sum to L_e. A flight through a thin flame is found by its point, at the
// grid's power, whatever the majorant; in dense smoke, whose collisions are many, they keep the
// weight. The balance heuristic measured the same within the seeds' noise (fire regime, 16
// samples, six seeds: mean relMSE 0.265 against the power heuristic's 0.257). Holdout media
// score nothing, as their collisions do not. Both are times the flight's own weight against the
// line sample of its vertex (render/line_emission.h), which sees the same line either way.
//
// On the fire regime against a 2048-sample reference, six seeds' relMSE at 16 samples went from
// 0.37–5.2 (mean 2.0) to 0.19–0.32 (mean 0.26), at 4 samples from 1.4–79 to 0.65–2.2; a frame
// of 64 samples takes ~6 % longer (the points' walks of the coarse grid, clipped to the box of
// its cells that glow).
//
// Where it applies: every straight flight of `volpath` (the camera ray too) in a scene whose
// glowing media are a light (`emission_sampling = "line"`, the default); curved flights keep
// their collisions alone, at weight 1.
#pragma once

#include "render/emission_light.h"
#include "render/path_recorder.h"

namespace mirage {

class FlightEmission {
public:
    // No point: the collisions keep their whole score.
    FlightEmission() = default;
    // Draws the point along ray (a unit direction) over (0, tEnd); one number.
    FlightEmission(const EmissionLight& light, const Ray& ray, float tEnd, Sampler& sampler,
                   TrackingContext& tracking);

    // The collision's share of its score β σa Le / σ̄: σ̄² / (σ̄² + p(t)²).
    float collisionShare(const Collision& c, TrackingContext& tracking) const {
        return mLight ? shareAt(c, tracking) : 1.f;
    }
    // Scores the point, once, when the flight has got past it: called with each tentative
    // collision's t before the collision changes β, and with tEnd when the flight got through.
    // beta: the flight's throughput; weight: its weight against the vertex's line sample. Inline
    // to the test: every tentative collision of every flight calls it.
    void reached(float t, const SampledSpectrum& beta, float weight, TrackingContext& tracking,
                 PathRecorder& rec) {
        if (mPending && t >= mPoint.t) score(beta * weight, tracking, rec);
    }

private:
    float shareAt(const Collision& c, TrackingContext& tracking) const;
    void score(const SampledSpectrum& beta, TrackingContext& tracking, PathRecorder& rec);

    const EmissionLight* mLight = nullptr;  // null: no point
    bool mPending = false;                  // the point is still ahead of the flight
    Ray mRay;
    EmissionLight::LinePoint mPoint;
};

}  // namespace mirage
