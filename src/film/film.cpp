// The film: spectral camera samples → CIE XYZ sums per pixel → working-space RGBA.
//
// Pixels accumulate XYZ, not RGB, because XYZ is what the colour-matching functions give and it
// does not depend on the working space; the 3×3 change to the working space is linear, so applying
// it once to the average equals applying it to every sample. Sums are in double so that a small
// sample added to a large running sum (thousands of samples, a firefly among them) is not lost to
// float's 24-bit mantissa.

#include "film/film.h"

#include <cmath>
#include <utility>

#include "core/error.h"
#include "film/color.h"
#include "spectrum/cie.h"

namespace mirage {

Film::Film(int width, int height, AovLayout aovs)
    : mWidth(width),
      mHeight(height),
      mPixels(size_t(std::max(width, 0)) * std::max(height, 0)),
      mAovs(std::move(aovs)),
      mAovSums(mPixels.size() * size_t(mAovs.stride()), 0.0) {
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
    addSample(x, y, L, w, alpha, extraXyz, nullptr);
}

bool Film::addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& w,
                     float alpha, const Vec3& extraXyz, const AovSample* aov) {
    MIRAGE_DCHECK(x >= 0 && x < mWidth && y >= 0 && y < mHeight);
    Pixel& p = mPixels[size_t(y) * mWidth + x];
    if (!L.isFinite() || !std::isfinite(alpha)) {
        ++p.nonFinite;
        return false;
    }
    // Finite radiance can still overflow float in L / pdf for a wavelength of tiny density.
    Vec3 xyz = spectrumToXyz(L, w) + extraXyz;
    if (!isFinite(xyz)) {
        ++p.nonFinite;
        return false;
    }
    for (int c = 0; c < 3; ++c) {
        p.xyz[c] += xyz[c];
        p.xyzSq[c] += double(xyz[c]) * double(xyz[c]);
    }
    p.alpha += alpha;
    ++p.samples;
    if (aov && !mAovs.empty()) addAovs(size_t(y) * mWidth + x, *aov, w);
    return true;
}

// The radiance passes go through spectrumToXyz exactly as the beauty does (a linear map), so
// Σ passes = beauty up to rounding. Albedo and transmittance are ratios: their XYZ is that of
// the spectrum as a radiance, mapped back to ratios in develop().
void Film::addAovs(size_t pixel, const AovSample& aov, const SampledWavelengths& w) {
    double* sums = mAovSums.data() + pixel * size_t(mAovs.stride());
    auto add3 = [&](int offset, const Vec3& v) {
        for (int c = 0; c < 3; ++c) sums[offset + c] += v[c];
    };
    for (const AovPass& pass : mAovs.passes()) switch (pass.kind) {
            case AovKind::LightPath:
                add3(pass.offset, spectrumToXyz(aov.path[size_t(pass.index)], w) +
                                      aov.pathXyz[size_t(pass.index)]);
                break;
            case AovKind::LightGroup:
                add3(pass.offset, spectrumToXyz(aov.group[size_t(pass.index)], w));
                break;
            case AovKind::Depth:
                if (std::isfinite(aov.depth)) {
                    sums[pass.offset] += aov.depth;
                    sums[pass.offset + 1] += 1.0;
                }
                break;
            case AovKind::Albedo:
                add3(pass.offset, spectrumToXyz(aov.albedo, w));
                break;
            case AovKind::Transmittance:
                add3(pass.offset, spectrumToXyz(aov.transmittance, w));
                break;
            case AovKind::Alpha:
                break;
        }
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
    image.layers = developAovs(toWorking);
    return image;
}

// Each pass averaged over the pixel's valid samples, like the beauty. Albedo and transmittance
// are divided by the working-space colour of an equal-energy spectrum (XYZ = 1, 1, 1 for CIE
// 1931), so that a ratio of 1 at every wavelength is (1, 1, 1). Depth is the mean of the
// samples that reached 50 % opacity, ∞ where none did.
std::vector<ImageLayer> Film::developAovs(const Mat3& toWorking) const {
    std::vector<ImageLayer> layers;
    const Vec3d unit = toWorking.apply(Vec3d(1.0, 1.0, 1.0));
    for (const AovPass& pass : mAovs.passes()) {
        ImageLayer layer;
        layer.name = pass.name;
        const bool ratio = pass.kind == AovKind::Albedo || pass.kind == AovKind::Transmittance;
        if (pass.kind == AovKind::Alpha)
            layer.channels = {"A"};
        else if (pass.kind == AovKind::Depth)
            layer.channels = {"Z"};
        else
            layer.channels = {"R", "G", "B"};
        const size_t n = layer.channels.size();
        layer.pixels.assign(mPixels.size() * n, 0.f);
        for (size_t i = 0; i < mPixels.size(); ++i) {
            const Pixel& p = mPixels[i];
            const double* sums = mAovSums.data() + i * size_t(mAovs.stride()) + pass.offset;
            float* out = &layer.pixels[i * n];
            if (pass.kind == AovKind::Depth) {
                out[0] = sums[1] > 0 ? float(sums[0] / sums[1]) : kInfinity;
                continue;
            }
            if (p.samples == 0) continue;
            const double inv = 1.0 / double(p.samples);
            if (pass.kind == AovKind::Alpha) {
                out[0] = float(p.alpha * inv);
                continue;
            }
            Vec3d rgb = toWorking.apply(Vec3d(sums[0] * inv, sums[1] * inv, sums[2] * inv));
            if (ratio) rgb = Vec3d(rgb.x / unit.x, rgb.y / unit.y, rgb.z / unit.z);
            out[0] = float(rgb.x);
            out[1] = float(rgb.y);
            out[2] = float(rgb.z);
        }
        layers.push_back(std::move(layer));
    }
    return layers;
}

}  // namespace mirage
