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
};

void writeExr(const std::string& path, const Image& image, const ExrOptions& options);
// Reads an RGBA EXR back (tests, the tradeoff instrument). Throws MirageError on failure.
Image readExr(const std::string& path, std::map<std::string, std::string>* metadata = nullptr);

// Converts a working-space image through display/view and writes an 8-bit preview.
void writePreview(const std::string& path, const Image& image, const ColorPipeline& color,
                  const std::string& display, const std::string& view);

}  // namespace mirage
