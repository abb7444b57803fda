// One OpenEXR file written atomically (core/atomic_file.h): the writer opens a temporary file
// next to the target, the caller writes the pixels, and the finished file is renamed into
// place; a failure removes the temporary and throws MirageError naming the target and `what`
// was being written. Shared by the partial file and the deep image.
#pragma once

#include <OpenImageIO/imageio.h>

#include <functional>
#include <string>

namespace mirage {

void writeOpenExrAtomically(const std::string& path, const OIIO::ImageSpec& spec,
                            const std::function<bool(OIIO::ImageOutput&)>& writePixels,
                            const std::string& what);

}  // namespace mirage
