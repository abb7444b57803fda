// The film: spectral camera samples → CIE XYZ sums per pixel → working-space RGBA.
//
// Pixels accumulate XYZ, not RGB, because XYZ is what the colour-matching functions give and it
// does not depend on the working space; the 3×3 change to the working space is linear, so applying
// it once to the average equals applying it to every sample. Sums are in double so that a small
// sample added to a large running sum (thousands of samples, a firefly among them) is not lost to
// float's 24-bit mantissa.

#include "film/film.h"

#include "core/error.h"
#include "film/color.h"
#include "spectrum/cie.h"

namespace mirage {

Film::Film(int width, int height)
    : mWidth(width), mHeight(height), mPixels(size_t(std::max(width, 0)) * std::max(height, 0)) {
    MIRAGE_CHECK(width > 0 && height > 0);
}

// A non-finite sample (NaN or ∞ from a degenerate path) is dropped before it can touch the sums:
// one NaN would blacken the pixel for good. It does not count towards the pixel's sample count
// either, so the pixel is the mean of its valid samples; the count of dropped samples is kept per
// pixel (each pixel is written by one thread only, so no atomics are needed) and reported.
void Film::addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                     float alpha) {
    addSample(x, y, L, w, alpha, Vec3(0.f));
}

void Film::addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                     float alpha, const Vec3& extraXyz) {
    MIRAGE_DCHECK(x >= 0 && x < mWidth && y >= 0 && y < mHeight);
    Pixel& p = mPixels[size_t(y) * mWidth + x];
    if (!L.isFinite() || !std::isfinite(alpha)) {
        ++p.nonFinite;
        return;
    }
    // Finite radiance can still overflow float in L / pdf for a wavelength of tiny density.
    Vec3 xyz = spectrumToXyz(L, w) + extraXyz;
    if (!isFinite(xyz)) {
        ++p.nonFinite;
        return;
    }
    for (int c = 0; c < 3; ++c) {
        p.xyz[c] += xyz[c];
        p.xyzSq[c] += double(xyz[c]) * double(xyz[c]);
    }
    p.alpha += alpha;
    ++p.samples;
}

uint64_t Film::nonFiniteSamples() const {
    uint64_t n = 0;
    for (const Pixel& p : mPixels) n += p.nonFinite;
    return n;
}

Image Film::develop(const ColorPipeline& color) const {
    Image image;
    image.width = mWidth;
    image.height = mHeight;
    image.rgba.assign(mPixels.size() * 4, 0.f);
    const Mat3& toWorking = color.xyzToWorking();
    for (size_t i = 0; i < mPixels.size(); ++i) {
        const Pixel& p = mPixels[i];
        if (p.samples == 0) continue;  // no valid sample: transparent black
        double inv = 1.0 / double(p.samples);
        Vec3d rgb = toWorking.apply(Vec3d(p.xyz[0] * inv, p.xyz[1] * inv, p.xyz[2] * inv));
        float* out = &image.rgba[i * 4];
        out[0] = float(rgb.x);
        out[1] = float(rgb.y);
        out[2] = float(rgb.z);
        out[3] = float(p.alpha * inv);
    }
    return image;
}

}  // namespace mirage
