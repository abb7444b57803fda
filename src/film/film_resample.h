// A film at another resolution: a draft rendered at a fraction of the frame's pixels
// (render/draft.h), reconstructed at the frame's own so that it is written, developed and judged
// like any render of the frame.
#pragma once

#include "film/film.h"

namespace mirage {

// `src` magnified to width × height by bilinear interpolation of its pixel means (the tent
// filter through its pixel centres, clamped at the edges), over the same image plane: pixel
// centre (x + ½, y + ½) of the result reads `src` at ((x + ½)·src.width / width − ½, …). Each
// result pixel holds its interpolated mean as one sample of zero variance; a source pixel
// without samples is left out of its neighbours' weights. The beauty and alpha only: `src`
// must have no passes (an ID or depth pass does not interpolate).
Film magnify(const Film& src, int width, int height);

}  // namespace mirage
