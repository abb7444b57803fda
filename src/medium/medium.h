// A medium at render time: a shader bound to NanoVDB grids, placed in the world by a
// transform, with a majorant grid for tracking; or a homogeneous medium, a shader whose
// components are all constants over an explicit object-space box. It only reports
// coefficients and majorants; free-flight sampling and transmittance are written once, in
// transport/ (which takes a closed form for homogeneous media, docs/design.md).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/transform.h"
#include "medium/confinement.h"
#include "medium/fluorescence.h"
#include "medium/medium_motion.h"
#include "medium/phase.h"
#include "medium/shader_binding.h"
#include "volume/grid.h"
#include "volume/majorant.h"
#include "volume/vector_grid.h"

namespace mirage {

// Coefficients at one point for a path's wavelengths.
struct MediumPoint {
    SampledSpectrum sigmaA, sigmaS;  // 1/m
    SampledSpectrum Le;       // emitted radiance, W·m⁻²·sr⁻¹·nm⁻¹ (emission = σa·Le)
    float temperature = 0.f;  // K, where Le is the blackbody's (intensity · B(λ, T)); else 0
    int components = 0;
    std::array<SampledSpectrum, kMaxComponents> sigmaSComponent;  // for the phase mixture
};

// The largest σt (1/m) a medium may reach: a mean free path of 1e-30 m is beyond any physics,
// and above it float sums of σ and products like σa·Le overflow. Larger products are refused.
constexpr double kMaxSigma = 1e30;

class Medium {
public:
    // `grids` holds one grid per entry of shader.gridSlots(), in that order; a slot without a
    // grid is refused (MirageError naming it).
    Medium(ShaderDesc shader, std::vector<FloatGrid> grids, const Transform& objectToWorld,
           float densityScale, int majorantResolution = 64);
    // A homogeneous medium filling objectBox: every component must have grid == "" and the
    // shader must not emit (emission reads a temperature grid). Its majorant is one cell of
    // σ̄ = Σ_c concentration_c · densityScale · max_λ(σa,c + σs,c): for a grey medium σ̄ = σt,
    // so delta tracking meets no null collision.
    Medium(ShaderDesc shader, const Bounds3& objectBox, const Transform& objectToWorld,
           float densityScale);

    // The shader and the grids it reads, with each component's law and grid
    // (medium/shader_binding.h): what the photon emitter and the optical-depth march integrate.
    const ShaderBinding& binding() const { return mBinding; }
    const ShaderDesc& shader() const { return mBinding.shader(); }
    const Transform& objectToWorld() const { return mObjectToWorld; }
    Bounds3 worldBounds() const { return mWorldBounds; }
    Bounds3 objectBounds() const { return mMajorant.bounds(); }
    const MajorantGrid& majorant() const { return mMajorant; }
    bool emissive() const { return shader().emission.has_value(); }
    // Some component re-emits absorbed light (Γ > 0): the Γ roulette applies (reemission.h).
    bool fluorescent() const { return mFluorescent; }
    // The largest forward value of a component's lobe, p(0) (1/sr): 1/4π isotropic, 26 for
    // HG g 0.92 (render/light_lobes.h guides paths towards the lights above 5/sr).
    float peakPhase() const { return mPeakPhase; }
    // "Model only what a scene requires" (docs/design.md): every component is linear with
    // wavelength-independent σa and σs and none fluoresces, so σ is one number per component.
    // Then eval() computes one value per component instead of one per wavelength, and
    // Context::setWavelengths() keeps the constants it set once instead of re-sampling σ(λ) for
    // every path. Emission (Planck, spectral by nature) is evaluated per wavelength either way.
    bool greyCoefficients() const { return mGreyCoefficients; }
    // Whether the grey path is taken when it applies (default true); false forces the spectral
    // path, for the test and benchmark that compare the two. Call before making contexts.
    void setGreyPath(bool on) { mGreyPath = on; }
    bool greyPath() const { return mGreyPath && mGreyCoefficients; }
    // Constant coefficients over objectBounds(): transmittance has the closed form
    // exp(−σt(λ) · length inside the box).
    bool homogeneous() const { return mBinding.grids().empty(); }

    // Where in its box the medium exists (medium/confinement.h): every coefficient is zero
    // elsewhere. Set once the shapes that hold media are known; the world bounds shrink to it.
    const Confinement& confinement() const { return mConfinement; }
    void setConfinement(Confinement confinement);
    // Beer–Lambert's closed form applies along any ray: homogeneous, and one interval of the
    // ray inside.
    bool closedFormTransmittance() const { return homogeneous() && mConfinement.oneInterval(); }

    // How the medium moves within the shutter (medium/medium_motion.h). setMotion rebuilds the
    // majorant of a medium whose lookups move with time over bounds grown by the largest
    // displacement along each axis, max|v_a|·|velocityScale|·maxTimeOffset, with each cell
    // dilated by the displacement of the velocity found in it, so that it bounds σt at every
    // time in the shutter; the world bounds grow to what keyed transforms sweep. A homogeneous
    // medium has no grids for a flow to carry: it keeps only the keys.
    const MediumMotion& motion() const { return mMotion; }
    void setMotion(MediumMotion motion);

    // Per-path state: grid accessors and the cross-sections at the path's wavelengths.
    class Context {
    public:
        explicit Context(const Medium& m);
        // Out of line: the accessors are NanoVDB's types (volume/grid_lookup.h).
        Context(Context&&) noexcept;
        Context& operator=(Context&&) noexcept;
        ~Context();
        void setWavelengths(const SampledWavelengths& w);
        const SampledWavelengths& wavelengths() const { return mLambda; }
        // The path's time relative to the frame, Δt = t − t₀ (seconds), and where the medium is
        // then (MediumMotion::Path::setTimeOffset).
        void setTimeOffset(float seconds) { mMotion.setTimeOffset(seconds); }
        float timeOffset() const { return mMotion.timeOffset(); }
        // The volume's transforms at the context's time.
        const Transform& objectToWorld() const { return mMotion.objectToWorld(); }
        const Transform& worldToObject() const { return mMotion.worldToObject(); }
        // The path's view of the medium's motion: its displacement and advected lookup point.
        MediumMotion::Path& motion() { return mMotion; }
        // A world ray in object space at the context's time, with the same parameter t
        // (direction not renormalised); and a world point.
        Ray toObject(const Ray& worldRay) const {
            const Transform& w2o = worldToObject();
            return {w2o.point(worldRay.o), w2o.vector(worldRay.d), worldRay.tMax};
        }
        Vec3 pointToObject(const Vec3& pWorld) const { return worldToObject().point(pWorld); }

    private:
        friend class Medium;
        const Medium* mMedium;
        MediumMotion::Path mMotion;
        SampledWavelengths mLambda;
        std::vector<FloatGrid::Accessor> mAcc;
        // Per component: its coefficients at the path's wavelengths, its law, its grid index.
        std::array<PathCoefficients, kMaxComponents> mPath;
        std::array<const ComponentModel*, kMaxComponents> mModel;
        std::array<int, kMaxComponents> mSlot;
        int mTemperatureSlot = -1;
        bool mGrey = false;  // the medium's grey path: σ set once, scalar eval
    };

    // Coefficients at an object-space point (zero outside the region the medium is confined to).
    void eval(const Vec3& pObject, Context& ctx, MediumPoint* out) const;
    // The same, ignoring confinement and exclusions: what the shader gives at the point. For a
    // homogeneous medium it is its σ anywhere, which bounds it exactly as a majorant.
    void evalUnconfined(const Vec3& pObject, Context& ctx, MediumPoint* out) const;
    // The coefficients of the still medium, the frame's, at an object-space point (confined like
    // eval()): a moving medium's lookup without its velocity lookup. Residual ratio tracking
    // takes it as its control, which need only be a function of the ray (transport/tracking.cpp).
    void evalStill(const Vec3& pObject, Context& ctx, MediumPoint* out) const;
    // Scattering coefficient σs(x, λ) (1/m) at an object-space point for one wavelength —
    // a photon's — whatever the context's wavelengths: Σ_c c_c(x) σs,c(λ).
    float sigmaSAt(const Vec3& pObject, Context& ctx, float lambdaNm) const;

    // Absorption coefficient of each component (1/m) at an object-space point for one
    // wavelength: which component absorbed a photon decides whether it fluoresces. Writes
    // shader().components.size() values.
    void sigmaAComponentsAt(const Vec3& pObject, Context& ctx, float lambdaNm, float* sigmaA) const;
    // The emission band of component i (valid when it is fluorescent).
    const FluorescenceEmission& fluorescence(int i) const { return mFluorescence[size_t(i)]; }

    // Phase function of the mixture at a point: p(λ) = Σ_c σs,c(λ) p_c / σs(λ).
    SampledSpectrum phaseEval(const MediumPoint& mp, const Vec3& wi, const Vec3& wo) const;
    // Samples wo by choosing a component ∝ its mean σs, then its lobe; returns the
    // per-wavelength weight p(λ)/pdf.
    Vec3 phaseSample(const MediumPoint& mp, const Vec3& wi, float uc, float u1, float u2,
                     SampledSpectrum* weight, float* pdf) const;
    // The pdf phaseSample draws wo with (1/sr): the mixture of lobes by mean σs,c.
    float phasePdf(const MediumPoint& mp, const Vec3& wi, const Vec3& wo) const;

private:
    void buildMajorantAndPhases(const Bounds3& objectBounds, int majorantResolution);
    void fillMajorant(const Bounds3& objectBounds, int majorantResolution);
    void updateWorldBounds();
    void checkBlurRadius(const MediumMotion& motion) const;
    void dilateMajorant();
    // The shader's coefficients from the still grids read at p (already advected, if at all).
    void evalGridsAt(const Vec3& p, Context& ctx, MediumPoint* out) const;
    // False for an object-space point where the confinement leaves no medium (at the context's
    // time).
    bool inRegion(const Vec3& pObject, const Context& ctx) const;
    void setZero(MediumPoint* out) const;
    double checkedSigmaMax(int i, const FloatGrid* grid, float k) const;
    void checkEmissionBound(double sigmaMax) const;
    // Component i's grid value at an object-space point (1 for a constant component).
    float gridValue(const Context& ctx, int i, const Vec3& p) const;

    ShaderBinding mBinding;
    Transform mObjectToWorld, mWorldToObject;
    Bounds3 mWorldBounds;
    Bounds3 mStillBounds;  // object bounds of the grids, before any motion
    int mMajorantResolution = 64;
    MajorantGrid mMajorant;
    MediumMotion mMotion;
    std::vector<ComponentPhase> mPhases;
    std::vector<FluorescenceEmission> mFluorescence;  // per component (empty when Γ = 0)
    Confinement mConfinement;
    bool mFluorescent = false;
    float mPeakPhase = 0.f;
    bool mGreyCoefficients = false, mGreyPath = true;
};

}  // namespace mirage
