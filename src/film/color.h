// Colour management through OpenColorIO. Mirage's own config (assets/ocio/config.ocio) is
// compiled into the binary, so Mirage runs anywhere; $OCIO, or an explicit path, overrides it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/matrix.h"

namespace mirage {

class ColorPipeline {
public:
    // configPath "" → $OCIO if set, else the built-in config. workingSpace "" → the config's
    // scene_linear role (ACEScg in Mirage's config). Throws MirageError if the config or a
    // colour space does not exist.
    explicit ColorPipeline(const std::string& configPath = "",
                           const std::string& workingSpace = "");
    ~ColorPipeline();

    const std::string& workingSpace() const;
    const std::string& configDescription() const;  // "built-in" or the path used
    // CIE XYZ (the config's "CIE XYZ D65" space) → working space, and back; linear, so the
    // OCIO processor is captured as a matrix.
    const Mat3& xyzToWorking() const;
    const Mat3& workingToXyz() const;
    // Chromaticities of the working space primaries and white (rx, ry, gx, gy, bx, by, wx, wy)
    // for EXR metadata: through ACES2065-1 when the config has the aces_interchange role (so
    // ACEScg gets AP1 and the ACES white), else through CIE XYZ D65 (see color.cpp).
    std::vector<float> workingChromaticities() const;
    // The same for another scene-linear space of the config, as if it were the working space
    // (an EXR written in [output] color_space). Throws MirageError for an unknown or a
    // non-linear space.
    std::vector<float> chromaticitiesOf(const std::string& space) const;

    // In-place conversion of interleaved RGB(A) pixels from the working space to another
    // colour space, or through a display/view for previews.
    void convert(std::vector<float>& pixels, int channels, const std::string& toSpace) const;
    void toDisplay(std::vector<float>& pixels, int channels, const std::string& display,
                   const std::string& view) const;
    std::vector<std::string> displays() const;
    std::vector<std::string> views(const std::string& display) const;  // empty if unknown
    std::vector<std::string> colorSpaces() const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// An output setting that names something the config lacks: `key` is "color_space", "display"
// or "view", `known` what the config offers in its place (the views of the display, for a view).
struct UnknownOutputName {
    std::string key, value;
    std::vector<std::string> known;
};
// The first of the output colour space (skipped when empty), preview display and view that
// `color` does not know, or nothing: checked before a long render, not after it.
std::optional<UnknownOutputName> findUnknownOutputName(const ColorPipeline& color,
                                                       const std::string& colorSpace,
                                                       const std::string& display,
                                                       const std::string& view);

// The text of the built-in config (assets/ocio/config.ocio, embedded at build time).
const char* builtinOcioConfig();

}  // namespace mirage
