// What film/ knows of a finished frame's EXR header, apart from the values a render measured
// (the frame stage fills those in, frame/frame_output.h): the format of a measured number, the
// output colour space (the developed image converted into it, and the tags that name it), the
// version and OCIO config, and the mark of a finished frame that --skip-existing trusts.
#pragma once

#include <string>

#include "film/image_io.h"

namespace mirage {

class ColorPipeline;

// A measured value in a header (seconds, an error, a limit): 6 significant digits, "%.6g".
std::string headerNumber(double v);

// The header of a finished frame in `space` (the scene's [output] color_space; "" = the
// working space of `color`): half or float, one part or one per layer, the colour space's name
// and chromaticities (none for a display-encoded space), mirage:version, mirage:ocio_config and
// mirage:complete = "true".
ExrOptions finishedFrameHeader(const ColorPipeline& color, const std::string& space,
                               bool halfFloat, bool multipart);

// Converts a developed image from the working space of `color` into `space` ("" or the working
// space's name: nothing to do): the beauty and the layers whose R G B convert like it.
void convertToOutputSpace(const ColorPipeline& color, const std::string& space, Image* image);

// True when `exrPath` is a finished Mirage frame (mirage:complete = "true"); a missing or
// unreadable file is not.
bool isCompleteFrame(const std::string& exrPath);

}  // namespace mirage
