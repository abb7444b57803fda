#include "medium/medium.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace mirage {

namespace {

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

void checkComponentCount(const ShaderDesc& shader) {
    if (shader.components.empty() || int(shader.components.size()) > kMaxComponents)
        throw MirageError("shader '" + shader.name + "': expected 1 to " +
                          std::to_string(kMaxComponents) + " components, found " +
                          std::to_string(shader.components.size()));
}

// Upper bound over all wavelengths of σt of a chlorophyll component at concentration C:
// σa(λ) = A(λ) C^e(λ) and σs(λ) = b(λ) C^s with A, e, b linear between whole nanometres (the
// dense form of Spectrum). Within one such interval C^e is monotone in λ, so its maximum is at
// an end, and the product is bounded by the larger A times the larger C^e of the two ends.
class PowerLawBound {
public:
    explicit PowerLawBound(const MediumComponent& c)
        : mSigmaSMax(c.sigmaS.maxValue()), mExponentS(c.sigmaSExponent) {
        for (int i = 0; i + 1 < Spectrum::kDenseSamples; ++i) {
            float l0 = kLambdaMin + float(i), l1 = l0 + 1.f;
            float e0 = c.sigmaAExponent(l0), e1 = c.sigmaAExponent(l1);
            mIntervals.push_back({std::max(c.sigmaA(l0), c.sigmaA(l1)), std::min(e0, e1),
                                  std::max(e0, e1)});
        }
    }
    // Non-decreasing in C (every exponent is ≥ 0). The relative margin covers float exp/log.
    float operator()(float C) const {
        if (!(C > 0.f)) return 0.f;
        double lc = std::log(double(C)), m = 0.0;
        for (const Interval& iv : mIntervals)
            m = std::max(m, iv.aMax * std::exp((lc >= 0.0 ? iv.eMax : iv.eMin) * lc));
        return float((m + mSigmaSMax * std::exp(mExponentS * lc)) * (1.0 + 1e-4));
    }

private:
    struct Interval {
        double aMax, eMin, eMax;
    };
    std::vector<Interval> mIntervals;
    double mSigmaSMax, mExponentS;
};

// PowerLawBound on the grid values of a majorant's cells, through a table at geometrically
// spaced concentrations (ratio 10^(4/255) ≈ 1.037) from 1e-4 × the largest to the largest: a
// cell gets the bound at the next tabulated C above its own, which is ≥ its bound because the
// bound grows with C. 256 × 470 exponentials instead of one PowerLawBound per cell.
class TabulatedBound {
public:
    TabulatedBound(const PowerLawBound& f, float cMax) : mF(f) {
        mC0 = cMax * 1e-4f;
        mLogStep = std::log(1e4) / (kSize - 1);
        for (int k = 0; k < kSize; ++k) {
            mC[k] = float(mC0 * std::exp(k * mLogStep));
            mValue[k] = f(mC[k]);
        }
        mC[kSize - 1] = cMax;
        mValue[kSize - 1] = f(cMax);
    }
    float operator()(float C) const {
        if (!(C > 0.f)) return 0.f;
        if (!(mC0 > 0.0)) return mF(C);  // an empty grid: no table
        int k = C <= mC0 ? 0 : int(std::ceil(std::log(double(C) / mC0) / mLogStep));
        k = std::max(k - 1, 0);
        while (k < kSize && mC[k] < C) ++k;  // the first tabulated C ≥ C, despite rounding
        return k < kSize ? mValue[k] : mF(C);
    }

private:
    static constexpr int kSize = 256;
    const PowerLawBound& mF;
    double mC0, mLogStep;
    std::array<float, kSize> mC, mValue;
};

}  // namespace

Medium::Medium(ShaderDesc shader, std::vector<FloatGrid> grids, const Transform& objectToWorld,
               float densityScale, int majorantResolution)
    : mShader(std::move(shader)),
      mGrids(std::move(grids)),
      mObjectToWorld(objectToWorld),
      mWorldToObject(objectToWorld.inverse()),
      mDensityScale(densityScale) {
    checkComponentCount(mShader);
    auto slots = mShader.gridSlots();
    MIRAGE_CHECK(slots.size() == mGrids.size());

    // Object bounds: union of the grids the components read. A medium made only of
    // homogeneous components has no extent of its own and is rejected by the scene loader.
    Bounds3 objectBounds;
    for (const auto& c : mShader.components) {
        if (c.grid.empty()) continue;
        size_t slot = std::find(slots.begin(), slots.end(), c.grid) - slots.begin();
        objectBounds.expand(mGrids[slot].objectBounds());
    }
    if (objectBounds.empty())
        throw MirageError("shader '" + mShader.name +
                          "': no component reads a grid with active voxels, so the medium has "
                          "no extent");
    buildMajorantAndPhases(objectBounds, majorantResolution);
}

Medium::Medium(ShaderDesc shader, const Bounds3& objectBox, const Transform& objectToWorld,
               float densityScale)
    : mShader(std::move(shader)),
      mObjectToWorld(objectToWorld),
      mWorldToObject(objectToWorld.inverse()),
      mDensityScale(densityScale) {
    checkComponentCount(mShader);
    for (const auto& c : mShader.components)
        if (!c.grid.empty())
            throw MirageError("shader '" + mShader.name + "': component '" + c.name +
                              "' reads grid '" + c.grid +
                              "', but a homogeneous medium has no grids");
    if (mShader.emission)
        throw MirageError("shader '" + mShader.name +
                          "': emission needs a temperature grid, which a homogeneous medium "
                          "does not have");
    if (objectBox.empty() || !isFinite(objectBox.lo) || !isFinite(objectBox.hi))
        throw MirageError("shader '" + mShader.name +
                          "': a homogeneous medium needs a finite, non-empty box");
    // One majorant cell: the coefficients are the same everywhere in the box.
    buildMajorantAndPhases(objectBox, 1);
}

void Medium::buildMajorantAndPhases(const Bounds3& objectBounds, int majorantResolution) {
    mWorldBounds = mObjectToWorld.apply(objectBounds);

    // Majorant: Σ_c concentration_c · max_λ(σa,c + σs,c) · max of the grid over each cell.
    auto slots = mShader.gridSlots();
    mMajorant = MajorantGrid(objectBounds, majorantResolution);
    bool greyAll = true;
    double sigmaMax = 0.0;  // the largest σt anywhere, summed over components, 1/m
    for (const auto& c : mShader.components) {
        const float k = c.concentration * mDensityScale;
        const FloatGrid* grid = nullptr;
        if (!c.grid.empty())
            grid = &mGrids[std::find(slots.begin(), slots.end(), c.grid) - slots.begin()];
        sigmaMax += checkedSigmaMax(c, grid, k);
        if (c.kind == ComponentKind::Chlorophyll) {
            // σ is non-linear in C: bound it at each cell's largest C = k × grid max.
            PowerLawBound bound(c);
            if (!grid) {
                mMajorant.addConstant(bound(k));
            } else {
                TabulatedBound table(bound, k * grid->maxValue());
                mMajorant.addGridMonotone(*grid, [&](float v) { return table(k * v); });
            }
        } else {
            float scale = k * (c.sigmaA.maxValue() + c.sigmaS.maxValue());
            if (!grid) mMajorant.addConstant(scale);
            else mMajorant.addGrid(*grid, scale);
        }
        mPhases.emplace_back(c.phase, c.g, c.g2, c.phaseWeight);
        greyAll &= c.kind != ComponentKind::Chlorophyll && c.sigmaA.isConstant() &&
                   c.sigmaS.isConstant() && !c.fluorescent();
        mFluorescent |= c.fluorescent();
        mFluorescence.push_back(c.fluorescent() ? FluorescenceEmission(c.emissionPeakNm,
                                                                       c.emissionFwhmNm,
                                                                       c.antiStokes)
                                                : FluorescenceEmission());
    }
    mGreyCoefficients = greyAll;
    if (!(sigmaMax <= kMaxSigma))
        throw MirageError("shader '" + mShader.name + "': its components sum to σt up to " +
                          formatNumber(sigmaMax) + " 1/m, above the limit of " +
                          formatNumber(kMaxSigma) + " 1/m; lower density_scale");
    checkEmissionBound(sigmaMax);
}

// The emission term σa·Le (W·m⁻³·sr⁻¹·nm⁻¹) at the hottest voxel, bounded by σt·max_λ B(λ, T):
// refused above kMaxSigma as well, where a hot grid (voxels up to kMaxVoxelValue K), a large
// intensity and a dense medium would multiply past float's range and every emitting sample
// would be dropped as non-finite.
void Medium::checkEmissionBound(double sigmaMax) const {
    if (!mShader.emission || mGrids.empty()) return;
    const EmissionSpec& e = *mShader.emission;
    auto slots = mShader.gridSlots();
    size_t slot = std::find(slots.begin(), slots.end(), e.temperatureGrid) - slots.begin();
    if (slot >= mGrids.size()) return;
    double T = double(mGrids[slot].maxValue()) * e.temperatureScale + e.temperatureOffset;
    double leMax = 0.0;  // Planck's maximum over the visible: sampled every 5 nm
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5.f)
        leMax = std::max(leMax, planck(l, T) * 1e-9 * e.intensity);
    if (!(sigmaMax * leMax <= kMaxSigma))
        throw MirageError("shader '" + mShader.name + "': emission σa·Le up to " +
                          formatNumber(sigmaMax * leMax) + " W/(m³·sr·nm) at " +
                          formatNumber(T) + " K (grid '" + mGrids[slot].name() +
                          "') is above the limit of " + formatNumber(kMaxSigma) +
                          "; lower the temperature scale, intensity or density");
}

// The largest σt = σa + σs of one component anywhere in the medium, in double so that the
// product cannot overflow before it is compared. Refuses (MirageError naming the shader,
// component and grid) a product above kMaxSigma: beyond it, float sums of σ, optical depths
// and σa·Le overflow to ∞ and every estimate that touches the medium is lost.
double Medium::checkedSigmaMax(const MediumComponent& c, const FloatGrid* grid, float k) const {
    const double gridMax = grid ? double(grid->maxValue()) : 1.0;
    double sigma = c.kind == ComponentKind::Chlorophyll
                       ? double(PowerLawBound(c)(float(std::min(double(k) * gridMax, 3e38))))
                       : double(k) * gridMax * (double(c.sigmaA.maxValue()) + c.sigmaS.maxValue());
    if (!(sigma <= kMaxSigma))
        throw MirageError("shader '" + mShader.name + "': component '" + c.name + "'" +
                          (grid ? " on grid '" + grid->name() + "' (max value " +
                                      formatNumber(gridMax) + ")"
                                : std::string()) +
                          ": σt up to " + formatNumber(sigma) +
                          " 1/m (concentration × density_scale × grid × cross-section) is above "
                          "the limit of " + formatNumber(kMaxSigma) +
                          " 1/m; lower density_scale, concentration or the cross-sections");
    return sigma;
}

Medium::Context::Context(const Medium& m) : mMedium(&m) {
    auto slots = m.mShader.gridSlots();
    for (const auto& g : m.mGrids) mAcc.push_back(g.accessor());
    for (size_t i = 0; i < m.mShader.components.size(); ++i) {
        const auto& c = m.mShader.components[i];
        mSlot[i] = c.grid.empty()
                       ? -1
                       : int(std::find(slots.begin(), slots.end(), c.grid) - slots.begin());
    }
    if (m.mShader.emission)
        mTemperatureSlot = int(std::find(slots.begin(), slots.end(),
                                         m.mShader.emission->temperatureGrid) -
                               slots.begin());
    // Grey: the coefficients do not depend on λ, so they are set here once, at any λ.
    if (m.greyPath()) {
        setWavelengths(SampledWavelengths::sampleVisible(0.5f));
        mGrey = true;
    }
}

void Medium::Context::setWavelengths(const SampledWavelengths& w) {
    mLambda = w;
    if (mGrey) return;  // σ(λ) is constant: nothing to re-sample
    const auto& comps = mMedium->mShader.components;
    for (size_t i = 0; i < comps.size(); ++i) {
        float k = comps[i].concentration * mMedium->mDensityScale;
        mPowerLaw[i] = comps[i].kind == ComponentKind::Chlorophyll;
        mScale[i] = k;
        // What depends only on λ is evaluated here, once per path, not per lookup.
        float linear = mPowerLaw[i] ? 1.f : k;
        mSigmaA[i] = comps[i].sigmaA.sample(w) * linear;
        mSigmaS[i] = comps[i].sigmaS.sample(w) * linear;
        if (mPowerLaw[i]) mExponentA[i] = comps[i].sigmaAExponent.sample(w);
    }
}

void Medium::confineTo(std::shared_ptr<const Region> region) {
    mRegion = std::move(region);
    if (!mRegion) return;
    // The medium's world bounds (the photon pass aims sun photons at them) shrink to the region
    // (empty when the two do not overlap: then the medium is nowhere).
    const Bounds3 r = mRegion->bounds();
    mWorldBounds.lo = vmax(mWorldBounds.lo, r.lo);
    mWorldBounds.hi = vmin(mWorldBounds.hi, r.hi);
}

void Medium::excludeFrom(std::shared_ptr<const Region> region) {
    if (region) mExcluded.push_back(std::move(region));
}

void Medium::eval(const Vec3& p, Context& ctx, MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(mShader.components.size());
    if (!inRegion(p)) {
        for (int i = 0; i < out->components; ++i) out->sigmaSComponent[i] = SampledSpectrum(0.f);
        out->Le = SampledSpectrum(0.f);
        return;
    }
    evalUnconfined(p, ctx, out);
}

void Medium::evalUnconfined(const Vec3& p, Context& ctx, MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(mShader.components.size());
    if (ctx.mGrey) {
        // One number per component, broadcast to the path's wavelengths once.
        float sigmaA = 0.f, sigmaS = 0.f;
        for (int i = 0; i < out->components; ++i) {
            int slot = ctx.mSlot[i];
            float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
            float s = ctx.mSigmaS[i][0] * c;
            sigmaA += ctx.mSigmaA[i][0] * c;
            sigmaS += s;
            if (out->components > 1) out->sigmaSComponent[i] = SampledSpectrum(s);
        }
        out->sigmaA = SampledSpectrum(sigmaA);
        out->sigmaS = SampledSpectrum(sigmaS);
        if (out->components == 1) out->sigmaSComponent[0] = out->sigmaS;
    } else {
        for (int i = 0; i < out->components; ++i) {
            int slot = ctx.mSlot[i];
            float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
            if (ctx.mPowerLaw[i]) {
                powerLawAt(ctx, i, c, &out->sigmaA, &out->sigmaSComponent[i]);
            } else {
                out->sigmaA += ctx.mSigmaA[i] * c;
                out->sigmaSComponent[i] = ctx.mSigmaS[i] * c;
            }
            out->sigmaS += out->sigmaSComponent[i];
        }
    }
    out->Le = SampledSpectrum(0.f);
    if (ctx.mTemperatureSlot >= 0 && !out->sigmaA.isZero()) {
        const EmissionSpec& e = *mShader.emission;
        float T = mGrids[ctx.mTemperatureSlot].sample(ctx.mAcc[ctx.mTemperatureSlot], p) *
                      e.temperatureScale +
                  e.temperatureOffset;
        if (T > e.minTemperature) {
            // Planck gives W·m⁻²·sr⁻¹ per metre of wavelength; the film integrates per nm.
            for (int i = 0; i < kSpectrumSamples; ++i)
                out->Le[i] = float(planck(ctx.mLambda.lambda[i], T) * 1e-9) * e.intensity;
        }
    }
}

void Medium::powerLawAt(const Context& ctx, int i, float gridValue, SampledSpectrum* sigmaA,
                        SampledSpectrum* sigmaS) const {
    // C^e = exp(e ln C): one logarithm for the four wavelengths and both coefficients.
    float C = ctx.mScale[i] * gridValue;
    if (!(C > 0.f)) {
        *sigmaS = SampledSpectrum(0.f);
        return;
    }
    float lc = std::log(C);
    for (int j = 0; j < kSpectrumSamples; ++j)
        (*sigmaA)[j] += ctx.mSigmaA[i][j] * std::exp(ctx.mExponentA[i][j] * lc);
    *sigmaS = ctx.mSigmaS[i] * std::exp(mShader.components[i].sigmaSExponent * lc);
}

float Medium::sigmaSAt(const Vec3& p, Context& ctx, float lambdaNm) const {
    float sigmaS = 0.f;
    if (!inRegion(p)) return 0.f;
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        const MediumComponent& comp = mShader.components[i];
        float xs = comp.sigmaS(lambdaNm);
        if (xs == 0.f) continue;
        int slot = ctx.mSlot[i];
        float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
        float C = c * comp.concentration * mDensityScale;
        if (comp.kind == ComponentKind::Chlorophyll)
            sigmaS += C > 0.f ? xs * std::pow(C, comp.sigmaSExponent) : 0.f;
        else
            sigmaS += C * xs;
    }
    return sigmaS;
}

void Medium::sigmaAComponentsAt(const Vec3& p, Context& ctx, float lambdaNm,
                                float* sigmaA) const {
    const bool inside = inRegion(p);
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        if (!inside) {
            sigmaA[i] = 0.f;
            continue;
        }
        const MediumComponent& comp = mShader.components[i];
        int slot = ctx.mSlot[i];
        float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
        float C = c * comp.concentration * mDensityScale;
        if (comp.kind == ComponentKind::Chlorophyll)
            sigmaA[i] = C > 0.f ? comp.sigmaA(lambdaNm) *
                                      std::pow(C, comp.sigmaAExponent(lambdaNm))
                                : 0.f;
        else
            sigmaA[i] = C * comp.sigmaA(lambdaNm);
    }
}

SampledSpectrum Medium::phaseEval(const MediumPoint& mp, const Vec3& wi, const Vec3& wo) const {
    float cosTheta = dot(wi, wo);
    if (mp.components == 1) return SampledSpectrum(mPhases[0].eval(cosTheta));
    SampledSpectrum sum(0.f);
    for (int i = 0; i < mp.components; ++i)
        sum += mp.sigmaSComponent[i] * mPhases[i].eval(cosTheta);
    return safeDiv(sum, mp.sigmaS);
}

Vec3 Medium::phaseSample(const MediumPoint& mp, const Vec3& wi, float uc, float u1, float u2,
                         SampledSpectrum* weight, float* pdf) const {
    if (mp.components == 1) {
        Vec3 wo = mPhases[0].sample(wi, u1, u2, pdf);
        *weight = SampledSpectrum(1.f);
        return wo;
    }
    // Choose a lobe ∝ mean σs,c; the pdf of the resulting direction is the mixture of lobes.
    float total = mp.sigmaS.average();
    int chosen = mp.components - 1;
    float acc = 0.f;
    for (int i = 0; i < mp.components; ++i) {
        acc += mp.sigmaSComponent[i].average();
        if (uc * total < acc) { chosen = i; break; }
    }
    Vec3 wo = mPhases[chosen].sample(wi, u1, u2, nullptr);
    float cosTheta = dot(wi, wo), mixPdf = 0.f;
    for (int i = 0; i < mp.components; ++i)
        mixPdf += mp.sigmaSComponent[i].average() / total * mPhases[i].eval(cosTheta);
    *pdf = mixPdf;
    *weight = mixPdf > 0.f ? phaseEval(mp, wi, wo) / mixPdf : SampledSpectrum(0.f);
    return wo;
}

}  // namespace mirage
