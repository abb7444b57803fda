// A finished frame's EXR header (exr_header.h).
#include "film/exr_header.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "film/color.h"

namespace mirage {

namespace {

// Whether `space` names an output colour space other than the working space. Compared by name,
// as the scene states it: a name the config resolves to the working space converts to itself.
bool otherSpace(const ColorPipeline& color, const std::string& space) {
    return !space.empty() && space != color.workingSpace();
}

}  // namespace

std::string headerNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

ExrOptions finishedFrameHeader(const ColorPipeline& color, const std::string& space,
                               bool halfFloat, bool multipart) {
    ExrOptions exr;
    exr.halfFloat = halfFloat;
    exr.multipart = multipart;
    exr.colorSpace = color.workingSpace();
    exr.chromaticities = color.workingChromaticities();
    if (otherSpace(color, space)) {
        exr.colorSpace = space;
        try {
            exr.chromaticities = color.chromaticitiesOf(space);
        } catch (const MirageError&) {
            exr.chromaticities.clear();  // a display-encoded space has no chromaticities
        }
    }
    exr.metadata = {{"version", MIRAGE_VERSION},
                    {"ocio_config", color.configDescription()},
                    {"complete", "true"}};
    return exr;
}

void convertToOutputSpace(const ColorPipeline& color, const std::string& space, Image* image) {
    if (!otherSpace(color, space)) return;
    color.convert(image->rgba, 4, space);
    for (ImageLayer& layer : image->layers)
        if (layer.channels.size() == 3 && layer.convertColor) color.convert(layer.pixels, 3, space);
}

bool isCompleteFrame(const std::string& exrPath) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(exrPath, ec)) return false;
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(exrPath);
    if (!in) {
        OIIO::geterror();  // clear OIIO's pending error: an unreadable file is just not complete
        return false;
    }
    const OIIO::ParamValue* p = in->spec().find_attribute("mirage:complete");
    const bool complete = p && p->get_string() == "true";
    in->close();
    return complete;
}

}  // namespace mirage
