// The atomic image writer (oiio_file.h).
#include "film/oiio_file.h"

#include <filesystem>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"

namespace mirage {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw MirageError(FileLoc{path, 0, 0}, message);
}

// An image's folder, created where missing; a path without a file name is refused.
void prepareFolder(const std::string& path) {
    const fs::path target(path);
    if (target.filename().empty() || target.filename() == "." || target.filename() == "..")
        fail(path, "not a file name");
    const fs::path dir = target.parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) fail(path, "cannot create the folder '" + dir.string() + "': " + ec.message());
    }
}

std::unique_ptr<OIIO::ImageOutput> createWriter(const std::string& path, const std::string& what) {
    std::unique_ptr<OIIO::ImageOutput> out =
        OIIO::ImageOutput::create(what.empty() ? path : std::string("openexr"));
    if (!out)
        fail(path, (what.empty() ? "no image writer for this file type: " : "no OpenEXR writer: ") +
                       OIIO::geterror());
    return out;
}

}  // namespace

void writeImageAtomically(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                          const SubimagePixels& writePixels, const std::string& what) {
    MIRAGE_CHECK(!specs.empty());
    if (what.empty())
        prepareFolder(path);
    else
        createParentFolders(path);  // quiet: opening the temporary reports a missing folder
    replaceFileAtomically(
        path,
        [&](const std::string& tmp) {
            std::unique_ptr<OIIO::ImageOutput> out = createWriter(path, what);
            const bool several = specs.size() > 1;
            if (several && !out->supports("multiimage"))
                fail(path, "this file type holds one image, not " + std::to_string(specs.size()));
            if (!(several ? out->open(tmp, int(specs.size()), specs.data())
                          : out->open(tmp, specs[0])))
                fail(path, "cannot open '" + tmp + "' for writing: " + out->geterror());
            bool ok = true;
            for (size_t i = 0; i < specs.size() && ok; ++i) {
                if (i > 0) ok = out->open(tmp, specs[i], OIIO::ImageOutput::AppendSubimage);
                ok = ok && writePixels(*out, i);
            }
            ok = out->close() && ok;
            if (!ok)
                fail(path, (what.empty() ? "cannot write: " : "cannot write the " + what + ": ") +
                               out->geterror());
        },
        "cannot move the " + (what.empty() ? std::string("finished file") : what) + " into place");
}

void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, const float* pixels,
                     OIIO::stride_t xstride) {
    writeSubimagesAtomically(path, {spec}, {pixels}, xstride);
}

void writeSubimagesAtomically(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                              const std::vector<const float*>& pixels, OIIO::stride_t xstride) {
    MIRAGE_CHECK(specs.size() == pixels.size());
    writeImageAtomically(path, specs, [&](OIIO::ImageOutput& out, size_t i) {
        return out.write_image(OIIO::TypeFloat, pixels[i], xstride);
    });
}

}  // namespace mirage
