// Magnifying a film (film_resample.h).
#include "film/film_resample.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace mirage {

namespace {

// The two source pixels a result pixel's centre falls between along one axis, and the weight of
// the second: the centre of result pixel i lies at source coordinate (i + ½)·n / m − ½.
struct Span {
    int i0, i1;
    double t;
};

Span spanOf(int i, int m, int n) {
    const double u = std::clamp((i + 0.5) * n / m - 0.5, 0.0, double(n - 1));
    const int i0 = std::min(int(u), n - 1);
    return {i0, std::min(i0 + 1, n - 1), u - i0};
}

}  // namespace

Film magnify(const Film& src, int width, int height) {
    MIRAGE_CHECK(src.aovs().empty());
    Film out(width, height);
    for (int y = 0; y < height; ++y) {
        const Span sy = spanOf(y, height, src.height());
        for (int x = 0; x < width; ++x) {
            const Span sx = spanOf(x, width, src.width());
            const int xs[4] = {sx.i0, sx.i1, sx.i0, sx.i1};
            const int ys[4] = {sy.i0, sy.i0, sy.i1, sy.i1};
            const double ws[4] = {(1 - sx.t) * (1 - sy.t), sx.t * (1 - sy.t), (1 - sx.t) * sy.t,
                                  sx.t * sy.t};
            double xyz[3] = {0, 0, 0}, alpha = 0, weight = 0;
            for (int c = 0; c < 4; ++c) {
                const Film::Pixel& p = src.pixel(xs[c], ys[c]);
                if (p.samples == 0 || ws[c] == 0) continue;
                const double w = ws[c] / p.samples;
                for (int k = 0; k < 3; ++k) xyz[k] += w * p.xyz[k];
                alpha += w * p.alpha;
                weight += ws[c];
            }
            if (weight == 0) continue;
            Film::Pixel& q = out.pixel(x, y);
            for (int k = 0; k < 3; ++k) {
                q.xyz[k] = xyz[k] / weight;
                q.xyzSq[k] = q.xyz[k] * q.xyz[k];
            }
            q.alpha = alpha / weight;
            q.samples = 1;
        }
    }
    return out;
}

}  // namespace mirage
