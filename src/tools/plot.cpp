#include "tools/plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"

namespace mirage {

namespace {

struct Rgb {
    float r, g, b;
};

// Colour-blind-safe series colours (Okabe & Ito 2008), then black.
const Rgb kPalette[] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f},
                        {0.80f, 0.47f, 0.65f}, {0.90f, 0.62f, 0.00f}, {0.34f, 0.71f, 0.91f},
                        {0.94f, 0.89f, 0.26f}, {0.00f, 0.00f, 0.00f}};
const Rgb kBlack{0.f, 0.f, 0.f}, kGrid{0.88f, 0.88f, 0.88f}, kWhite{1.f, 1.f, 1.f};

// Drawing onto an opaque image: `coverage` of a pixel takes `c`, the rest keeps what was there.
class Canvas {
public:
    explicit Canvas(Image& image) : mImage(image) {}

    void blend(int x, int y, const Rgb& c, float coverage) {
        if (x < 0 || y < 0 || x >= mImage.width || y >= mImage.height || coverage <= 0.f) return;
        float a = std::min(coverage, 1.f);
        float* p = mImage.pixel(x, y);
        p[0] += (c.r - p[0]) * a;
        p[1] += (c.g - p[1]) * a;
        p[2] += (c.b - p[2]) * a;
    }

    void fillRect(int x0, int y0, int x1, int y1, const Rgb& c) {
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) blend(x, y, c, 1.f);
    }

    // An antialiased line `width` pixels wide: each pixel is covered by the part of its unit
    // square nearer the segment than width/2, approximated by clamp(width/2 + ½ − distance)
    // (Wu's idea of coverage-weighted pixels, for thick lines).
    void line(double xa, double ya, double xb, double yb, const Rgb& c, double width = 1.0) {
        double h = 0.5 * width;
        int x0 = int(std::floor(std::min(xa, xb) - h - 1)), x1 = int(std::ceil(std::max(xa, xb) + h + 1));
        int y0 = int(std::floor(std::min(ya, yb) - h - 1)), y1 = int(std::ceil(std::max(ya, yb) + h + 1));
        double dx = xb - xa, dy = yb - ya, len2 = dx * dx + dy * dy;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                double px = x + 0.5 - xa, py = y + 0.5 - ya;
                double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
                double d = std::hypot(px - t * dx, py - t * dy);
                blend(x, y, c, float(std::clamp(h + 0.5 - d, 0.0, 1.0)));
            }
    }

    // A filled square marker with a dark outline, centred on (x, y).
    void marker(double x, double y, const Rgb& c, int half = 4) {
        int cx = int(std::lround(x)), cy = int(std::lround(y));
        fillRect(cx - half, cy - half, cx + half, cy + half, kBlack);
        fillRect(cx - half + 1, cy - half + 1, cx + half - 1, cy + half - 1, c);
    }

private:
    Image& mImage;
};

// Text through OIIO (FreeType). The font is looked up once; without one, text is skipped.
class TextPen {
public:
    explicit TextPen(Image& image)
        : mBuf(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT),
               image.rgba.data()) {
        for (const char* f : {"DejaVuSans", "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"})
            if (OIIO::ImageBufAlgo::text_size("10", 14, f).defined()) {
                mFont = f;
                break;
            }
    }
    bool available() const { return !mFont.empty(); }

    void text(int x, int y, const std::string& s, int size,
              OIIO::ImageBufAlgo::TextAlignX ax = OIIO::ImageBufAlgo::TextAlignX::Left,
              OIIO::ImageBufAlgo::TextAlignY ay = OIIO::ImageBufAlgo::TextAlignY::Baseline,
              const Rgb& c = kBlack) {
        if (mFont.empty() || s.empty()) return;
        const float color[4] = {c.r, c.g, c.b, 1.f};
        OIIO::ImageBufAlgo::render_text(mBuf, x, y, s, size, mFont, color, ax, ay);
    }
    // The power of ten 10^e as "10" with a raised exponent (OIIO's text renderer takes one byte
    // per glyph, so Unicode superscripts are out). (x, y): the baseline at the left, centre or
    // right end of the label, as `ax` says.
    void decade(int x, int y, int e, OIIO::ImageBufAlgo::TextAlignX ax) {
        using AX = OIIO::ImageBufAlgo::TextAlignX;
        const std::string exponent = std::to_string(e);
        int w10 = width("10", 16), wExp = width(exponent, 12), total = w10 + wExp + 1;
        int x0 = ax == AX::Left ? x : ax == AX::Center ? x - total / 2 : x - total;
        text(x0, y, "10", 16);
        text(x0 + w10 + 1, y - 7, exponent, 12);
    }
    int width(const std::string& s, int size) const {
        if (mFont.empty()) return 0;
        OIIO::ROI r = OIIO::ImageBufAlgo::text_size(s, size, mFont);
        return r.defined() ? r.width() : 0;
    }

private:
    OIIO::ImageBuf mBuf;  // wraps the Image's pixels; draws in place
    std::string mFont;
};

// The decade range [lo, hi] (exponents) covering the positive values of `v`, at least one
// decade wide.
void decadeRange(const std::vector<double>& v, int* lo, int* hi) {
    double mn = INFINITY, mx = -INFINITY;
    for (double x : v)
        if (x > 0 && std::isfinite(x)) {
            mn = std::min(mn, x);
            mx = std::max(mx, x);
        }
    if (!(mn <= mx)) mn = mx = 1.0;
    *lo = int(std::floor(std::log10(mn) + 1e-9));
    *hi = int(std::ceil(std::log10(mx) - 1e-9));
    if (*hi <= *lo) *hi = *lo + 1;
}

// The plot area in pixels (room for tick labels and axis titles on the left and below when
// there are labels) and the decades it spans: where a value lands.
struct PlotArea {
    int left, right, top, bottom;
    int xLo, xHi, yLo, yHi;  // decade exponents
    double px(double x) const {
        return left + (std::log10(x) - xLo) / (xHi - xLo) * (right - left);
    }
    double py(double y) const {
        return bottom - (std::log10(y) - yLo) / (yHi - yLo) * (bottom - top);
    }
};

PlotArea plotArea(const LogLogPlot& plot, int width, int height, bool labels) {
    PlotArea a{labels ? 92 : 30, width - 24, labels ? 44 : 20, height - (labels ? 64 : 20),
               0, 0, 0, 0};
    std::vector<double> xs, ys;
    for (const auto& s : plot.series) {
        xs.insert(xs.end(), s.x.begin(), s.x.end());
        ys.insert(ys.end(), s.y.begin(), s.y.end());
    }
    decadeRange(xs, &a.xLo, &a.xHi);
    decadeRange(ys, &a.yLo, &a.yHi);
    return a;
}

// Decade grid, then the frame, then ticks: major at 10ⁿ, minor at 2–9 × 10ⁿ.
void drawAxes(const PlotArea& a, Canvas& canvas) {
    for (int e = a.xLo; e <= a.xHi; ++e)
        canvas.line(a.px(std::pow(10, e)), a.top, a.px(std::pow(10, e)), a.bottom, kGrid);
    for (int e = a.yLo; e <= a.yHi; ++e)
        canvas.line(a.left, a.py(std::pow(10, e)), a.right, a.py(std::pow(10, e)), kGrid);
    canvas.line(a.left, a.top, a.right, a.top, kBlack);
    canvas.line(a.left, a.bottom, a.right, a.bottom, kBlack);
    canvas.line(a.left, a.top, a.left, a.bottom, kBlack);
    canvas.line(a.right, a.top, a.right, a.bottom, kBlack);
    for (int e = a.xLo; e <= a.xHi; ++e)
        for (int m = 1; m <= 9 && (e < a.xHi || m == 1); ++m) {
            double x = a.px(m * std::pow(10, e)), len = m == 1 ? 9 : 5;
            canvas.line(x, a.bottom, x, a.bottom - len, kBlack);
            canvas.line(x, a.top, x, a.top + len, kBlack);
        }
    for (int e = a.yLo; e <= a.yHi; ++e)
        for (int m = 1; m <= 9 && (e < a.yHi || m == 1); ++m) {
            double y = a.py(m * std::pow(10, e)), len = m == 1 ? 9 : 5;
            canvas.line(a.left, y, a.left + len, y, kBlack);
            canvas.line(a.right, y, a.right - len, y, kBlack);
        }
}

const Rgb& seriesColour(size_t i) { return kPalette[i % (sizeof kPalette / sizeof kPalette[0])]; }

bool plottable(const PlotSeries& s, size_t j) {
    return s.x[j] > 0 && s.y[j] > 0 && std::isfinite(s.x[j]) && std::isfinite(s.y[j]);
}

// The series: polylines first, markers on top.
void drawSeries(const LogLogPlot& plot, const PlotArea& a, Canvas& canvas) {
    for (size_t i = 0; i < plot.series.size(); ++i) {
        const auto& s = plot.series[i];
        bool have = false;
        double lx = 0, ly = 0;
        for (size_t j = 0; j < s.x.size() && j < s.y.size(); ++j) {
            if (!plottable(s, j)) continue;
            double x = a.px(s.x[j]), y = a.py(s.y[j]);
            if (have) canvas.line(lx, ly, x, y, seriesColour(i), 2.0);
            have = true;
            lx = x;
            ly = y;
        }
    }
    for (size_t i = 0; i < plot.series.size(); ++i) {
        const auto& s = plot.series[i];
        for (size_t j = 0; j < s.x.size() && j < s.y.size(); ++j)
            if (plottable(s, j)) canvas.marker(a.px(s.x[j]), a.py(s.y[j]), seriesColour(i));
    }
}

// Tick numbers at the decades, the axis titles and the plot's title.
void drawLabels(const LogLogPlot& plot, const PlotArea& a, int height, TextPen& pen) {
    using AX = OIIO::ImageBufAlgo::TextAlignX;
    for (int e = a.xLo; e <= a.xHi; ++e)
        pen.decade(int(a.px(std::pow(10, e))), a.bottom + 26, e, AX::Center);
    for (int e = a.yLo; e <= a.yHi; ++e)
        pen.decade(a.left - 10, int(a.py(std::pow(10, e))) + 6, e, AX::Right);
    pen.text((a.left + a.right) / 2, height - 16, plot.xLabel, 17, AX::Center);
    pen.text(a.left, a.top - 14, plot.yLabel, 17, AX::Left);
    pen.text(a.right, a.top - 14, plot.title, 15, AX::Right);
}

// The legend in the top-right corner of the plot area, on white: the series that have a label.
void drawLegend(const LogLogPlot& plot, const PlotArea& a, Canvas& canvas, TextPen& pen) {
    int rows = 0, w = 0;
    for (const auto& s : plot.series)
        if (!s.label.empty()) {
            ++rows;
            w = std::max(w, pen.width(s.label, 15));
        }
    if (rows == 0) return;
    const int x0 = a.right - w - 52, y0 = a.top + 12, rowH = 22;
    canvas.fillRect(x0, y0, a.right - 12, y0 + rows * rowH + 8, kGrid);
    canvas.fillRect(x0 + 1, y0 + 1, a.right - 13, y0 + rows * rowH + 7, kWhite);
    int row = 0;
    for (size_t i = 0; i < plot.series.size(); ++i) {
        if (plot.series[i].label.empty()) continue;
        const int y = y0 + 4 + row * rowH + rowH / 2;
        canvas.line(x0 + 8, y, x0 + 32, y, seriesColour(i), 2.0);
        canvas.marker(x0 + 20, y, seriesColour(i), 3);
        pen.text(x0 + 40, y, plot.series[i].label, 15, OIIO::ImageBufAlgo::TextAlignX::Left,
                 OIIO::ImageBufAlgo::TextAlignY::Center);
        ++row;
    }
}

}  // namespace

Image drawLogLogPlot(const LogLogPlot& plot, int width, int height) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.assign(size_t(width) * height * 4, 1.f);
    Canvas canvas(image);
    TextPen pen(image);
    const PlotArea area = plotArea(plot, width, height, pen.available());
    drawAxes(area, canvas);
    drawSeries(plot, area, canvas);
    if (!pen.available()) return image;
    drawLabels(plot, area, height, pen);
    drawLegend(plot, area, canvas, pen);
    return image;
}

void writePlotPng(const std::string& path, const Image& image) {
    createParentFolders(path);
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            // The temporary name has no image extension: name the format explicitly.
            auto out = OIIO::ImageOutput::create("png");
            OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
            bool ok = out && out->open(tmp, spec) &&
                      out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data(),
                                       4 * sizeof(float)) &&
                      out->close();
            if (!ok)
                throw MirageError(FileLoc{path, 0, 0}, "cannot write the plot: " +
                                                           (out ? out->geterror() : OIIO::geterror()));
        },
        "cannot rename the plot into place");
}

}  // namespace mirage
