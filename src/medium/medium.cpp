#include "medium/medium.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "volume/grid_lookup.h"

namespace mirage {

namespace {

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// The longest displacement over the shutter a velocity grid may give, in units of the
// medium's own size (the diagonal of its bounds).
constexpr double kMaxBlurToSize = 100.0;

// A homogeneous medium's shader reads no grid and does not emit (emission reads a temperature
// grid); refused before it is bound, so that the message says why.
ShaderDesc homogeneousShader(ShaderDesc shader) {
    if (shader.components.empty() || int(shader.components.size()) > kMaxComponents)
        return shader;  // the binding refuses it
    for (const auto& c : shader.components)
        if (!c.grid.empty())
            throw MirageError("shader '" + shader.name + "': component '" + c.name +
                              "' reads grid '" + c.grid +
                              "', but a homogeneous medium has no grids");
    if (shader.emission)
        throw MirageError("shader '" + shader.name +
                          "': emission needs a temperature grid, which a homogeneous medium "
                          "does not have");
    return shader;
}

}  // namespace

Medium::Medium(ShaderDesc shader, std::vector<FloatGrid> grids, const Transform& objectToWorld,
               float densityScale, int majorantResolution)
    : mBinding(std::move(shader), std::move(grids), densityScale),
      mObjectToWorld(objectToWorld),
      mWorldToObject(objectToWorld.inverse()) {
    // Object bounds: union of the grids the components read. A medium made only of
    // homogeneous components has no extent of its own and is rejected by the scene loader.
    Bounds3 objectBounds;
    for (size_t i = 0; i < mBinding.shader().components.size(); ++i)
        if (const FloatGrid* grid = mBinding.componentGrid(int(i)))
            objectBounds.expand(grid->objectBounds());
    if (objectBounds.empty())
        throw MirageError("shader '" + mBinding.shader().name +
                          "': no component reads a grid with active voxels, so the medium has "
                          "no extent");
    buildMajorantAndPhases(objectBounds, majorantResolution);
}

Medium::Medium(ShaderDesc shader, const Bounds3& objectBox, const Transform& objectToWorld,
               float densityScale)
    : mBinding(homogeneousShader(std::move(shader)), {}, densityScale),
      mObjectToWorld(objectToWorld),
      mWorldToObject(objectToWorld.inverse()) {
    if (objectBox.empty() || !isFinite(objectBox.lo) || !isFinite(objectBox.hi))
        throw MirageError("shader '" + mBinding.shader().name +
                          "': a homogeneous medium needs a finite, non-empty box");
    // One majorant cell: the coefficients are the same everywhere in the box.
    buildMajorantAndPhases(objectBox, 1);
}

// Majorant: Σ_c of each component's bound at the largest concentration in each cell.
void Medium::fillMajorant(const Bounds3& objectBounds, int majorantResolution) {
    mMajorant = MajorantGrid(objectBounds, majorantResolution);
    const auto& comps = shader().components;
    for (size_t i = 0; i < comps.size(); ++i)
        mBinding.componentModel(int(i)).addToMajorant(
            &mMajorant, mBinding.componentGrid(int(i)),
            comps[i].concentration * mBinding.densityScale());
}

void Medium::updateWorldBounds() {
    mWorldBounds = mMotion.sweep(mMajorant.bounds(), mObjectToWorld);
    // The medium's world bounds (the photon pass aims sun photons at them) shrink to its region
    // (empty when the two do not overlap: then the medium is nowhere).
    mWorldBounds = mConfinement.clipBounds(mWorldBounds);
}

void Medium::buildMajorantAndPhases(const Bounds3& objectBounds, int majorantResolution) {
    mStillBounds = objectBounds;
    mMajorantResolution = majorantResolution;
    fillMajorant(objectBounds, majorantResolution);
    updateWorldBounds();

    bool greyAll = true;
    double sigmaMax = 0.0;  // the largest σt anywhere, summed over components, 1/m
    for (size_t i = 0; i < shader().components.size(); ++i) {
        const MediumComponent& c = shader().components[i];
        const float k = c.concentration * mBinding.densityScale();
        sigmaMax += checkedSigmaMax(int(i), mBinding.componentGrid(int(i)), k);
        mPhases.emplace_back(c.phase, c.g, c.g2, c.phaseWeight);
        mPeakPhase = std::max(mPeakPhase, mPhases.back().eval(1.f));
        greyAll &= mBinding.componentModel(int(i)).grey() && !c.fluorescent();
        mFluorescent |= c.fluorescent();
        mFluorescence.push_back(
            !c.fluorescent() ? FluorescenceEmission()
            : c.emissionMatrix
                ? FluorescenceEmission(*c.emissionMatrix, c.antiStokes)
                : FluorescenceEmission(c.emissionPeakNm, c.emissionFwhmNm, c.antiStokes));
    }
    mGreyCoefficients = greyAll;
    if (!(sigmaMax <= kMaxSigma))
        throw MirageError("shader '" + shader().name + "': its components sum to σt up to " +
                          formatNumber(sigmaMax) + " 1/m, above the limit of " +
                          formatNumber(kMaxSigma) + " 1/m; lower density_scale");
    checkEmissionBound(sigmaMax);
}

// The emission term σa·Le (W·m⁻³·sr⁻¹·nm⁻¹) at the hottest voxel, bounded by σt·max_λ B(λ, T):
// refused above kMaxSigma as well, where a hot grid (voxels up to kMaxVoxelValue K), a large
// intensity and a dense medium would multiply past float's range and every emitting sample
// would be dropped as non-finite.
void Medium::checkEmissionBound(double sigmaMax) const {
    if (!shader().emission || homogeneous()) return;
    const EmissionSpec& e = *shader().emission;
    if (mBinding.temperatureSlot() < 0) return;
    const FloatGrid& temperature = mBinding.grids()[size_t(mBinding.temperatureSlot())];
    double T = double(temperature.maxValue()) * e.temperatureScale + e.temperatureOffset;
    double leMax = 0.0;  // Planck's maximum over the visible: sampled every 5 nm
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5.f)
        leMax = std::max(leMax, planck(l, T) * 1e-9 * e.intensity);
    if (!(sigmaMax * leMax <= kMaxSigma))
        throw MirageError("shader '" + shader().name + "': emission σa·Le up to " +
                          formatNumber(sigmaMax * leMax) + " W/(m³·sr·nm) at " + formatNumber(T) +
                          " K (grid '" + temperature.name() + "') is above the limit of " +
                          formatNumber(kMaxSigma) +
                          "; lower the temperature scale, intensity or density");
}

// The largest σt = σa + σs of one component anywhere in the medium, in double so that the
// product cannot overflow before it is compared. Refuses (MirageError naming the shader,
// component and grid) a product above kMaxSigma: beyond it, float sums of σ, optical depths
// and σa·Le overflow to ∞ and every estimate that touches the medium is lost.
double Medium::checkedSigmaMax(int i, const FloatGrid* grid, float k) const {
    const MediumComponent& c = shader().components[size_t(i)];
    const double gridMax = grid ? double(grid->maxValue()) : 1.0;
    const double sigma = mBinding.componentModel(i).sigmaTBound(double(k) * gridMax);
    if (!(sigma <= kMaxSigma))
        throw MirageError(
            "shader '" + shader().name + "': component '" + c.name + "'" +
            (grid ? " on grid '" + grid->name() + "' (max value " + formatNumber(gridMax) + ")"
                  : std::string()) +
            ": σt up to " + formatNumber(sigma) +
            " 1/m (concentration × density_scale × grid × cross-section) is above "
            "the limit of " +
            formatNumber(kMaxSigma) +
            " 1/m; lower density_scale, concentration or the cross-sections");
    return sigma;
}

Medium::Context::Context(const Medium& m)
    : mMedium(&m), mMotion(m.mMotion, m.mObjectToWorld, m.mWorldToObject) {
    const ShaderBinding& b = m.mBinding;
    for (const auto& g : b.grids()) mAcc.push_back(g.accessor());
    for (size_t i = 0; i < b.shader().components.size(); ++i) {
        mSlot[i] = b.componentSlot(int(i));
        mModel[i] = &b.componentModel(int(i));
    }
    mTemperatureSlot = b.temperatureSlot();
    // Grey: the coefficients do not depend on λ, so they are set here once, at any λ.
    if (m.greyPath()) {
        setWavelengths(SampledWavelengths::sampleVisible(0.5f));
        mGrey = true;
    }
}

Medium::Context::Context(Context&&) noexcept = default;
Medium::Context& Medium::Context::operator=(Context&&) noexcept = default;
Medium::Context::~Context() = default;

void Medium::Context::setWavelengths(const SampledWavelengths& w) {
    mLambda = w;
    if (mGrey) return;  // σ(λ) is constant: nothing to re-sample
    // What depends only on λ is evaluated here, once per path, not per lookup.
    const auto& comps = mMedium->shader().components;
    for (size_t i = 0; i < comps.size(); ++i)
        mModel[i]->sampleWavelengths(w, comps[i].concentration * mMedium->mBinding.densityScale(),
                                     &mPath[i]);
}

void Medium::setConfinement(Confinement confinement) {
    mConfinement = std::move(confinement);
    updateWorldBounds();
}

void Medium::setMotion(MediumMotion motion) {
    if (homogeneous()) motion.setVelocity(VectorGrid(), 1.f, 0.f);
    checkBlurRadius(motion);
    mMotion = std::move(motion);
    if (mMotion.moving()) dilateMajorant();
    updateWorldBounds();
}

// A displacement far beyond the medium's size smears it over a box the majorant grid cannot
// resolve (a few cells, each as dense as the densest voxel), and tracking then crawls through
// it: almost always a unit mistake (cm/s read as m/s, a frame count taken for seconds), so it
// is refused with the figures that show it.
void Medium::checkBlurRadius(const MediumMotion& motion) const {
    const double R = double(motion.blurRadius());
    const double size = double(length(mStillBounds.diagonal()));
    if (R <= kMaxBlurToSize * size) return;
    const VectorGrid& v = motion.velocity();
    throw MirageError("velocity grid '" + v.name() + "': |v| up to " +
                      formatNumber(v.magnitudeBound()) + " m/s × velocity_scale " +
                      formatNumber(motion.velocityScale()) + " moves shader '" + shader().name +
                      "' up to " + formatNumber(R) + " m within the shutter, more than " +
                      formatNumber(kMaxBlurToSize) + " times its size (" + formatNumber(size) +
                      " m); velocities are in object units per second: check "
                      "velocity_scale, [output] fps and the shutter");
}

// σt at x and time Δt is the still σt at x − v·Δt, a point at most |v_a|·|Δt| away along each
// axis a: the maximum of the still majorant over the cells within that reach bounds it, over
// bounds grown by it. Per axis, so a rising plume's box grows mostly upwards.
void Medium::dilateMajorant() {
    const VectorGrid& velocity = mMotion.velocity();
    const float k = mMotion.reachPerVelocity();
    const Vec3 reach = velocity.componentBound() * k;
    Bounds3 grown = mStillBounds;
    grown.lo = grown.lo - reach;
    grown.hi = grown.hi + reach;
    fillMajorant(grown, mMajorantResolution);
    // Per cell, the reach of the velocity found in that cell: a fast jet then widens the
    // majorant only around itself, not across the whole cache.
    std::vector<Vec3> local = mMajorant.cellComponentBounds(velocity);
    for (Vec3& r : local) r = r * k;
    mMajorant.dilateLocally(local);
}

inline float Medium::gridValue(const Context& ctx, int i, const Vec3& p) const {
    int slot = ctx.mSlot[size_t(i)];
    return slot < 0 ? 1.f : mBinding.grids()[size_t(slot)].sample(ctx.mAcc[size_t(slot)], p);
}

inline bool Medium::inRegion(const Vec3& pObject, const Context& ctx) const {
    if (!mConfinement.confines()) return true;
    return mConfinement.contains(ctx.objectToWorld().point(pObject));
}

void Medium::eval(const Vec3& p, Context& ctx, MediumPoint* out) const {
    if (!inRegion(p, ctx)) return setZero(out);
    evalUnconfined(p, ctx, out);
}

void Medium::evalStill(const Vec3& p, Context& ctx, MediumPoint* out) const {
    if (!inRegion(p, ctx)) return setZero(out);
    evalGridsAt(p, ctx, out);
}

void Medium::setZero(MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(shader().components.size());
    for (int i = 0; i < out->components; ++i) out->sigmaSComponent[i] = SampledSpectrum(0.f);
    out->Le = SampledSpectrum(0.f);
    out->temperature = 0.f;
}

void Medium::evalUnconfined(const Vec3& pAtTime, Context& ctx, MediumPoint* out) const {
    evalGridsAt(ctx.mMotion.lookupPoint(pAtTime), ctx, out);
}

void Medium::evalGridsAt(const Vec3& p, Context& ctx, MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(shader().components.size());
    if (ctx.mGrey) {
        // One number per component, broadcast to the path's wavelengths once.
        float sigmaA = 0.f, sigmaS = 0.f;
        for (int i = 0; i < out->components; ++i) {
            float c = gridValue(ctx, i, p);
            float s = ctx.mPath[i].sigmaS[0] * c;
            sigmaA += ctx.mPath[i].sigmaA[0] * c;
            sigmaS += s;
            if (out->components > 1) out->sigmaSComponent[i] = SampledSpectrum(s);
        }
        out->sigmaA = SampledSpectrum(sigmaA);
        out->sigmaS = SampledSpectrum(sigmaS);
        if (out->components == 1) out->sigmaSComponent[0] = out->sigmaS;
    } else {
        for (int i = 0; i < out->components; ++i) {
            ctx.mModel[i]->evalPath(ctx.mPath[i], gridValue(ctx, i, p), &out->sigmaA,
                                    &out->sigmaSComponent[i]);
            out->sigmaS += out->sigmaSComponent[i];
        }
    }
    out->Le = SampledSpectrum(0.f);
    out->temperature = 0.f;
    if (ctx.mTemperatureSlot >= 0 && !out->sigmaA.isZero()) {
        const EmissionSpec& e = *shader().emission;
        float T = mBinding.grids()[size_t(ctx.mTemperatureSlot)].sample(
                      ctx.mAcc[ctx.mTemperatureSlot], p) *
                      e.temperatureScale +
                  e.temperatureOffset;
        if (T > e.minTemperature) {
            out->temperature = T;
            // Planck gives W·m⁻²·sr⁻¹ per metre of wavelength; the film integrates per nm.
            for (int i = 0; i < kSpectrumSamples; ++i)
                out->Le[i] = float(planck(ctx.mLambda.lambda[i], T) * 1e-9) * e.intensity;
        }
    }
}

float Medium::sigmaSAt(const Vec3& pAtTime, Context& ctx, float lambdaNm) const {
    float sigmaS = 0.f;
    if (!inRegion(pAtTime, ctx)) return 0.f;
    const Vec3 p = ctx.mMotion.lookupPoint(pAtTime);
    if (ctx.mGrey) {
        // The grey path's coefficients (set once in the context), as evalGridsAt reads them:
        // no spectrum or component law to evaluate per lookup (the photon estimates call this
        // once per photon they gather).
        for (size_t i = 0; i < shader().components.size(); ++i)
            if (ctx.mPath[i].sigmaS[0] > 0.f)
                sigmaS += ctx.mPath[i].sigmaS[0] * gridValue(ctx, int(i), p);
        return sigmaS;
    }
    for (size_t i = 0; i < shader().components.size(); ++i) {
        const MediumComponent& comp = shader().components[i];
        // A component that does not scatter at λ needs no grid lookup.
        if (comp.sigmaS(lambdaNm) == 0.f) continue;
        float C = gridValue(ctx, int(i), p) * comp.concentration * mBinding.densityScale();
        sigmaS += mBinding.componentModel(int(i)).sigmaS(C, lambdaNm);
    }
    return sigmaS;
}

void Medium::sigmaAComponentsAt(const Vec3& pAtTime, Context& ctx, float lambdaNm,
                                float* sigmaA) const {
    const bool inside = inRegion(pAtTime, ctx);
    const Vec3 p = ctx.mMotion.lookupPoint(pAtTime);
    for (size_t i = 0; i < shader().components.size(); ++i) {
        if (!inside) {
            sigmaA[i] = 0.f;
            continue;
        }
        const MediumComponent& comp = shader().components[i];
        float C = gridValue(ctx, int(i), p) * comp.concentration * mBinding.densityScale();
        sigmaA[i] = mBinding.componentModel(int(i)).sigmaA(C, lambdaNm);
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
        if (uc * total < acc) {
            chosen = i;
            break;
        }
    }
    Vec3 wo = mPhases[chosen].sample(wi, u1, u2, nullptr);
    const float mixPdf = phasePdf(mp, wi, wo);
    *pdf = mixPdf;
    *weight = mixPdf > 0.f ? phaseEval(mp, wi, wo) / mixPdf : SampledSpectrum(0.f);
    return wo;
}

float Medium::phasePdf(const MediumPoint& mp, const Vec3& wi, const Vec3& wo) const {
    const float cosTheta = dot(wi, wo);
    if (mp.components == 1) return mPhases[0].eval(cosTheta);
    const float total = mp.sigmaS.average();
    if (!(total > 0.f)) return 0.f;
    float mixPdf = 0.f;
    for (int i = 0; i < mp.components; ++i)
        mixPdf += mp.sigmaSComponent[i].average() / total * mPhases[i].eval(cosTheta);
    return mixPdf;
}

}  // namespace mirage
