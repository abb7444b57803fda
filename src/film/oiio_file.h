// The one atomic image writer of film/: every file film/ writes through OpenImageIO (EXR frames
// and their parts, previews, assembled frames, deep images, partial files) goes to a temporary
// file next to its target and is renamed into place only once complete and closed
// (core/atomic_file.h), so a reader never sees half a file and a killed write leaves the previous
// good file alone. Only film/ includes it: OIIO stays out of every other stage's headers.
#pragma once

#include <OpenImageIO/imageio.h>

#include <functional>
#include <string>
#include <vector>

namespace mirage {

// Writes subimage `index` once the writer has opened it; false: OIIO failed (its message is
// read from the writer).
using SubimagePixels = std::function<bool(OIIO::ImageOutput& out, size_t index)>;

// Writes the subimages `specs` (several: EXR parts) through a temporary file next to `path`, then
// renames it into place. `what` "" is an image whose writer the extension of `path` chooses (the
// temporary's name has none), whose folder is created or refused with a message; else the
// OpenEXR file of that name ("deep image", "partial file": the partial file ends in .partial),
// and the messages name it. On any failure the temporary file is removed and a MirageError names
// `path`.
void writeImageAtomically(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                          const SubimagePixels& writePixels, const std::string& what = "");

// Float pixels, `xstride` bytes apart: one image, or one per subimage (pixels[i] those of
// specs[i]).
void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, const float* pixels,
                     OIIO::stride_t xstride);
void writeSubimagesAtomically(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                              const std::vector<const float*>& pixels,
                              OIIO::stride_t xstride = OIIO::AutoStride);

}  // namespace mirage
