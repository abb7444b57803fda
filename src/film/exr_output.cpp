#include "film/exr_output.h"

#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"

namespace mirage {

void writeOpenExrAtomically(const std::string& path, const OIIO::ImageSpec& spec,
                            const std::function<bool(OIIO::ImageOutput&)>& writePixels,
                            const std::string& what) {
    auto fail = [&](const std::string& message) {
        throw MirageError(FileLoc{path, 0, 0}, message);
    };
    createParentFolders(path);
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("openexr");
            if (!out) fail("no OpenEXR writer: " + OIIO::geterror());
            if (!out->open(tmp, spec))
                fail("cannot open '" + tmp + "' for writing: " + out->geterror());
            bool ok = writePixels(*out);
            ok = out->close() && ok;
            if (!ok) fail("cannot write the " + what + ": " + out->geterror());
        },
        "cannot move the " + what + " into place");
}

}  // namespace mirage
