// The estimated error of a film, from each pixel's first and second moments (Film::Pixel::xyz,
// xyzSq): what `--noise-threshold` stops on, where adaptive sampling puts its samples, and what
// the EXR header records as mirage:estimated_error.
//
// Per pixel and CIE channel c (X, Y, Z), with n valid samples x_i: the mean m = Σx/n, the
// unbiased sample variance s² = (Σx² − n m²)/(n − 1), and the variance of the mean s²/n. The
// image's relative error is the race's relMSE (docs/performance.md) with its expectation put in
// place of the converged reference: over the covered pixels P (mean alpha > 0.01, n ≥ 2),
//     relMSE ≈ (1/|P|) Σ_p (1/3) Σ_c (s²_pc / n_p) / (m_pc² + ε),   ε = 10⁻³ · (mean m)²,
// the mean over P and c of m; the estimated relative error is √relMSE. This is the variance
// part of the error only: it sees the camera samples' noise and, in a progressive photon
// render, the noise between passes' photon maps, but not a bias (the photon estimate's blur,
// a path cap). Photon-map noise within one pass is shared by every sample of the pass and so
// is underestimated by the per-sample variance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "film/film.h"

namespace mirage {

// Variance of the mean of channel c (0 X, 1 Y, 2 Z) of a pixel; 0 with fewer than 2 samples.
double varianceOfMean(const Film::Pixel& p, int c);
// The covariance of the means of two quantities a and b over n samples, from their sums Σa,
// Σb and Σab: (Σab − n ā b̄)/(n − 1)/n, the unbiased sample covariance over n; 0 for n < 2.
double covarianceOfMean(double sumA, double sumB, double sumAB, uint32_t n);

struct FilmError {
    double relMse = 0;        // the estimated relMSE of the image (above)
    size_t pixels = 0;        // covered pixels it averages over
    double relError() const;  // √relMSE
    // Per pixel, row-major: √ of its term (1/3) Σ_c (s²/n)/(m² + ε); 0 for an uncovered pixel.
    std::vector<float> pixelError;
};
FilmError estimateFilmError(const Film& film);

// Adaptive sampling: which pixels the next pass samples (1) — those whose estimated relative
// error, the largest over their 3×3 neighbourhood, is above `threshold`. The neighbourhood
// guards a pixel whose few samples happen to agree (a firefly not yet drawn) by its
// neighbours, which see the same smoke.
std::vector<uint8_t> noisyPixels(const Film& film, const FilmError& error, double threshold);

}  // namespace mirage
