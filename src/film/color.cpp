// Colour management through OpenColorIO 2.1: which config, which working space, and the
// conversions the film and the image writers need.
//
// The film works in CIE XYZ (what the colour-matching functions give) and hands the image over in
// the working space; that step is one 3×3 matrix per pixel, so the OCIO processor between the
// config's XYZ space and the working space is captured once as a Mat3 instead of being called per
// pixel. Everything else (other colour spaces, display/views for previews) goes through OCIO's
// CPU processors on whole images.

#include "film/color.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace OCIO = OCIO_NAMESPACE;

namespace mirage {

namespace {

// The XYZ space of a config: the v2 interchange role if the config declares it (the ACES studio
// configs do), else Mirage's own name for it.
constexpr const char* kXyzRole = "cie_xyz_d65_interchange";
constexpr const char* kXyzName = "CIE XYZ D65";
constexpr const char* kAcesRole = "aces_interchange";

std::string joinNames(const std::vector<std::string>& names) {
    if (names.empty()) return "(none)";
    return joinList(names, [](const std::string& n) { return "'" + n + "'"; });
}

std::vector<std::string> colorSpaceNames(const OCIO::ConstConfigRcPtr& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumColorSpaces(); ++i)
        names.emplace_back(config->getColorSpaceNameByIndex(i));
    return names;
}

OCIO::ConstCPUProcessorRcPtr cpuProcessor(const OCIO::ConstConfigRcPtr& config,
                                          const OCIO::ConstTransformRcPtr& transform) {
    return config->getProcessor(transform)->getDefaultCPUProcessor();
}

// Applies interleaved RGB or RGBA float pixels in place (alpha passes through OCIO unchanged).
void applyInPlace(const OCIO::ConstCPUProcessorRcPtr& cpu, std::vector<float>& pixels,
                  int channels) {
    MIRAGE_CHECK(channels == 3 || channels == 4);
    MIRAGE_CHECK(pixels.size() % size_t(channels) == 0);
    long count = long(pixels.size() / size_t(channels));
    if (count == 0) return;
    OCIO::PackedImageDesc desc(pixels.data(), count, 1, channels);
    cpu->apply(desc);
}

}  // namespace

struct ColorPipeline::Impl {
    OCIO::ConstConfigRcPtr config;
    std::string description;  // "built-in" or the config path
    std::string working;      // canonical name of the working space
    std::string xyzSpace;
    Mat3 xyzToWorking, workingToXyz;

    std::string resolveColorSpace(const std::string& name, const char* what) const {
        OCIO::ConstColorSpaceRcPtr cs = config->getColorSpace(name.c_str());
        if (!cs)
            throw MirageError("OCIO config " + description + ": unknown " + what + " '" + name +
                              "'; valid colour spaces: " + joinNames(colorSpaceNames(config)));
        return cs->getName();
    }

    // The matrix of a linear OCIO conversion: the images of the unit vectors are its columns.
    // A log or display-encoded space is not linear; a probe with mixed signs and magnitudes
    // catches that, since a matrix captured from it would be silently wrong.
    Mat3 linearMatrix(const std::string& from, const std::string& to) const {
        Mat3 m;
        try {
            OCIO::ConstCPUProcessorRcPtr cpu =
                config->getProcessor(from.c_str(), to.c_str())->getDefaultCPUProcessor();
            for (int c = 0; c < 3; ++c) {
                float e[3] = {0.f, 0.f, 0.f};
                e[c] = 1.f;
                cpu->applyRGB(e);
                for (int r = 0; r < 3; ++r) m(r, c) = e[r];
            }
            float probe[3] = {2.f, -0.5f, 0.25f};
            Vec3d expect = m.apply(Vec3d(probe[0], probe[1], probe[2]));
            cpu->applyRGB(probe);
            for (int r = 0; r < 3; ++r)
                if (!(std::abs(probe[r] - expect[r]) <= 1e-4 * (1.0 + std::abs(expect[r]))))
                    throw MirageError("OCIO config " + description + ": the conversion from '" +
                                      from + "' to '" + to + "' is not linear; the working " +
                                      "space must be scene-linear (e.g. the scene_linear role)");
        } catch (const OCIO::Exception& e) {
            throw MirageError("OCIO config " + description + ": cannot convert '" + from +
                              "' to '" + to + "': " + boundedMessage(e.what()));
        }
        return m;
    }

    // The matrices between the config's XYZ and the working space.
    void setWorkingMatrices() {
        xyzToWorking = linearMatrix(xyzSpace, working);
        if (!(std::abs(xyzToWorking.determinant()) > 1e-12))
            throw MirageError("OCIO config " + description + ": the transform from '" + xyzSpace +
                              "' to '" + working + "' is singular");
        workingToXyz = xyzToWorking.inverse();
    }

    std::vector<float> workingChromaticities() const;

    std::vector<std::string> views(const std::string& display) const {
        std::vector<std::string> names;
        for (int i = 0; i < config->getNumViews(display.c_str()); ++i)
            names.emplace_back(config->getView(display.c_str(), i));
        return names;
    }
};

ColorPipeline::ColorPipeline(const std::string& configPath, const std::string& workingSpace)
    : mImpl(std::make_unique<Impl>()) {
    Impl& im = *mImpl;

    // Which config: the explicit path, else $OCIO (the convention every OCIO application
    // follows), else the one compiled into Mirage.
    std::string path = configPath;
    if (path.empty()) {
        const char* env = std::getenv("OCIO");
        if (env && *env) path = env;
    }
    try {
        if (path.empty()) {
            std::istringstream text(builtinOcioConfig());
            im.config = OCIO::Config::CreateFromStream(text);
            im.description = "built-in";
        } else {
            std::error_code ec;
            if (!std::filesystem::is_regular_file(path, ec))
                throw MirageError(FileLoc{path, 0, 0},
                                  "OCIO config file does not exist" +
                                      std::string(configPath.empty() ? " (from $OCIO)" : ""));
            im.config = OCIO::Config::CreateFromFile(path.c_str());
            im.description = path;
        }
    } catch (const OCIO::Exception& e) {
        throw MirageError(FileLoc{path.empty() ? std::string("built-in OCIO config") : path, 0, 0},
                          "cannot load OCIO config: " + boundedMessage(e.what()));
    }

    // The working space: the scene_linear role unless one is named.
    if (workingSpace.empty()) {
        OCIO::ConstColorSpaceRcPtr cs = im.config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
        if (!cs)
            throw MirageError("OCIO config " + im.description +
                              ": no working space given and no scene_linear role; valid " +
                              "colour spaces: " + joinNames(colorSpaceNames(im.config)));
        im.working = cs->getName();
    } else {
        im.working = im.resolveColorSpace(workingSpace, "working colour space");
    }

    if (im.config->hasRole(kXyzRole)) {
        im.xyzSpace =
            im.resolveColorSpace(kXyzRole, "colour space for role cie_xyz_d65_interchange");
    } else if (im.config->getColorSpace(kXyzName)) {
        im.xyzSpace = kXyzName;
    } else {
        throw MirageError("OCIO config " + im.description + ": needs the role '" + kXyzRole +
                          "' or a colour space '" + kXyzName +
                          "' (the film works in CIE XYZ); valid colour spaces: " +
                          joinNames(colorSpaceNames(im.config)));
    }

    im.setWorkingMatrices();
}

ColorPipeline::~ColorPipeline() = default;

const std::string& ColorPipeline::workingSpace() const { return mImpl->working; }
const std::string& ColorPipeline::configDescription() const { return mImpl->description; }
const Mat3& ColorPipeline::xyzToWorking() const { return mImpl->xyzToWorking; }
const Mat3& ColorPipeline::workingToXyz() const { return mImpl->workingToXyz; }

// A primary is RGB (1,0,0) etc.: its XYZ is a column of the working → XYZ matrix; the white is
// RGB (1,1,1); chromaticity (x, y) = (X, Y) / (X + Y + Z).
//
// Which XYZ matters. An OCIO config relates spaces only after chromatic adaptation, so through
// the "CIE XYZ D65" space every working space has the D65 white and primaries adapted to it:
// ACEScg would be tagged with neither the AP1 primaries nor the ACES white that every tool
// recognises it by. When the config has an ACES reference (role aces_interchange), the XYZ is
// instead taken through ACES2065-1, whose AP0 primaries are defined in unadapted CIE XYZ
// (SMPTE ST 2065-1): exact for the ACES spaces, and for a D65 space (Rec.709) its primaries as
// adapted to the ACES white, a consistent description that a reader adapts back to its display.
// Without that role the D65 description is used.
std::vector<float> ColorPipeline::workingChromaticities() const {
    return mImpl->workingChromaticities();
}

std::vector<float> ColorPipeline::chromaticitiesOf(const std::string& space) const {
    Impl other = *mImpl;
    other.working = other.resolveColorSpace(space, "working colour space");
    other.setWorkingMatrices();
    return other.workingChromaticities();
}

std::vector<float> ColorPipeline::Impl::workingChromaticities() const {
    Mat3 toXyz = workingToXyz;
    if (config->hasRole(kAcesRole)) {
        // AP0 → CIE XYZ, SMPTE ST 2065-1:2012 section 4.3 (white x = 0.32168, y = 0.33767).
        Mat3 ap0ToXyz;
        ap0ToXyz.m = {0.9525523959,  0.0, 0.0000936786, 0.3439664498, 0.7281660966,
                      -0.0721325464, 0.0, 0.0,          1.0088251844};
        std::string aces = resolveColorSpace(kAcesRole,
                                             "colour space for role "
                                             "aces_interchange");
        toXyz = ap0ToXyz * linearMatrix(working, aces);
    }
    std::vector<float> xy;
    auto push = [&xy](const Vec3d& xyz) {
        double sum = xyz.x + xyz.y + xyz.z;
        xy.push_back(float(xyz.x / sum));
        xy.push_back(float(xyz.y / sum));
    };
    for (int c = 0; c < 3; ++c) push(Vec3d(toXyz(0, c), toXyz(1, c), toXyz(2, c)));
    push(toXyz.apply(Vec3d(1.0, 1.0, 1.0)));
    return xy;
}

void ColorPipeline::convert(std::vector<float>& pixels, int channels,
                            const std::string& toSpace) const {
    std::string target = mImpl->resolveColorSpace(toSpace, "colour space");
    if (target == mImpl->working) return;
    try {
        auto cpu = mImpl->config->getProcessor(mImpl->working.c_str(), target.c_str())
                       ->getDefaultCPUProcessor();
        applyInPlace(cpu, pixels, channels);
    } catch (const OCIO::Exception& e) {
        throw MirageError("OCIO config " + mImpl->description + ": cannot convert '" +
                          mImpl->working + "' to '" + target + "': " + boundedMessage(e.what()));
    }
}

void ColorPipeline::toDisplay(std::vector<float>& pixels, int channels, const std::string& display,
                              const std::string& view) const {
    std::vector<std::string> known = displays();
    if (std::find(known.begin(), known.end(), display) == known.end())
        throw MirageError("OCIO config " + mImpl->description + ": unknown display '" + display +
                          "'; valid displays: " + joinNames(known));
    std::vector<std::string> knownViews = views(display);
    if (std::find(knownViews.begin(), knownViews.end(), view) == knownViews.end())
        throw MirageError("OCIO config " + mImpl->description + ": unknown view '" + view +
                          "' for display '" + display + "'; valid views: " + joinNames(knownViews));
    try {
        OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
        t->setSrc(mImpl->working.c_str());
        t->setDisplay(display.c_str());
        t->setView(view.c_str());
        applyInPlace(cpuProcessor(mImpl->config, t), pixels, channels);
    } catch (const OCIO::Exception& e) {
        throw MirageError("OCIO config " + mImpl->description + ": cannot apply display '" +
                          display + "' view '" + view + "': " + boundedMessage(e.what()));
    }
}

std::vector<std::string> ColorPipeline::displays() const {
    std::vector<std::string> names;
    for (int i = 0; i < mImpl->config->getNumDisplays(); ++i)
        names.emplace_back(mImpl->config->getDisplay(i));
    return names;
}

std::vector<std::string> ColorPipeline::views(const std::string& display) const {
    return mImpl->views(display);
}

std::vector<std::string> ColorPipeline::colorSpaces() const {
    return colorSpaceNames(mImpl->config);
}

std::optional<UnknownOutputName> findUnknownOutputName(const ColorPipeline& color,
                                                       const std::string& colorSpace,
                                                       const std::string& display,
                                                       const std::string& view) {
    auto miss = [](const char* key, const std::string& value,
                   std::vector<std::string> known) -> std::optional<UnknownOutputName> {
        if (std::find(known.begin(), known.end(), value) != known.end()) return std::nullopt;
        return UnknownOutputName{key, value, std::move(known)};
    };
    if (!colorSpace.empty())
        if (auto m = miss("color_space", colorSpace, color.colorSpaces())) return m;
    if (auto m = miss("display", display, color.displays())) return m;
    return miss("view", view, color.views(display));
}

}  // namespace mirage
