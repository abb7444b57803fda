#include "light/radiance_hdr.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"

namespace mirage {

namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// The file's bytes, read at once (a sky map is a few megabytes), and where the reader is.
struct Bytes {
    std::vector<unsigned char> data;
    size_t at = 0;
    int get() { return at < data.size() ? data[at++] : EOF; }
    bool take(unsigned char* out, size_t n) {
        if (data.size() - at < n) return false;
        std::memcpy(out, &data[at], n);
        at += n;
        return true;
    }
};

// One header line without its newline; false at the end of the file.
bool readLine(Bytes& f, std::string* line) {
    line->clear();
    for (int c; (c = f.get()) != EOF;) {
        if (c == '\n') return true;
        if (line->size() > 4096) return false;  // no text header: a binary file
        line->push_back(char(c));
    }
    return !line->empty();
}

// The header up to its blank line: false where it is not an RGBE picture's.
bool readHeader(Bytes& f, int* width, int* height) {
    std::string line;
    if (!readLine(f, &line) || (line != "#?RADIANCE" && line != "#?RGBE")) return false;
    bool rgbe = true;  // a header without FORMAT is RGBE
    while (readLine(f, &line) && !line.empty())
        if (line.rfind("FORMAT=", 0) == 0) rgbe = line == "FORMAT=32-bit_rle_rgbe";
    if (!rgbe || !readLine(f, &line)) return false;
    char y[3] = {}, x[3] = {};
    char tail = 0;
    if (std::sscanf(line.c_str(), "%2s %d %2s %d%c", y, height, x, width, &tail) != 4)
        return false;
    return std::strcmp(y, "-Y") == 0 && std::strcmp(x, "+X") == 0 && *width > 0 && *height > 0 &&
           *width <= (1 << 16) && *height <= (1 << 16);
}

// One scanline of RGBE bytes: run-length encoded in four planes (a scanline 8 to 32767 wide
// starting 2 2 hi lo), else flat. A flat pixel 1 1 1 n is a pixel, as OIIO reads it, not the
// repeat of the 1980s' scheme.
void readScanline(Bytes& f, int width, unsigned char* rgbe, const std::string& path) {
    unsigned char head[4];
    if (!f.take(head, 4)) throw MirageError(path + ": the RGBE picture is truncated");
    const bool encoded = width >= 8 && width < 32768 && head[0] == 2 && head[1] == 2 &&
                         (head[2] & 0x80) == 0;
    if (!encoded) {
        std::memcpy(rgbe, head, 4);
        if (!f.take(rgbe + 4, 4 * (size_t(width) - 1)))
            throw MirageError(path + ": the RGBE picture is truncated");
        return;
    }
    if ((head[2] << 8 | head[3]) != width)
        throw MirageError(path + ": an RGBE scanline's length is not the picture's width");
    for (int plane = 0; plane < 4; ++plane)
        for (int i = 0; i < width;) {
            const int code = f.get();
            if (code == EOF) throw MirageError(path + ": the RGBE picture is truncated");
            const bool run = code > 128;
            const int n = run ? code - 128 : code;
            if (n == 0 || i + n > width)
                throw MirageError(path + ": an RGBE scanline overruns the picture's width");
            if (run) {
                const int v = f.get();
                if (v == EOF) throw MirageError(path + ": the RGBE picture is truncated");
                for (int k = 0; k < n; ++k) rgbe[4 * (i + k) + plane] = (unsigned char)v;
            } else {
                for (int k = 0; k < n; ++k) {
                    const int v = f.get();
                    if (v == EOF) throw MirageError(path + ": the RGBE picture is truncated");
                    rgbe[4 * (i + k) + plane] = (unsigned char)v;
                }
            }
            i += n;
        }
}

}  // namespace

bool readRadianceHdr(const std::string& path, RadianceHdr* out) {
    File file(std::fopen(path.c_str(), "rb"));
    if (!file) return false;
    char magic[2] = {};
    if (std::fread(magic, 1, 2, file.get()) != 2 || magic[0] != '#' || magic[1] != '?')
        return false;
    Bytes f;
    std::fseek(file.get(), 0, SEEK_END);
    const long size = std::ftell(file.get());
    std::fseek(file.get(), 0, SEEK_SET);
    if (size <= 0) return false;
    f.data.resize(size_t(size));
    if (std::fread(f.data.data(), 1, f.data.size(), file.get()) != f.data.size())
        throw MirageError(path + ": cannot read the file");
    int width = 0, height = 0;
    if (!readHeader(f, &width, &height)) return false;
    // Every scanline takes at least its 4 bytes a pixel (flat) or its 4-byte start and, per
    // plane, 2 bytes a 127-pixel run (encoded): a header promising more than the file holds is
    // refused before its pixels are allocated.
    const double leastPerLine = std::min(4.0 * width, 4.0 + 8.0 * std::ceil(width / 127.0));
    if (double(height) * leastPerLine > double(f.data.size() - f.at))
        throw MirageError(path + ": the RGBE picture is truncated");
    std::vector<unsigned char> line(size_t(width) * 4);
    std::vector<float> rgb(size_t(width) * size_t(height) * 3);
    for (int j = 0; j < height; ++j) {
        readScanline(f, width, line.data(), path);
        float* row = &rgb[size_t(j) * size_t(width) * 3];
        for (int i = 0; i < width; ++i) {
            const unsigned char* p = &line[4 * size_t(i)];
            // Mantissas over 256 times the exponent's power of two, 2^(e − 128 − 8).
            const float scale = p[3] ? std::ldexp(1.f, int(p[3]) - 136) : 0.f;
            for (int k = 0; k < 3; ++k) row[3 * i + k] = float(p[k]) * scale;
        }
    }
    out->width = width;
    out->height = height;
    out->rgb = std::move(rgb);
    return true;
}

}  // namespace mirage
