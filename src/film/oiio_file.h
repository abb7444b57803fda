// The one atomic image writer of film/ (image_io.cpp), for the files that need OIIO's own
// ImageSpec (an assembled frame's channels and attributes, exr_assembly.cpp). Only film/
// includes it: OIIO stays out of every other stage's headers.
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

namespace mirage {

// Writes `spec` and the pixels (float, `xstride` bytes apart) through a temporary file next to
// `path`, then renames it into place. On any failure the temporary file is removed and a
// MirageError names `path`. The format follows the extension of `path`, not of the temporary.
void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, const float* pixels,
                     OIIO::stride_t xstride);
// The same for a file of several subimages (EXR parts), pixels[i] those of specs[i].
void writeSubimagesAtomically(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                              const std::vector<const float*>& pixels,
                              OIIO::stride_t xstride = OIIO::AutoStride);

}  // namespace mirage
