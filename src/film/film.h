// The film: per-pixel accumulation of spectral samples as CIE XYZ plus alpha, then conversion
// to the working space. Each pixel belongs to one tile and is summed in sample order, so the
// image is bit-identical whatever the thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/spectral.h"

namespace mirage {

class ColorPipeline;

// An RGBA float image, interleaved, in a named colour space.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba;  // 4 floats per pixel, row-major from the top-left
    float* pixel(int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

class Film {
public:
    Film(int width, int height);
    int width() const { return mWidth; }
    int height() const { return mHeight; }

    // One camera sample: radiance L (W·m⁻²·sr⁻¹·nm⁻¹) at wavelengths w, and coverage alpha.
    // Non-finite samples are dropped and counted (reported in the summary and EXR metadata).
    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                   float alpha);
    // The same, plus radiance already in XYZ (a photon-map estimate, integrator.h), added to
    // the sample's own XYZ; a non-finite xyz drops the whole sample.
    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                   float alpha, const Vec3& xyz);
    uint64_t nonFiniteSamples() const;

    // Averages the samples and converts XYZ to the working space of `color`.
    Image develop(const ColorPipeline& color) const;

    // A pixel's running sums: what a partial file (partial_film.h) stores so that a resumed
    // render continues exactly where the killed one stopped.
    struct Pixel {
        double xyz[3] = {0, 0, 0};
        double alpha = 0;
        // Σ of each sample's squared X, Y, Z: with xyz and samples, the per-pixel variance
        // (film_error.h: the estimated error of a render in passes, a variance AOV).
        double xyzSq[3] = {0, 0, 0};
        uint32_t samples = 0;
        uint32_t nonFinite = 0;
    };
    const Pixel& pixel(int x, int y) const { return mPixels[size_t(y) * mWidth + x]; }
    Pixel& pixel(int x, int y) { return mPixels[size_t(y) * mWidth + x]; }

private:
    int mWidth, mHeight;
    std::vector<Pixel> mPixels;
};

}  // namespace mirage
