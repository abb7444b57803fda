// Image output through OpenImageIO: scene-linear OpenEXR with colour-space tags and metadata,
// and display-referred previews (PNG/JPEG) through an OCIO display/view. Every file is written
// to a temporary name in the same folder and renamed, so a killed render never leaves a broken
// file where a good one was expected.
#pragma once

#include <map>
#include <string>

#include "film/film.h"

namespace mirage {

struct ExrOptions {
    bool halfFloat = true;  // half by default, float on request
    std::string colorSpace;  // tag written as oiio:ColorSpace; chromaticities follow it
    std::vector<float> chromaticities;  // 8 values, optional
    std::map<std::string, std::string> metadata;  // written as "mirage:<key>" string attributes
    // A region of a larger frame (mirage render --region): the image is the data window, its
    // pixel (0, 0) at (dataX, dataY) of a display window fullWidth × fullHeight from (0, 0).
    // fullWidth = 0: the image is the whole frame.
    int dataX = 0, dataY = 0, fullWidth = 0, fullHeight = 0;
    // Image::layers (the AOVs) as parts of their own instead of channels of the beauty's part.
    bool multipart = false;
};

// Writes the beauty as R G B A and each layer's channels as `layer.channel` (depth in float
// even when the rest is half): one part, or with options.multipart one part per layer, named
// "rgba" and after the layers.

void writeExr(const std::string& path, const Image& image, const ExrOptions& options);
// Reads an RGBA EXR back (tests, the tradeoff instrument), and its `layer.channel` channels as
// Image::layers, from one part or several. Throws MirageError on failure.
Image readExr(const std::string& path, std::map<std::string, std::string>* metadata = nullptr);

// Converts a working-space image through display/view and writes an 8-bit preview.
void writePreview(const std::string& path, const Image& image, const ColorPipeline& color,
                  const std::string& display, const std::string& view);

}  // namespace mirage
