#include "medium/medium.h"

#include <algorithm>

#include "core/error.h"

namespace mirage {

namespace {

void checkComponentCount(const ShaderDesc& shader) {
    if (shader.components.empty() || int(shader.components.size()) > kMaxComponents)
        throw MirageError("shader '" + shader.name + "': expected 1 to " +
                          std::to_string(kMaxComponents) + " components, found " +
                          std::to_string(shader.components.size()));
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
    for (const auto& c : mShader.components) {
        float sigmaT = c.sigmaA.maxValue() + c.sigmaS.maxValue();
        float scale = c.concentration * mDensityScale * sigmaT;
        if (c.grid.empty()) {
            mMajorant.addConstant(scale);
        } else {
            size_t slot = std::find(slots.begin(), slots.end(), c.grid) - slots.begin();
            mMajorant.addGrid(mGrids[slot], scale);
        }
        mPhases.emplace_back(c.g);
    }
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
}

void Medium::Context::setWavelengths(const SampledWavelengths& w) {
    mLambda = w;
    const auto& comps = mMedium->mShader.components;
    for (size_t i = 0; i < comps.size(); ++i) {
        float k = comps[i].concentration * mMedium->mDensityScale;
        mSigmaA[i] = comps[i].sigmaA.sample(w) * k;
        mSigmaS[i] = comps[i].sigmaS.sample(w) * k;
    }
}

void Medium::eval(const Vec3& p, Context& ctx, MediumPoint* out) const {
    out->sigmaA = SampledSpectrum(0.f);
    out->sigmaS = SampledSpectrum(0.f);
    out->components = int(mShader.components.size());
    for (int i = 0; i < out->components; ++i) {
        int slot = ctx.mSlot[i];
        float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
        out->sigmaA += ctx.mSigmaA[i] * c;
        out->sigmaSComponent[i] = ctx.mSigmaS[i] * c;
        out->sigmaS += out->sigmaSComponent[i];
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

float Medium::sigmaSAt(const Vec3& p, Context& ctx, float lambdaNm) const {
    float sigmaS = 0.f;
    for (size_t i = 0; i < mShader.components.size(); ++i) {
        const MediumComponent& comp = mShader.components[i];
        float xs = comp.sigmaS(lambdaNm);
        if (xs == 0.f) continue;
        int slot = ctx.mSlot[i];
        float c = slot < 0 ? 1.f : mGrids[slot].sample(ctx.mAcc[slot], p);
        sigmaS += c * comp.concentration * mDensityScale * xs;
    }
    return sigmaS;
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
