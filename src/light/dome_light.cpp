// The dome light (dome_light.h): incident light by importance sampling, the radiance of escaped
// rays, and photon emission.
//
// Sampling the image. A pixel (i, j) covers φ ∈ 2π [i, i+1)/W and θ ∈ π [j, j+1)/H, a solid
// angle of ΔΩ = 2π²/(WH) sin θ (to first order in the pixel's size). Drawing (u, v) from the
// piecewise-constant distribution of w_ij = Y_ij sin θ_j (Y: the pixel's luminance) and mapping
// it to the direction gives the density in solid angle
//     p(ω) = p(u, v) / (2π² sin θ)
// (Pharr, Jakob & Humphreys, PBRT 4th ed., §12.5.2), so that L/p is nearly constant over the
// image and a sun in a small map is found by most shadow rays. The radiance is constant over a
// pixel (nearest lookup), the same step function the density follows.
//
// Spectra. A pixel's RGB becomes a spectrum the way every illuminant colour does
// (rgbIlluminantSpectrum): three smooth basis windows B_k with coefficients c_k = M rgb, clamped
// at 0, so L(ω, λ) = Σ_k c_k(ω) B_k(λ) and the film shows the pixel's RGB back.
//
// Photons. Light from direction ω crosses the scene's bounding sphere (radius r) through the
// disc of area πr² facing ω, so the dome sends Φ = πr² ∫∫ L(ω, λ) dω dλ into the scene. A
// photon draws ω ∝ p(ω), a point on that disc, and λ ∝ L(ω, λ) (a basis window by its share of
// the pixel's power, then λ within it); its weight L̄(ω) / (p(ω) ∫ L̄) with L̄ = ∫ L dλ has mean 1
// (exactly 1 for the constant dome, whose directions are uniform on the sphere).
#include "light/dome_light.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "core/distribution.h"
#include "core/error.h"
#include "core/sampling.h"
#include "light/light_common.h"
#include "light/radiance_hdr.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

namespace {

constexpr float kInv2Pi2 = 1.f / (2.f * kPi * kPi);

// ∫ S dλ over 360–830 nm at the 1 nm of the dense tables (trapezoids).
double spectralIntegral(const Spectrum& s) {
    double sum = 0.0;
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
        sum += s(float(l)) * ((l == int(kLambdaMin) || l == int(kLambdaMax)) ? 0.5 : 1.0);
    return sum;
}

// The direction of image coordinates (u, v) ∈ [0, 1)² and back (the convention of
// dome_light.h), for a dome turned by `rotation` radians about +y. Turning (−sinθ sinφ, cosθ,
// sinθ cosφ) by a about +y (right-handed: −z towards −x) gives the same form at φ − a.
Vec3 latLongDirection(float u, float v, float rotation) {
    const float theta = kPi * v, phi = 2.f * kPi * u - rotation;
    const float sinT = std::sin(theta);
    return {-sinT * std::sin(phi), std::cos(theta), sinT * std::cos(phi)};
}
void latLongCoordinates(const Vec3& d, float rotation, float* u, float* v) {
    const float theta = std::acos(clamp(d.y, -1.f, 1.f));
    float phi = std::atan2(-d.x, d.z) + rotation;
    phi -= 2.f * kPi * std::floor(phi / (2.f * kPi));
    *u = std::min(phi / (2.f * kPi), 0x1.fffffep-1f);
    *v = std::min(theta / kPi, 0x1.fffffep-1f);
}

class DomeLight : public Light {
public:
    // A constant dome.
    DomeLight(const Spectrum& L, const DomeSettings& s)
        : mSettings(s), mRotation(radians(s.rotationDeg)), mConstant(L) {
        mTotal = 4.0 * kPi * spectralIntegral(L);
        if (mTotal > 0.0) mConstantLambda = SpectrumSampler(L);
    }

    // An image dome.
    DomeLight(const LatLongImage& img, float intensity, const Mat3& xyzToWorking,
              const DomeSettings& s)
        : mSettings(s), mRotation(radians(s.rotationDeg)), mWidth(img.width), mHeight(img.height) {
        const Mat3 toCoefficients = rgbIlluminantCoefficients(xyzToWorking);
        std::array<double, 3> basisIntegral, basisY;
        for (int k = 0; k < 3; ++k) {
            mBasis[k] = rgbBasisSpectrum(k);
            mBasisLambda[k] = SpectrumSampler(mBasis[k]);
            basisIntegral[k] = spectralIntegral(mBasis[k]);
            basisY[k] = spectrumToXyz(mBasis[k]).y;
        }
        const size_t n = size_t(mWidth) * size_t(mHeight);
        mTexels.resize(n);
        mPixelPower.resize(n);
        std::vector<double> weight(n);
        mTotal = 0.0;
        for (int j = 0; j < mHeight; ++j) {
            const double dOmega = pixelSolidAngle(j);
            const double sinT = std::sin(kPi * (j + 0.5) / double(mHeight));
            for (int i = 0; i < mWidth; ++i) {
                const size_t p = size_t(j) * mWidth + i;
                const Vec3d rgb(img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]);
                const Vec3d c = vmax(toCoefficients.apply(rgb * double(intensity)), Vec3d(0.0));
                mTexels[p].c = Vec3(c);
                mPixelPower[p] =
                    float(c.x * basisIntegral[0] + c.y * basisIntegral[1] + c.z * basisIntegral[2]);
                weight[p] = (c.x * basisY[0] + c.y * basisY[1] + c.z * basisY[2]) * sinT;
                mTotal += mPixelPower[p] * dOmega;
            }
        }
        mDistribution = Distribution2D(weight, mWidth, mHeight);
        for (int j = 0; j < mHeight; ++j)
            for (int i = 0; i < mWidth; ++i)
                mTexels[size_t(j) * mWidth + i].pdfUv = mDistribution.pdf(
                    (float(i) + 0.5f) / float(mWidth), (float(j) + 0.5f) / float(mHeight));
        findSun();
    }

    bool sampleLi(const Vec3&, float u1, float u2, const SampledWavelengths& w,
                  LightSample* out) const override {
        float pdf;
        size_t texel;
        const Vec3 d = sampleDirection(u1, u2, &pdf, &texel);
        if (!(pdf > 0.f)) return false;
        out->wi = d;
        out->distance = kInfinity;
        // The drawn cell's own radiance, whose density pdf is: mapping d back to the image (an
        // arc cosine and an arc tangent per shadow ray) found the same pixel, or at its edge a
        // neighbour.
        out->Li = (mDistribution.empty() ? radiance(d, w) : texelRadiance(mTexels[texel], w)) / pdf;
        out->pdf = pdf;
        return !out->Li.isZero();
    }
    // Every direction reaches the dome: a phase-function sample in a medium is a second
    // strategy, weighed against this light's own samples (render/direct_light.cpp).
    bool hitLi(const Vec3&, const Vec3& wi, const SampledWavelengths& w,
               LightSample* out) const override {
        out->wi = wi;
        out->distance = kInfinity;
        if (mDistribution.empty()) {
            out->pdf = kInv4Pi;
            out->Li = mConstant.sample(w);
        } else {  // one lookup of the pixel's texel for both (Texel)
            float u, v;
            latLongCoordinates(wi, mRotation, &u, &v);
            const Texel& t = mTexels[pixelAt(u, v)];
            const float sinT = std::sin(kPi * v);
            out->pdf = sinT > 0.f ? t.pdfUv * kInv2Pi2 / sinT : 0.f;
            out->Li = texelRadiance(t, w);
        }
        return out->pdf > 0.f && !out->Li.isZero();
    }

    SampledSpectrum escapedRadiance(const Vec3& d, const SampledWavelengths& w,
                                    bool cameraRay) const override {
        if (cameraRay && !mSettings.cameraVisible) return SampledSpectrum(0.f);
        return radiance(d, w);
    }
    bool infinite() const override { return true; }
    bool uniformRadiance() const override { return mDistribution.empty(); }
    std::optional<LightLobe> lobe() const override { return mSun; }

    float emittedPower(const Bounds3& b) const override {
        if (b.empty()) return 0.f;
        const float r = 0.5f * length(b.diagonal());
        return float(kPi * r * r * mTotal);
    }

    // A direction ∝ p(ω), a uniform point on the disc of the bounding sphere facing it, just
    // outside the sphere, travelling into the scene along −ω.
    bool emitPhoton(const Bounds3& b, Sampler& s, PhotonEmission* out) const override {
        if (b.empty() || !(mTotal > 0.0)) return false;
        const float u1 = s.get1D(), u2 = s.get1D();
        float pdf;
        const Vec3 d = sampleDirection(u1, u2, &pdf);
        if (!(pdf > 0.f)) return false;
        const float r = 0.5f * length(b.diagonal());
        const float u3 = s.get1D(), u4 = s.get1D();
        const float rho = r * std::sqrt(u3), phi = 2.f * kPi * u4;
        const Frame f(d);
        out->origin = b.center() + f.s * (rho * std::cos(phi)) + f.t * (rho * std::sin(phi)) +
                      d * (r * 1.001f);
        out->direction = -d;
        colour(d, pdf, s.get1D(), out);
        return out->weight > 0.f && r > 0.f;
    }
    std::unique_ptr<PhotonProjection> projection(const ProjectionTargets& t) const override;

    // A constant dome's colour is one spectrum everywhere (render/achromatic_film.h films it
    // exactly); an image's varies over directions, within the span of the three basis windows.
    const Spectrum* spectrum() const override { return mWidth == 0 ? &mConstant : nullptr; }
    // An image's radiance is Σ_k c_k(ω) B_k(λ) everywhere: three shapes, whatever the image.
    std::vector<const Spectrum*> spectralShapes() const override {
        if (mWidth == 0) return {&mConstant};
        return {&mBasis[0], &mBasis[1], &mBasis[2]};
    }
    std::string describe() const override {
        char buf[160];
        if (mDistribution.empty())
            std::snprintf(buf, sizeof buf, "dome light, constant, ∫∫L dω dλ = %g W/m²", mTotal);
        else
            std::snprintf(buf, sizeof buf, "dome light, %d×%d image, ∫∫L dω dλ = %g W/m²", mWidth,
                          mHeight, mTotal);
        std::string s = buf;
        if (mSettings.rotationDeg != 0.f)
            s += ", rotated " + numStr(mSettings.rotationDeg) + "°";
        if (!mSettings.cameraVisible) s += ", hidden from the camera";
        return s;
    }

private:
    // A pixel's coefficients c_k (intensity folded in) and its cell's density on [0, 1)² as
    // mDistribution.pdf gives it, side by side: a direction's radiance and density (hitLi, the
    // phase function's strategy, called at every scattering vertex) then cost one cache miss
    // where the two arrays and the distribution's row cost three.
    struct Texel {
        Vec3 c;
        float pdfUv = 0.f;
    };

    friend class DomeProjection;

    // A photon's wavelength, and its weight L̄(ω) / (p(ω) ∫ L̄), for the direction d towards the
    // dome drawn with density pdf.
    void colour(const Vec3& d, float pdf, float uLambda, PhotonEmission* out) const {
        if (!mDistribution.empty()) {
            const size_t p = pixel(d);
            const Vec3& c = mTexels[p].c;
            out->lambda = sampleBasis(c, mPixelPower[p], uLambda);
            out->weight = float(mPixelPower[p] / (pdf * mTotal));
        } else {
            out->lambda = mConstantLambda.sample(uLambda);
            out->weight = 1.f;
        }
    }

    // The row's solid angle per pixel, exactly: 2π/W (cos θ0 − cos θ1).
    double pixelSolidAngle(int row) const {
        return 2.0 * kPi / mWidth *
               (std::cos(kPi * row / double(mHeight)) -
                std::cos(kPi * (row + 1) / double(mHeight)));
    }
    Vec3 pixelDirection(int i, int j) const {
        return latLongDirection((i + 0.5f) / mWidth, (j + 0.5f) / mHeight, mRotation);
    }

    // A sun in the map: the power within kSunRadius of the brightest pixel, if it holds at
    // least kSunShare of the dome's. Then a strongly forward medium's paths are guided towards
    // it (render/light_lobes.h), as they are towards a distant light: the light a cloud's
    // vertex receives through its forward lobe from a small, bright sun is what its phase
    // samples find rarely and brightly.
    void findSun() {
        const float kSunRadius = radians(5.f);
        constexpr double kSunShare = 0.5;
        if (!(mTotal > 0.0)) return;
        const size_t brightest =
            size_t(std::max_element(mPixelPower.begin(), mPixelPower.end()) - mPixelPower.begin());
        const Vec3 centre = pixelDirection(int(brightest % mWidth), int(brightest / mWidth));
        const float cosRadius = std::cos(kSunRadius);
        double power = 0.0;
        Vec3d mean(0.0);
        for (int j = 0; j < mHeight; ++j) {
            const double dOmega = pixelSolidAngle(j);
            for (int i = 0; i < mWidth; ++i) {
                const Vec3 d = pixelDirection(i, j);
                if (dot(d, centre) < cosRadius) continue;
                const double p = mPixelPower[size_t(j) * mWidth + i] * dOmega;
                power += p;
                mean = mean + Vec3d(d.x, d.y, d.z) * p;
            }
        }
        if (power < kSunShare * mTotal) return;
        mSun = LightLobe{normalize(Vec3(mean)), float(power / (kLambdaMax - kLambdaMin))};
    }

    // A direction ∝ p(ω), with its density and, for an image, the pixel drawn (*texel).
    Vec3 sampleDirection(float u1, float u2, float* pdf, size_t* texel = nullptr) const {
        if (mDistribution.empty()) {
            *pdf = kInv4Pi;
            return sampleUniformSphere(u1, u2);
        }
        float u, v, pdfUv;
        mDistribution.sample(u1, u2, &u, &v, &pdfUv, texel);
        const float sinT = std::sin(kPi * v);
        *pdf = sinT > 0.f ? pdfUv * kInv2Pi2 / sinT : 0.f;
        return latLongDirection(u, v, mRotation);
    }

    size_t pixelAt(float u, float v) const {
        const int i = std::min(mWidth - 1, int(u * mWidth));
        const int j = std::min(mHeight - 1, int(v * mHeight));
        return size_t(j) * mWidth + i;
    }
    size_t pixel(const Vec3& d) const {
        float u, v;
        latLongCoordinates(d, mRotation, &u, &v);
        return pixelAt(u, v);
    }

    SampledSpectrum texelRadiance(const Texel& t, const SampledWavelengths& w) const {
        return mBasis[0].sample(w) * t.c.x + mBasis[1].sample(w) * t.c.y +
               mBasis[2].sample(w) * t.c.z;
    }
    SampledSpectrum radiance(const Vec3& d, const SampledWavelengths& w) const {
        if (mDistribution.empty()) return mConstant.sample(w);
        return texelRadiance(mTexels[pixel(d)], w);
    }

    // λ ∝ Σ c_k B_k(λ): the window k by its share c_k ∫B_k of the pixel's power, then λ in it.
    float sampleBasis(const Vec3& c, float power, float u) const {
        float acc = 0.f;
        for (int k = 0; k < 3; ++k) {
            const float share = float(c[k] * mBasisLambda[k].integral()) / power;
            if (u < acc + share || k == 2) {
                const float uk = share > 0.f ? clamp((u - acc) / share, 0.f, 0x1.fffffep-1f) : 0.5f;
                return mBasisLambda[k].sample(uk);
            }
            acc += share;
        }
        return mBasisLambda[2].sample(u);
    }

    DomeSettings mSettings;
    float mRotation;      // radians
    double mTotal = 0.0;  // ∫∫ L dω dλ, W/m²
    // Constant dome.
    Spectrum mConstant;
    SpectrumSampler mConstantLambda;
    // Image dome.
    int mWidth = 0, mHeight = 0;
    std::array<Spectrum, 3> mBasis;
    std::array<SpectrumSampler, 3> mBasisLambda;
    std::vector<Texel> mTexels;
    std::vector<float> mPixelPower;  // ∫ L dλ per pixel, W·m⁻²·sr⁻¹
    Distribution2D mDistribution;    // empty for the constant dome
    std::optional<LightLobe> mSun;   // findSun
};

// The dome's projection map: light from each direction crosses the targets' discs facing it
// (DiscUnion). A photon draws its direction as the dome's own do, then a point of the discs'
// union from their mixture (density c/Σ πR_k²), so that power() = Σ πR_k² ∫∫ L dω dλ with the
// weight of the direction over the coverage c.
class DomeProjection : public PhotonProjection {
public:
    DomeProjection(const DomeLight& dome, const ProjectionTargets& t)
        : mDome(dome), mDiscs(t.spheres), mScene(t.scene) {}
    double power() const override { return mDiscs.areaSum() * mDome.mTotal; }
    bool emit(Sampler& s, PhotonEmission* out) const override {
        const float u1 = s.get1D(), u2 = s.get1D();
        float pdf;
        const Vec3 d = mDome.sampleDirection(u1, u2, &pdf);
        if (!(pdf > 0.f)) return false;
        const float pick = s.get1D(), u3 = s.get1D(), u4 = s.get1D();
        int coverage;
        out->direction = -d;
        out->origin = upstreamOfScene(
            mScene, mDiscs.sample(out->direction, pick, u3, u4, &coverage), out->direction);
        mDome.colour(d, pdf, s.get1D(), out);
        out->weight /= float(coverage);
        return out->weight > 0.f;
    }

private:
    const DomeLight& mDome;
    DiscUnion mDiscs;
    Bounds3 mScene;
};

std::unique_ptr<PhotonProjection> DomeLight::projection(const ProjectionTargets& t) const {
    if (t.spheres.empty() || t.scene.empty() || !(mTotal > 0.0)) return nullptr;
    return std::make_unique<DomeProjection>(*this, t);
}

}  // namespace

LatLongImage readLatLongImage(const std::string& path) {
    RadianceHdr hdr;
    if (readRadianceHdr(path, &hdr)) return LatLongImage{hdr.width, hdr.height, std::move(hdr.rgb)};
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw MirageError(path + ": cannot read the dome image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    LatLongImage img;
    img.width = spec.width;
    img.height = spec.height;
    const int channels = spec.nchannels;
    if (img.width <= 0 || img.height <= 0 || channels <= 0)
        throw MirageError(path + ": the dome image is empty");
    std::vector<float> all(size_t(img.width) * img.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeFloat, all.data()))
        throw MirageError(path + ": cannot read the dome image: " + in->geterror());
    img.rgb.resize(size_t(img.width) * img.height * 3);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
        for (int k = 0; k < 3; ++k)
            img.rgb[3 * p + k] = all[p * channels + std::min(k, channels - 1)];
    return img;
}

std::unique_ptr<Light> makeDomeLight(const Spectrum& radiance, const DomeSettings& settings) {
    return std::make_unique<DomeLight>(radiance, settings);
}

std::unique_ptr<Light> makeDomeLight(const LatLongImage& image, float intensity,
                                     const Mat3& xyzToWorking, const DomeSettings& settings,
                                     const std::string& source) {
    const std::string name = source.empty() ? "dome image" : source;
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != size_t(image.width) * image.height * 3)
        throw MirageError(name + ": expected a non-empty RGB image");
    for (size_t p = 0; p < image.rgb.size(); ++p)
        if (!std::isfinite(image.rgb[p]) || image.rgb[p] < 0.f)
            throw MirageError(name + ": pixel (" + std::to_string((p / 3) % image.width) + ", " +
                              std::to_string((p / 3) / image.width) +
                              ") is negative or not finite; expected scene-linear radiance ≥ 0");
    return std::make_unique<DomeLight>(image, intensity, xyzToWorking, settings);
}

}  // namespace mirage
