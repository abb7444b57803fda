// Image files through OpenImageIO: scene-linear OpenEXR with colour tags and Mirage metadata,
// 8-bit display previews, and the EXR reader the tests and the tradeoff instrument use.
//
// Every write goes through the atomic writer of oiio_file.h: a reader (a compositor watching the
// folder, a render farm's checker) sees the old file or the new one, never half of one.

#include "film/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "film/color.h"
#include "film/oiio_file.h"

namespace mirage {

namespace {

namespace fs = std::filesystem;

// The colour-space tag as an EXR header attribute. OIIO 2.4 treats "oiio:ColorSpace" as an
// in-memory hint: it does not store it in EXR files and reports "Linear" for every EXR it reads.
// Mirage therefore also writes the name under its own prefix and maps it back when reading.
constexpr const char* kColorSpaceAttr = "mirage:colorSpace";

// Largest finite half (IEEE 754 binary16). Larger values would become +∞ in a half EXR and
// poison every filter a compositor runs over them; a clamped highlight is still a highlight.
constexpr float kHalfMax = 65504.f;

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw MirageError(FileLoc{path, 0, 0}, message);
}

void checkImage(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
        fail(path, "cannot write an empty or inconsistent image (" + std::to_string(image.width) +
                       " x " + std::to_string(image.height) + ", " +
                       std::to_string(image.rgba.size()) + " floats)");
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

namespace {

// A region of a larger frame (ExrOptions::fullWidth > 0): the image is the data window, placed
// at (dataX, dataY) of a display window that is the whole frame.
void placeDataWindow(const ExrOptions& options, const Image& image, OIIO::ImageSpec* spec) {
    if (options.fullWidth <= 0) return;
    MIRAGE_CHECK(options.dataX >= 0 && options.dataY >= 0 &&
                 options.dataX + image.width <= options.fullWidth &&
                 options.dataY + image.height <= options.fullHeight);
    spec->x = options.dataX;
    spec->y = options.dataY;
    spec->full_x = spec->full_y = 0;
    spec->full_width = options.fullWidth;
    spec->full_height = options.fullHeight;
}

// The header every part of an EXR shares: compression, colour tags, metadata.
void describeExr(const ExrOptions& options, OIIO::ImageSpec* spec) {
    // ZIP (16 scanlines per block, lossless): the usual choice for final frames, read fast by
    // every compositor; rendered noise defeats the gain PIZ has on photographs.
    spec->attribute("compression", "zip");
    if (!options.colorSpace.empty()) {
        spec->attribute("oiio:ColorSpace", options.colorSpace);
        spec->attribute(kColorSpaceAttr, options.colorSpace);
    }
    if (!options.chromaticities.empty())
        spec->attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8),
                        options.chromaticities.data());
    for (const auto& [key, value] : options.metadata) spec->attribute("mirage:" + key, value);
}

// Interleaved channels and their names and formats, to be written as one part.
struct Channels {
    std::vector<std::string> names;
    std::vector<OIIO::TypeDesc> formats;
    std::vector<const std::vector<float>*> sources;  // interleaved source of each channel
    std::vector<int> strides, offsets;               // floats per pixel, channel in the pixel

    void add(const std::string& name, OIIO::TypeDesc format, const std::vector<float>& src,
             int stride, int offset) {
        names.push_back(name);
        formats.push_back(format);
        sources.push_back(&src);
        strides.push_back(stride);
        offsets.push_back(offset);
    }
    void addLayer(const ImageLayer& layer, bool half) {
        const int n = int(layer.channels.size());
        for (int c = 0; c < n; ++c)
            // Depth stays float: half keeps three digits, a compositor's Z needs more.
            add(layer.name + "." + layer.channels[c],
                half && !layer.fullFloat && layer.channels[c] != "Z" ? OIIO::TypeHalf
                                                                     : OIIO::TypeFloat,
                layer.pixels, n, c);
    }
    // The part's pixels, channel-interleaved, half channels clamped to the finite half range.
    std::vector<float> interleave(size_t pixels) const {
        const size_t n = names.size();
        std::vector<float> out(pixels * n);
        for (size_t c = 0; c < n; ++c) {
            const bool half = formats[c] == OIIO::TypeHalf;
            for (size_t p = 0; p < pixels; ++p) {
                float v = (*sources[c])[p * size_t(strides[c]) + size_t(offsets[c])];
                if (half && std::isfinite(v)) v = clamp(v, -kHalfMax, kHalfMax);
                out[p * n + c] = v;
            }
        }
        return out;
    }
    OIIO::ImageSpec spec(const Image& image, const std::string& partName,
                         const ExrOptions& options) const {
        OIIO::ImageSpec spec(image.width, image.height, int(names.size()), formats[0]);
        spec.channelnames = names;
        spec.channelformats = formats;
        auto a = std::find(names.begin(), names.end(), "A");
        spec.alpha_channel = a == names.end() ? -1 : int(a - names.begin());
        if (!partName.empty()) spec.attribute("name", partName);
        describeExr(options, &spec);
        for (const auto& [key, value] : image.attributes) spec.attribute(key, value);
        return spec;
    }
};

}  // namespace

void writeExr(const std::string& path, const Image& image, const ExrOptions& options) {
    checkImage(path, image);
    if (lowerExtension(path) != ".exr") fail(path, "an OpenEXR file name must end in .exr");
    MIRAGE_CHECK(options.chromaticities.empty() || options.chromaticities.size() == 8);
    const size_t pixels = size_t(image.width) * size_t(image.height);
    for (const ImageLayer& layer : image.layers)
        MIRAGE_CHECK(layer.pixels.size() == pixels * layer.channels.size());

    const OIIO::TypeDesc format = options.halfFloat ? OIIO::TypeHalf : OIIO::TypeFloat;
    std::vector<Channels> parts(1);
    for (int c = 0; c < 4; ++c) parts[0].add(std::string(1, "RGBA"[c]), format, image.rgba, 4, c);
    for (const ImageLayer& layer : image.layers) {
        if (options.multipart) parts.emplace_back();
        parts.back().addLayer(layer, options.halfFloat);
    }
    std::vector<std::vector<float>> buffers;
    std::vector<OIIO::ImageSpec> specs;
    for (size_t i = 0; i < parts.size(); ++i) {
        buffers.push_back(parts[i].interleave(pixels));
        const std::string name = !options.multipart ? ""
                                 : i == 0           ? "rgba"
                                                    : image.layers[i - 1].name;
        specs.push_back(parts[i].spec(image, name, options));
        placeDataWindow(options, image, &specs.back());
    }
    std::vector<const float*> data;
    for (const std::vector<float>& b : buffers) data.push_back(b.data());
    writeSubimagesAtomically(path, specs, data, OIIO::AutoStride);
}

namespace {

// The `layer.channel` channels of the current part into image->layers, in the order the file
// stores them (a layer read before from another part is extended).
void readLayers(const OIIO::ImageSpec& spec, const std::vector<float>& all, Image* image) {
    const int n = spec.nchannels;
    const size_t pixels = size_t(spec.width) * size_t(spec.height);
    for (int c = 0; c < n; ++c) {
        const std::string& full = spec.channelnames[size_t(c)];
        const size_t dot = full.rfind('.');
        if (dot == std::string::npos || dot == 0) continue;
        const std::string name = full.substr(0, dot);
        auto it = std::find_if(image->layers.begin(), image->layers.end(),
                               [&](const ImageLayer& l) { return l.name == name; });
        if (it == image->layers.end()) {
            image->layers.push_back({name, {}, {}});
            it = image->layers.end() - 1;
        }
        it->channels.push_back(full.substr(dot + 1));
        std::vector<float> merged(pixels * it->channels.size());
        const size_t m = it->channels.size();
        for (size_t p = 0; p < pixels; ++p) {
            for (size_t k = 0; k + 1 < m; ++k) merged[p * m + k] = it->pixels[p * (m - 1) + k];
            merged[p * m + m - 1] = all[p * size_t(n) + size_t(c)];
        }
        it->pixels = std::move(merged);
    }
}

}  // namespace

Image readExr(const std::string& path, std::map<std::string, std::string>* metadata) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (!in) fail(path, "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    int n = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || n <= 0) fail(path, "image has no pixels");

    std::vector<float> all(size_t(spec.width) * spec.height * n);
    if (!in->read_image(0, 0, 0, n, OIIO::TypeFloat, all.data()))
        fail(path, "cannot read pixels: " + in->geterror());

    // Channels by name (EXR stores them sorted: A, B, G, R); a single-channel image is grey.
    auto channel = [&spec, n](const char* name, int fallback) {
        int c = spec.channelindex(name);
        return c >= 0 ? c : std::min(fallback, n - 1);
    };
    int r = channel("R", 0), g = channel("G", 1), b = channel("B", 2);
    int a = spec.alpha_channel >= 0 ? spec.alpha_channel : spec.channelindex("A");

    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.rgba.resize(size_t(spec.width) * spec.height * 4);
    for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p) {
        const float* src = &all[p * n];
        float* dst = &image.rgba[p * 4];
        dst[0] = src[r];
        dst[1] = src[g];
        dst[2] = src[b];
        dst[3] = a >= 0 ? src[a] : 1.f;  // no alpha: fully covered
    }
    readLayers(spec, all, &image);
    // Further parts of a multi-part file: their layers, when they match the first's size.
    for (int part = 1; in->seek_subimage(part, 0); ++part) {
        const OIIO::ImageSpec& ps = in->spec();
        if (ps.width != spec.width || ps.height != spec.height || ps.deep) continue;
        std::vector<float> more(size_t(ps.width) * ps.height * size_t(ps.nchannels));
        if (!in->read_image(part, 0, 0, ps.nchannels, OIIO::TypeFloat, more.data()))
            fail(path,
                 "cannot read pixels of part " + std::to_string(part) + ": " + in->geterror());
        readLayers(ps, more, &image);
    }

    if (metadata) {
        metadata->clear();
        for (const OIIO::ParamValue& p : spec.extra_attribs)
            (*metadata)[p.name().string()] = p.get_string(1024);
        auto tag = metadata->find(kColorSpaceAttr);
        if (tag != metadata->end()) (*metadata)["oiio:ColorSpace"] = tag->second;
    }
    in->close();
    return image;
}

// Previews are 8-bit RGB: the image is premultiplied (alpha is coverage), so dropping alpha shows
// it over black, which is what a viewer of a render expects; PNG would otherwise need
// un-premultiplied colour and JPEG has no alpha at all. OIIO rounds and clamps float → 8 bit.
void writePreview(const std::string& path, const Image& image, const ColorPipeline& color,
                  const std::string& display, const std::string& view) {
    checkImage(path, image);
    std::string ext = lowerExtension(path);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
        fail(path, "a preview must be a .png, .jpg or .jpeg file");

    std::vector<float> pixels(image.rgba);
    color.toDisplay(pixels, 4, display, view);
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeUInt8);
    if (ext != ".png") spec.attribute("CompressionQuality", 95);
    writeAtomically(path, spec, pixels.data(), 4 * sizeof(float));
}

}  // namespace mirage
