// The film: per-pixel accumulation of spectral samples as CIE XYZ plus alpha, then conversion
// to the working space. Each pixel belongs to one tile and is summed in sample order, so the
// image is bit-identical whatever the thread count.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/matrix.h"
#include "core/spectral.h"
#include "film/aov.h"

namespace mirage {

class SampleXyz;  // spectrum/cie.h

class ColorPipeline;

// One render pass developed: a layer of the EXR, whose channels are written `name.channel`
// (Nuke splits such names into layers), interleaved per pixel like Image::rgba.
struct ImageLayer {
    std::string name;
    std::vector<std::string> channels;  // "R", "G", "B"; "A"; "Z"
    std::vector<float> pixels;          // channels.size() floats per pixel
    // Whether an output colour space converts its R G B like the beauty's (not a variance).
    bool convertColor = true;
    // Written as 32-bit float even in a half-float EXR (Cryptomatte's IDs are float32 bits).
    bool fullFloat = false;
};

// An RGBA float image, interleaved, in a named colour space, with its render passes.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba;  // 4 floats per pixel, row-major from the top-left
    std::vector<ImageLayer> layers;  // the AOVs, in the order they were asked for
    // Header attributes the layers need, written as named (Cryptomatte's manifest).
    std::vector<std::pair<std::string, std::string>> attributes;
    float* pixel(int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

class Film {
public:
    // `aovs`: the render passes to accumulate beside the beauty (none: the film keeps the
    // beauty alone and costs what it always did).
    Film(int width, int height, AovLayout aovs = {});
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    const AovLayout& aovs() const { return mAovs; }

    // One camera sample: radiance L (W·m⁻²·sr⁻¹·nm⁻¹) at wavelengths w, and coverage alpha.
    // Non-finite samples are dropped and counted (reported in the summary and EXR metadata).
    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                   float alpha);
    // The same, plus radiance already in XYZ (a photon-map estimate, integrator.h), added to
    // the sample's own XYZ; a non-finite xyz drops the whole sample.
    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                   float alpha, const Vec3& xyz);
    // The same, plus the sample's passes (null when the film has none): every pass of a
    // sample is kept or dropped with its beauty. Returns whether it was kept.
    bool addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w, float alpha,
                   const Vec3& xyz, const AovSample* aov);
    uint64_t nonFiniteSamples() const;

    // Averages the samples and converts XYZ to the working space of `color`; the passes
    // become Image::layers.
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
    // A pixel's pass sums, aovs().stride() doubles (AovPass::offset says whose).
    const double* aovSums(int x, int y) const {
        return mAovSums.data() + (size_t(y) * mWidth + x) * size_t(mAovs.stride());
    }
    double* aovSums(int x, int y) {
        return mAovSums.data() + (size_t(y) * mWidth + x) * size_t(mAovs.stride());
    }

private:
    void addAovs(size_t pixel, const AovSample& aov, const SampleXyz& toXyz, const Vec3& xyz);
    std::vector<ImageLayer> developAovs(
        const Mat3& toWorking, std::vector<std::pair<std::string, std::string>>* attributes) const;
    void developCryptomatte(const AovPass& pass, std::vector<ImageLayer>* layers,
                            std::vector<std::pair<std::string, std::string>>* attributes) const;

    int mWidth, mHeight;
    std::vector<Pixel> mPixels;
    AovLayout mAovs;
    std::vector<double> mAovSums;
};

}  // namespace mirage
