// A small log-log line plot drawn into an Image, for the speed↔accuracy instrument
// (`mirage tradeoff`): one polyline per series with square markers at the points, axes with
// tick marks at the powers of ten (minor ticks at 2–9 × 10ⁿ) and a faint decade grid. Axis
// labels, tick numbers and a legend are drawn with OpenImageIO's text renderer when it finds a
// font (DejaVu Sans on Debian); without one the plot is drawn unlabelled.
#pragma once

#include <string>
#include <vector>

#include "film/film.h"

namespace mirage {

struct PlotSeries {
    std::string label;          // legend text ("" = no legend entry)
    std::vector<double> x, y;   // joined in the given order; points ≤ 0 are skipped
};

struct LogLogPlot {
    std::string title, xLabel, yLabel;
    std::vector<PlotSeries> series;
};

// Draws the plot into a width × height RGBA image (display-referred sRGB values in [0, 1]).
Image drawLogLogPlot(const LogLogPlot& plot, int width = 900, int height = 640);

// Writes a plot image as an 8-bit PNG (atomically: a temporary name, then a rename).
void writePlotPng(const std::string& path, const Image& image);

}  // namespace mirage
