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

void checkComponentCount(const ShaderDesc& shader) {
    if (shader.components.empty() || int(shader.components.size()) > kMaxComponents)
        throw MirageError("shader '" + shader.name + "': expected 1 to " +
                          std::to_string(kMaxComponents) + " components, found " +
                          std::to_string(shader.components.size()));
}

// The longest displacement over the shutter a velocity grid may give, in units of the
// medium's own size (the diagonal of its bounds).
constexpr double kMaxBlurToSize = 100.0;

std::string quotedList(const std::vector<std::string>& names) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "'" : ", '") + n + "'";
    return list;
}

}  // namespace

Medium::Medium(ShaderDesc shader, std::vector<FloatGrid> grids, const Transform& objectToWorld,
               float densityScale, int majorantResolution)
    : mShader(std::move(shader)),
      mGrids(std::move(grids)),
      mObjectToWorld(objectToWorld),
      mWorldToObject(objectToWorld.inverse()),
      mDensityScale(densityScale) {
    checkComponentCount(mShader);
    resolveSlots();

    // Object bounds: union of the grids the components read. A medium made only of
    // homogeneous components has no extent of its own and is rejected by the scene loader.
    Bounds3 objectBounds;
    for (int slot : mComponentSlot)
        if (slot >= 0) objectBounds.expand(mGrids[size_t(slot)].objectBounds());
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
    resolveSlots();
    if (objectBox.empty() || !isFinite(objectBox.lo) || !isFinite(objectBox.hi))
        throw MirageError("shader '" + mShader.name +
                          "': a homogeneous medium needs a finite, non-empty box");
    // One majorant cell: the coefficients are the same everywhere in the box.
    buildMajorantAndPhases(objectBox, 1);
}

// Every grid slot the shader names gets the index of its grid, once: the lookups index grids()
// directly. The slots are the shader's own (gridSlots), so a slot without a grid is a caller
// that bound fewer grids than the shader reads.
void Medium::resolveSlots() {
    const std::vector<std::string> slots = mShader.gridSlots();
    if (slots.size() != mGrids.size()) {
        std::vector<std::string> missing;
        for (size_t i = mGrids.size(); i < slots.size(); ++i) missing.push_back(slots[i]);
        throw MirageError(
            "shader '" + mShader.name + "' reads grid slot(s) " + quotedList(slots) + ", but " +
            std::to_string(mGrids.size()) + " grid(s) are bound" +
            (missing.empty() ? std::string() : "; no grid for " + quotedList(missing)));
    }
    auto indexOf = [&](const std::string& name) {
        if (name.empty()) return -1;
        return int(std::find(slots.begin(), slots.end(), name) - slots.begin());
    };
    for (const auto& c : mShader.components) {
        mComponentSlot.push_back(indexOf(c.grid));
        mModels.push_back(ComponentModel::make(c));
    }
    if (!mShader.emission) return;
    if (mShader.emission->temperatureGrid.empty())
        throw MirageError("shader '" + mShader.name +
                          "': [emission] names no temperature grid slot");
    mTemperatureSlot = indexOf(mShader.emission->temperatureGrid);
}

// Majorant: Σ_c of each component's bound at the largest concentration in each cell.
void Medium::fillMajorant(const Bounds3& objectBounds, int majorantResolution) {
    mMajorant = MajorantGrid(objectBounds, majorantResolution);
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        const int slot = mComponentSlot[i];
        mModels[i]->addToMajorant(&mMajorant, slot < 0 ? nullptr : &mGrids[size_t(slot)],
                                  mShader.components[i].concentration * mDensityScale);
    }
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
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        const MediumComponent& c = mShader.components[i];
        const float k = c.concentration * mDensityScale;
        const int slot = mComponentSlot[i];
        const FloatGrid* grid = slot < 0 ? nullptr : &mGrids[size_t(slot)];
        sigmaMax += checkedSigmaMax(int(i), grid, k);
        mPhases.emplace_back(c.phase, c.g, c.g2, c.phaseWeight);
        mPeakPhase = std::max(mPeakPhase, mPhases.back().eval(1.f));
        greyAll &= mModels[i]->grey() && !c.fluorescent();
        mFluorescent |= c.fluorescent();
        mFluorescence.push_back(
            c.fluorescent() ? FluorescenceEmission(c.emissionPeakNm, c.emissionFwhmNm, c.antiStokes)
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
    if (mTemperatureSlot < 0) return;
    const size_t slot = size_t(mTemperatureSlot);
    double T = double(mGrids[slot].maxValue()) * e.temperatureScale + e.temperatureOffset;
    double leMax = 0.0;  // Planck's maximum over the visible: sampled every 5 nm
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5.f)
        leMax = std::max(leMax, planck(l, T) * 1e-9 * e.intensity);
    if (!(sigmaMax * leMax <= kMaxSigma))
        throw MirageError("shader '" + mShader.name + "': emission σa·Le up to " +
                          formatNumber(sigmaMax * leMax) + " W/(m³·sr·nm) at " + formatNumber(T) +
                          " K (grid '" + mGrids[slot].name() + "') is above the limit of " +
                          formatNumber(kMaxSigma) +
                          "; lower the temperature scale, intensity or density");
}

// The largest σt = σa + σs of one component anywhere in the medium, in double so that the
// product cannot overflow before it is compared. Refuses (MirageError naming the shader,
// component and grid) a product above kMaxSigma: beyond it, float sums of σ, optical depths
// and σa·Le overflow to ∞ and every estimate that touches the medium is lost.
double Medium::checkedSigmaMax(int i, const FloatGrid* grid, float k) const {
    const MediumComponent& c = mShader.components[size_t(i)];
    const double gridMax = grid ? double(grid->maxValue()) : 1.0;
    const double sigma = mModels[size_t(i)]->sigmaTBound(double(k) * gridMax);
    if (!(sigma <= kMaxSigma))
        throw MirageError(
            "shader '" + mShader.name + "': component '" + c.name + "'" +
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
    for (const auto& g : m.mGrids) mAcc.push_back(g.accessor());
    for (size_t i = 0; i < m.mShader.components.size(); ++i) {
        mSlot[i] = m.mComponentSlot[i];
        mModel[i] = m.mModels[i].get();
    }
    mTemperatureSlot = m.mTemperatureSlot;
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
    const auto& comps = mMedium->mShader.components;
    for (size_t i = 0; i < comps.size(); ++i)
        mModel[i]->sampleWavelengths(w, comps[i].concentration * mMedium->mDensityScale, &mPath[i]);
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
                      formatNumber(motion.velocityScale()) + " moves shader '" + mShader.name +
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
    return slot < 0 ? 1.f : mGrids[size_t(slot)].sample(ctx.mAcc[size_t(slot)], p);
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
    out->components = int(mShader.components.size());
    for (int i = 0; i < out->components; ++i) out->sigmaSComponent[i] = SampledSpectrum(0.f);
    out->Le = SampledSpectrum(0.f);
}

void Medium::evalUnconfined(const Vec3& pAtTime, Context& ctx, MediumPoint* out) const {
    evalGridsAt(ctx.mMotion.lookupPoint(pAtTime), ctx, out);
}

void Medium::evalGridsAt(const Vec3& p, Context& ctx, MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(mShader.components.size());
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

float Medium::sigmaSAt(const Vec3& pAtTime, Context& ctx, float lambdaNm) const {
    float sigmaS = 0.f;
    if (!inRegion(pAtTime, ctx)) return 0.f;
    const Vec3 p = ctx.mMotion.lookupPoint(pAtTime);
    if (ctx.mGrey) {
        // The grey path's coefficients (set once in the context), as evalGridsAt reads them:
        // no spectrum or component law to evaluate per lookup (the photon estimates call this
        // once per photon they gather).
        for (size_t i = 0; i < mShader.components.size(); ++i)
            if (ctx.mPath[i].sigmaS[0] > 0.f)
                sigmaS += ctx.mPath[i].sigmaS[0] * gridValue(ctx, int(i), p);
        return sigmaS;
    }
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        const MediumComponent& comp = mShader.components[i];
        // A component that does not scatter at λ needs no grid lookup.
        if (comp.sigmaS(lambdaNm) == 0.f) continue;
        float C = gridValue(ctx, int(i), p) * comp.concentration * mDensityScale;
        sigmaS += mModels[i]->sigmaS(C, lambdaNm);
    }
    return sigmaS;
}

void Medium::sigmaAComponentsAt(const Vec3& pAtTime, Context& ctx, float lambdaNm,
                                float* sigmaA) const {
    const bool inside = inRegion(pAtTime, ctx);
    const Vec3 p = ctx.mMotion.lookupPoint(pAtTime);
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        if (!inside) {
            sigmaA[i] = 0.f;
            continue;
        }
        const MediumComponent& comp = mShader.components[i];
        float C = gridValue(ctx, int(i), p) * comp.concentration * mDensityScale;
        sigmaA[i] = mModels[i]->sigmaA(C, lambdaNm);
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
