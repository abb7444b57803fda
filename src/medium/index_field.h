// Refractive-index fields n(x, λ) for curved light (Gutierrez et al. 2005, §4): the index, its
// gradient, and bounds on |∇n| per region so that the straight-line code runs wherever the index
// is constant ("model only what a scene requires", docs/design.md).
//
// Double precision throughout: the index of air differs from 1 by ~3e-4, and a path stepper run
// at tolerances down to 1e-14 needs the digits. Positions in metres, wavelengths in nanometres,
// ∇n in 1/m.
#pragma once

#include <limits>

#include "core/math.h"

namespace mirage {

class IndexField {
public:
    virtual ~IndexField() = default;

    // n and ∇n at x for wavelength λ. The path stepper calls this once per Runge–Kutta stage,
    // so the two come together: every field shares work between them.
    virtual void eval(const Vec3d& x, double lambdaNm, double* n, Vec3d* gradient) const = 0;

    double index(const Vec3d& x, double lambdaNm) const {
        double n;
        Vec3d g;
        eval(x, lambdaNm, &n, &g);
        return n;
    }

    // An upper bound on |∇n| over the box [lo, hi] (any λ in 360–830 nm). 0 means n is constant
    // over the box: paths are straight there.
    virtual double gradientBound(const Vec3d& lo, const Vec3d& hi) const = 0;

    // How far a straight path from x along the unit direction d runs through constant n (∇n = 0
    // all the way), up to maxDistance; 0 when ∇n may be non-zero at x. The stepper takes that
    // stretch as one exact straight chord. The default never promises a straight stretch.
    virtual double straightDistance(const Vec3d& x, const Vec3d& d, double maxDistance) const {
        (void)x;
        (void)d;
        (void)maxDistance;
        return 0.0;
    }
};

// The analytic validation profile n = n0 + k·(x − origin)·axis (n = n0 + k·y with
// axis = +y). Not dispersive. Rays in it are catenaries (linear_profile_exact.h).
class LinearIndexField final : public IndexField {
public:
    LinearIndexField(double n0, double k, const Vec3d& axis = Vec3d(0, 1, 0))
        : mN0(n0), mK(k), mAxis(normalize(axis)) {}

    void eval(const Vec3d& x, double, double* n, Vec3d* gradient) const override {
        *n = mN0 + mK * dot(x, mAxis);
        *gradient = mAxis * mK;
    }
    double gradientBound(const Vec3d&, const Vec3d&) const override { return std::abs(mK); }
    double straightDistance(const Vec3d&, const Vec3d&, double maxDistance) const override {
        return mK == 0.0 ? maxDistance : 0.0;
    }

    double n0() const { return mN0; }
    double k() const { return mK; }
    const Vec3d& axis() const { return mAxis; }

private:
    double mN0, mK;
    Vec3d mAxis;
};

}  // namespace mirage
