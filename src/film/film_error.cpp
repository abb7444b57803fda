// The estimated error of a film: see film_error.h for the estimator.
#include "film/film_error.h"

#include <algorithm>
#include <cmath>

namespace mirage {

namespace {

constexpr double kCoveredAlpha = 0.01;  // the race's mask: reference alpha > 0.01

bool covered(const Film::Pixel& p) {
    return p.samples >= 2 && p.alpha / double(p.samples) > kCoveredAlpha;
}

}  // namespace

double covarianceOfMean(double sumA, double sumB, double sumAB, uint32_t samples) {
    if (samples < 2) return 0.0;
    const double n = double(samples);
    const double a = sumA / n, b = sumB / n;
    return (sumAB - n * a * b) / (n - 1.0) / n;
}

double varianceOfMean(const Film::Pixel& p, int c) {
    // Rounding can leave Σx² − n m² a little below 0 for a constant pixel.
    return std::max(0.0, covarianceOfMean(p.xyz[c], p.xyz[c], p.xyzSq[c], p.samples));
}

double FilmError::relError() const { return std::sqrt(relMse); }

FilmError estimateFilmError(const Film& film) {
    const int w = film.width(), h = film.height();
    FilmError e;
    e.pixelError.assign(size_t(w) * size_t(h), 0.f);
    // ε from the mean of the covered pixels' channel means.
    double meanSum = 0;
    size_t count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            if (!covered(p)) continue;
            meanSum += (p.xyz[0] + p.xyz[1] + p.xyz[2]) / double(p.samples);
            ++count;
        }
    if (count == 0) return e;
    const double eps = 1e-3 * std::pow(meanSum / (3.0 * double(count)), 2.0);
    double sum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            if (!covered(p)) continue;
            double term = 0;
            for (int c = 0; c < 3; ++c) {
                const double m = p.xyz[c] / double(p.samples);
                term += varianceOfMean(p, c) / (m * m + eps);
            }
            term /= 3.0;
            sum += term;
            e.pixelError[size_t(y) * w + x] = float(std::sqrt(term));
        }
    e.pixels = count;
    e.relMse = sum / double(count);
    return e;
}

std::vector<uint8_t> noisyPixels(const Film& film, const FilmError& error, double threshold) {
    const int w = film.width(), h = film.height();
    std::vector<uint8_t> active(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float worst = 0.f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                    worst = std::max(worst, error.pixelError[size_t(ny) * w + nx]);
                }
            active[size_t(y) * w + x] = double(worst) > threshold ? 1 : 0;
        }
    return active;
}

}  // namespace mirage
