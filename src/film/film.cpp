// The film: spectral camera samples → CIE XYZ sums per pixel → working-space RGBA.
//
// Pixels accumulate XYZ, not RGB, because XYZ is what the colour-matching functions give and it
// does not depend on the working space; the 3×3 change to the working space is linear, so applying
// it once to the average equals applying it to every sample. Sums are in double so that a small
// sample added to a large running sum (thousands of samples, a firefly among them) is not lost to
// float's 24-bit mantissa.

#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "film/color.h"
#include "film/cryptomatte.h"
#include "film/film_error.h"
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
    const SampleXyz toXyz(w);
    Vec3 xyz = toXyz(L) + extraXyz;
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
    if (aov && !mAovs.empty()) addAovs(size_t(y) * mWidth + x, *aov, toXyz, xyz);
    return true;
}

// The radiance passes go through spectrumToXyz exactly as the beauty does (a linear map), so
// Σ passes = beauty up to rounding. Albedo and transmittance are ratios: their XYZ is that of
// the spectrum as a radiance, mapped back to ratios in develop(). The variance sums the
// products of the sample's XYZ (the beauty's `xyz`) that Pixel::xyzSq does not keep. The
// light-path passes and light groups a sample left empty add nothing (AovSample::litPaths).
void Film::addAovs(size_t pixel, const AovSample& aov, const SampleXyz& toXyz,
                   const Vec3& xyz) {
    double* sums = mAovSums.data() + pixel * size_t(mAovs.stride());
    const AovOffsets& at = mAovs.offsets();
    auto add3 = [&](int offset, const Vec3& v) {
        for (int c = 0; c < 3; ++c) sums[offset + c] += v[c];
    };
    // A light-path pass or light group: its spectral part in XYZ plus the part already in XYZ
    // (render/achromatic_film.h).
    auto addLight = [&](int offset, const SampledSpectrum& L, const Vec3& xyzPart) {
        if (offset >= 0) add3(offset, toXyz(L) + xyzPart);
    };
    for (uint32_t m = aov.litPaths; m != 0; m &= m - 1) {
        const size_t p = size_t(AovSample::lowestBit(m));
        addLight(at.path[p], aov.path[p], aov.pathXyz[p]);
    }
    if (aov.groupsLit)
        for (size_t g = 0; g < at.group.size(); ++g)
            addLight(at.group[g], aov.group[g], aov.groupXyz[g]);
    if (at.depth >= 0 && std::isfinite(aov.depth)) {
        sums[at.depth] += aov.depth;
        sums[at.depth + 1] += 1.0;
    }
    if (at.albedo >= 0) add3(at.albedo, toXyz(aov.albedo));
    if (at.transmittance >= 0) add3(at.transmittance, toXyz(aov.transmittance));
    if (at.variance >= 0) {
        sums[at.variance + 0] += double(xyz.x) * double(xyz.y);
        sums[at.variance + 1] += double(xyz.x) * double(xyz.z);
        sums[at.variance + 2] += double(xyz.y) * double(xyz.z);
    }
    for (int k = 0; k < 2; ++k) {
        if (at.crypto[size_t(k)] < 0) continue;
        const std::vector<float>& c = k == 0 ? aov.volumeCoverage : aov.shapeCoverage;
        for (size_t i = 0; i < c.size(); ++i) sums[at.crypto[size_t(k)] + int(i)] += c[i];
    }
}

namespace {

// The variance of a pixel's mean in each working-space channel r = Σ_c M_rc X_c: the quadratic
// form Σ_a Σ_b M_ra M_rb Cov(X̄_a, X̄_b) of the XYZ means' covariance (film_error.h), the
// squares from the beauty's sums and the products XY, XZ, YZ from the pass's.
Vec3d varianceOfMeanRgb(const Film::Pixel& p, const double* products, const Mat3& toWorking) {
    double cov[3][3];
    for (int a = 0; a < 3; ++a) cov[a][a] = varianceOfMean(p, a);
    const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int k = 0; k < 3; ++k) {
        const int a = pairs[k][0], b = pairs[k][1];
        cov[a][b] = cov[b][a] = covarianceOfMean(p.xyz[a], p.xyz[b], products[k], p.samples);
    }
    double v[3];
    for (int r = 0; r < 3; ++r) {
        v[r] = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) v[r] += toWorking(r, a) * toWorking(r, b) * cov[a][b];
        v[r] = std::max(0.0, v[r]);  // rounding, for a pixel whose samples agree
    }
    return Vec3d(v[0], v[1], v[2]);
}

}  // namespace

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
    image.layers = developAovs(toWorking, &image.attributes);
    return image;
}

// Each pass averaged over the pixel's valid samples, like the beauty. Albedo and transmittance
// are divided by the working-space colour of an equal-energy spectrum (XYZ = 1, 1, 1 for CIE
// 1931), so that a ratio of 1 at every wavelength is (1, 1, 1). Depth is the mean of the
// samples that reached 50 % opacity, ∞ where none did.
std::vector<ImageLayer> Film::developAovs(
    const Mat3& toWorking, std::vector<std::pair<std::string, std::string>>* attributes) const {
    std::vector<ImageLayer> layers;
    const Vec3d unit = toWorking.apply(Vec3d(1.0, 1.0, 1.0));
    for (const AovPass& pass : mAovs.passes()) {
        if (pass.kind == AovKind::Cryptomatte) {
            developCryptomatte(pass, &layers, attributes);
            continue;
        }
        ImageLayer layer;
        layer.name = pass.name;
        const bool ratio = pass.kind == AovKind::Albedo || pass.kind == AovKind::Transmittance;
        layer.convertColor = pass.kind != AovKind::Variance;
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
            if (pass.kind == AovKind::Variance) {
                const Vec3d v = varianceOfMeanRgb(p, sums, toWorking);
                out[0] = float(v.x);
                out[1] = float(v.y);
                out[2] = float(v.z);
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

// A Cryptomatte's three layers (ranks 0–5) from each pixel's mean coverage per object, and its
// header attributes.
void Film::developCryptomatte(const AovPass& pass, std::vector<ImageLayer>* layers,
                              std::vector<std::pair<std::string, std::string>>* attributes) const {
    const CryptoObjects& o = mAovs.cryptoObjects();
    const std::vector<std::string>& objects = pass.index == 0 ? o.volumes : o.shapes;
    std::vector<float> coverage(mPixels.size() * objects.size(), 0.f);
    for (size_t i = 0; i < mPixels.size(); ++i) {
        if (mPixels[i].samples == 0) continue;
        const double inv = 1.0 / double(mPixels[i].samples);
        const double* sums = mAovSums.data() + i * size_t(mAovs.stride()) + pass.offset;
        for (size_t j = 0; j < objects.size(); ++j)
            coverage[i * objects.size() + j] = float(sums[j] * inv);
    }
    for (ImageLayer& l : cryptomatteLayers(pass.name, objects, coverage, mPixels.size()))
        layers->push_back(std::move(l));
    for (auto& a : cryptomatteAttributes(pass.name, objects)) attributes->push_back(std::move(a));
}

}  // namespace mirage
