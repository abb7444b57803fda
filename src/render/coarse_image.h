// The coarse image: the frame rendered at half its resolution in each axis by an integrator
// without photon passes, then magnified to the frame's (film/film_resample.h). It is what a
// render with a time limit shorter than one full pass delivers (render/passes.h), and what
// `mirage render --coarse SPP` renders on its own to reproduce it.
//
// Why: one full pass of the default photon mapper on dense smoke costs its photon map plus one
// sample of every pixel (0.3–0.4 s on the race scene, docs/performance-history.md, "A time limit
// shorter than one pass"); a time limit below that used to be overrun by the whole first pass. A
// quarter of the pixels by the path tracer costs ~1/13 of that pass per sample and its error is
// mostly noise and the magnification's blur (race scene: 1 sample 0.026 s, relMSE 2.5; 4 samples
// 0.09 s, 0.85; the blur alone 0.08).
//
// Its samples continue from pass to pass (samples [n, n + k) of each coarse pixel), so a coarse
// image that took 1, 1 and 2 samples is the same bits as one of 4 samples.
#pragma once

#include "film/film.h"
#include "render/renderer.h"

namespace mirage {

class CancelToken;

// The coarse image's pixels per frame pixel, in each axis.
constexpr int kCoarseDivisor = 2;

// Whether a frame can have a coarse image: the whole frame (no --region) and the beauty alone
// (passes such as depth or Cryptomatte IDs do not magnify).
bool coarseImagePossible(const RenderSettings& s);

// The settings of the frame's coarse image: its resolution rounded up, the same camera, seed,
// tiles and sampler, no passes, quiet.
RenderSettings coarseSettings(const RenderSettings& frame);

struct CoarseImage {
    Film film;    // at coarseSettings(frame)'s resolution
    int spp = 0;  // samples per coarse pixel so far
    // The caller's stop (core/cancel.h) for its renders; null: SIGINT/SIGTERM.
    const CancelToken* cancel = nullptr;
    explicit CoarseImage(const RenderSettings& frame);
};

// Adds `spp` samples to every pixel of `image` (its samples [image->spp, image->spp + spp)).
// Returns false, leaving `image` as it was, when a stop (image->cancel, a signal) came.
bool addCoarseSamples(const RenderScene& scene, Integrator& integrator, const RenderSettings& frame,
                      int spp, CoarseImage* image);

// The coarse image at the frame's resolution.
Film magnifyCoarse(const CoarseImage& image, const RenderSettings& frame);

}  // namespace mirage
