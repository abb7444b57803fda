#include "render/sky_profile.h"

namespace mirage {

SkyProfile SkyProfile::march(const Medium& medium, Medium::Context& ctx, const Ray& r, float a,
                             float b) {
    SkyProfile p;
    p.start = a;
    p.step = (b - a) / float(kSteps);
    for (int k = 0; k < kSteps; ++k) {
        MediumPoint mp;
        medium.eval(r.at(a + (float(k) + 0.5f) * p.step), ctx, &mp);
        p.sigma[size_t(k)] = (mp.sigmaA + mp.sigmaS).average();
        p.depth += p.sigma[size_t(k)] * p.step;
    }
    return p;
}

int SkyProfile::stratify(float u, int strata, float* t, float* pdf) const {
    if (!(depth > 0.f)) return 0;
    int placed = 0;
    float before = 0.f;  // the depth up to step k
    size_t k = 0;
    float across = sigma[0] * step;
    for (int i = 0; i < strata; ++i) {
        const float tau = (float(i) + u) * depth / float(strata);
        while (k < size_t(kSteps) && !(before + across > tau)) {
            before += across;
            if (++k < size_t(kSteps)) across = sigma[k] * step;
        }
        if (k == size_t(kSteps)) break;  // rounding: the sum fell short of tau
        t[placed] = start + (float(k) + (tau - before) / across) * step;
        // The step's own density: t may round onto the next step's edge.
        pdf[placed] = float(strata) * sigma[k] / depth;
        ++placed;
    }
    return placed;
}

}  // namespace mirage
