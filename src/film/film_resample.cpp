// Magnifying a film (film_resample.h).
#include "film/film_resample.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
    // Each source pixel's mean once (a division per source pixel, not per tap), and each
    // column's span once.
    struct Mean {
        double v[4];  // X, Y, Z, alpha
        bool any;
    };
    std::vector<Mean> means(size_t(src.width()) * size_t(src.height()));
    for (int y = 0; y < src.height(); ++y)
        for (int x = 0; x < src.width(); ++x) {
            const Film::Pixel& p = src.pixel(x, y);
            Mean& m = means[size_t(y) * src.width() + x];
            m.any = p.samples > 0;
            const double inv = m.any ? 1.0 / p.samples : 0.0;
            for (int k = 0; k < 3; ++k) m.v[k] = p.xyz[k] * inv;
            m.v[3] = p.alpha * inv;
        }
    std::vector<Span> columns(static_cast<size_t>(width));
    for (int x = 0; x < width; ++x) columns[x] = spanOf(x, width, src.width());
    Film out(width, height);
    for (int y = 0; y < height; ++y) {
        const Span sy = spanOf(y, height, src.height());
        const Mean* rows[2] = {&means[size_t(sy.i0) * src.width()],
                               &means[size_t(sy.i1) * src.width()]};
        for (int x = 0; x < width; ++x) {
            const Span& sx = columns[x];
            const Mean* taps[4] = {&rows[0][sx.i0], &rows[0][sx.i1], &rows[1][sx.i0],
                                   &rows[1][sx.i1]};
            const double ws[4] = {(1 - sx.t) * (1 - sy.t), sx.t * (1 - sy.t), (1 - sx.t) * sy.t,
                                  sx.t * sy.t};
            double v[4] = {0, 0, 0, 0}, weight = 0;
            for (int c = 0; c < 4; ++c) {
                if (!taps[c]->any || ws[c] == 0) continue;
                for (int k = 0; k < 4; ++k) v[k] += ws[c] * taps[c]->v[k];
                weight += ws[c];
            }
            if (weight == 0) continue;
            // The weights sum to 1 unless a tap was empty: then the others share its weight.
            const double inv = weight == 1.0 ? 1.0 : 1.0 / weight;
            Film::Pixel& q = out.pixel(x, y);
            for (int k = 0; k < 3; ++k) {
                q.xyz[k] = v[k] * inv;
                q.xyzSq[k] = q.xyz[k] * q.xyz[k];
            }
            q.alpha = v[3] * inv;
            q.samples = 1;
        }
    }
    return out;
}

}  // namespace mirage
