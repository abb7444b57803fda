// The partial file: see partial_film.h for the layout and why it holds the accumulators.

#include "film/partial_film.h"

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cstring>

#include "core/error.h"
#include "core/text.h"
#include "film/oiio_file.h"

namespace mirage {

namespace {

// The accumulator channels, in the order of PixelRecord::acc: the pixel's doubles (pixelDouble)
// as high and low words, then its two counts.
const char* const kAccChannels[] = {
    "acc.Xhi",  "acc.Xlo",  "acc.Yhi",  "acc.Ylo",  "acc.Zhi",  "acc.Zlo",  "acc.Ahi", "acc.Alo",
    "acc.XXhi", "acc.XXlo", "acc.YYhi", "acc.YYlo", "acc.ZZhi", "acc.ZZlo", "acc.N",   "acc.bad"};
constexpr int kAccDoubles = 7;
constexpr int kAcc = 2 * kAccDoubles + 2;

// The pixel's i-th double: X, Y, Z sums, alpha, then the X², Y², Z² sums.
double* pixelDouble(Film::Pixel& p, int i) {
    return i < 3 ? &p.xyz[i] : i == 3 ? &p.alpha : &p.xyzSq[i - 4];
}

// One pixel in the file's native layout: 4 float channels, then kAcc uint32 channels, then two
// uint32 channels per double of the film's AOV sums (acc.aov<i>hi, acc.aov<i>lo).
struct PixelRecord {
    float rgba[4];
    uint32_t acc[kAcc];
};
static_assert(sizeof(PixelRecord) == 4 * 4 + kAcc * 4, "no padding in the native layout");
constexpr int kRecordWords = int(sizeof(PixelRecord) / 4);

std::string aovChannel(int i, bool high) {
    return "acc.aov" + std::to_string(i) + (high ? "hi" : "lo");
}

// The layout's names and light groups, as the metadata keeps them (the names hold no ',').
std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start < s.size()) {
        size_t comma = s.find(',', start);
        if (comma == std::string::npos) comma = s.size();
        out.push_back(s.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw MirageError(FileLoc{path, 0, 0}, message);
}

void splitDouble(double d, uint32_t* hi, uint32_t* lo) {
    uint64_t bits;
    std::memcpy(&bits, &d, 8);
    *hi = uint32_t(bits >> 32);
    *lo = uint32_t(bits);
}

// Sets the high or the low word of a double (splitDouble's inverse, one word at a time).
void setWord(double* slot, bool high, uint32_t v) {
    uint64_t bits;
    std::memcpy(&bits, slot, 8);
    bits = high ? (bits & 0xffffffffull) | (uint64_t(v) << 32) : (bits & ~0xffffffffull) | v;
    std::memcpy(slot, &bits, 8);
}

// The preview channels of a finished pixel: its mean in the working space.
void developPixel(const Film::Pixel& p, const Mat3& toWorking, float rgba[4]) {
    double inv = 1.0 / double(p.samples);
    Vec3d rgb = toWorking.apply(Vec3d(p.xyz[0] * inv, p.xyz[1] * inv, p.xyz[2] * inv));
    rgba[0] = float(rgb.x);
    rgba[1] = float(rgb.y);
    rgba[2] = float(rgb.z);
    rgba[3] = float(p.alpha * inv);
}

std::string encodeDone(const std::vector<uint8_t>& done) {
    std::string s((done.size() + 3) / 4, '0');
    for (size_t t = 0; t < done.size(); ++t)
        if (done[t]) {
            int v = (s[t / 4] <= '9' ? s[t / 4] - '0' : s[t / 4] - 'a' + 10) | (1 << (t % 4));
            s[t / 4] = "0123456789abcdef"[v];
        }
    return s;
}

bool decodeDone(const std::string& s, size_t tiles, std::vector<uint8_t>* done) {
    if (s.size() != (tiles + 3) / 4) return false;
    done->assign(tiles, 0);
    for (size_t t = 0; t < tiles; ++t) {
        char c = s[t / 4];
        int v = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (v < 0) return false;
        (*done)[t] = (v >> (t % 4)) & 1;
    }
    return true;
}

double nowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::string partialPathFor(const std::string& outputPath) { return outputPath + ".partial"; }

void writePartialFilm(const std::string& path, const Film& film, int tileSize,
                      const std::vector<uint8_t>& done, const Mat3& toWorking,
                      const std::map<std::string, std::string>& metadata,
                      const std::string& compression) {
    const int w = film.width(), h = film.height();
    const int tilesX = (w + tileSize - 1) / tileSize;
    MIRAGE_CHECK(tileSize > 0 && done.size() == size_t(tilesX) * ((h + tileSize - 1) / tileSize));

    // Only finished tiles are read: the others may be in progress on another thread.
    const int stride = film.aovs().stride();
    const size_t words = size_t(kRecordWords + 2 * stride);
    std::vector<uint32_t> record(size_t(w) * h * words, 0u);
    for (size_t t = 0; t < done.size(); ++t) {
        if (!done[t]) continue;
        int x0 = int(t % tilesX) * tileSize, y0 = int(t / tilesX) * tileSize;
        for (int y = y0; y < std::min(y0 + tileSize, h); ++y)
            for (int x = x0; x < std::min(x0 + tileSize, w); ++x) {
                Film::Pixel p = film.pixel(x, y);
                uint32_t* word = &record[(size_t(y) * w + x) * words];
                const double* aov = film.aovSums(x, y);
                for (int i = 0; i < stride; ++i)
                    splitDouble(aov[i], &word[kRecordWords + 2 * i],
                                &word[kRecordWords + 2 * i + 1]);
                PixelRecord r;
                std::memset(&r, 0, sizeof r);
                for (int i = 0; i < kAccDoubles; ++i)
                    splitDouble(*pixelDouble(p, i), &r.acc[2 * i], &r.acc[2 * i + 1]);
                r.acc[2 * kAccDoubles] = p.samples;
                r.acc[2 * kAccDoubles + 1] = p.nonFinite;
                if (p.samples > 0) developPixel(p, toWorking, r.rgba);
                std::memcpy(word, &r, sizeof r);
            }
    }

    OIIO::ImageSpec spec(w, h, int(words), OIIO::TypeFloat);
    spec.channelnames = {"R", "G", "B", "A"};
    spec.channelformats.assign(4, OIIO::TypeFloat);
    for (const char* name : kAccChannels) {
        spec.channelnames.push_back(name);
        spec.channelformats.push_back(OIIO::TypeUInt32);
    }
    for (int i = 0; i < stride; ++i)
        for (bool high : {true, false}) {
            spec.channelnames.push_back(aovChannel(i, high));
            spec.channelformats.push_back(OIIO::TypeUInt32);
        }
    spec.alpha_channel = 3;
    spec.tile_width = tileSize;
    spec.tile_height = tileSize;
    spec.attribute("compression", compression);
    spec.attribute("mirage:partial", "true");
    spec.attribute("mirage:tile_size", std::to_string(tileSize));
    spec.attribute("mirage:tiles_done", encodeDone(done));
    for (const auto& [key, value] : metadata) spec.attribute("mirage:" + key, value);
    if (!film.aovs().empty()) {
        spec.attribute("mirage:aovs", joinList(film.aovs().names(), ","));
        spec.attribute("mirage:light_groups", joinList(film.aovs().lightGroups(), ","));
        // Cryptomatte's object names (letters, digits and _ - . / :, so a comma list).
        spec.attribute("mirage:crypto_volumes", joinList(film.aovs().cryptoObjects().volumes, ","));
        spec.attribute("mirage:crypto_shapes", joinList(film.aovs().cryptoObjects().shapes, ","));
    }

    // Temporary file next to the target, then rename (atomic within one folder).
    writeImageAtomically(
        path, {spec},
        [&](OIIO::ImageOutput& out, size_t) {
            return out.write_image(OIIO::TypeUnknown, record.data(), words * 4);
        },
        "partial file");
}

PartialFilm readPartialFilm(const std::string& path) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create("openexr");
    if (!in) fail(path, "no OpenEXR reader: " + OIIO::geterror());
    OIIO::ImageSpec spec;
    if (!in->open(path, spec)) fail(path, "cannot read the partial file: " + in->geterror());

    PartialFilm result;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        std::string name = p.name().string();
        if (name.rfind("mirage:", 0) == 0) result.metadata[name.substr(7)] = p.get_string(1 << 20);
    }
    if (result.metadata["partial"] != "true")
        fail(path, "not a Mirage partial file (no mirage:partial metadata)");
    const int w = spec.width, h = spec.height;
    result.tileSize = std::atoi(result.metadata["tile_size"].c_str());
    if (w <= 0 || h <= 0 || result.tileSize <= 0)
        fail(path, "partial file has no pixels or no tile size");
    size_t tiles = size_t((w + result.tileSize - 1) / result.tileSize) *
                   size_t((h + result.tileSize - 1) / result.tileSize);
    if (!decodeDone(result.metadata["tiles_done"], tiles, &result.done))
        fail(path, "partial file has a malformed mirage:tiles_done list");

    int index[kAcc];
    for (int c = 0; c < kAcc; ++c) {
        index[c] = spec.channelindex(kAccChannels[c]);
        if (index[c] < 0)
            fail(path,
                 std::string("partial file lacks the accumulator channel ") + kAccChannels[c]);
    }
    AovLayout layout;
    if (!result.metadata["aovs"].empty()) {
        try {
            layout = AovLayout(splitList(result.metadata["aovs"]),
                               splitList(result.metadata["light_groups"]),
                               {splitList(result.metadata["crypto_volumes"]),
                                splitList(result.metadata["crypto_shapes"])});
        } catch (const MirageError& e) {
            fail(path, std::string("partial file has a malformed mirage:aovs list: ") + e.what());
        }
    }
    result.film = std::make_unique<Film>(w, h, layout);
    std::vector<uint32_t> channel(size_t(w) * h);
    for (int c = 0; c < kAcc; ++c) {
        if (!in->read_image(0, 0, index[c], index[c] + 1, OIIO::TypeUInt32, channel.data()))
            fail(path, "cannot read the partial file's pixels: " + in->geterror());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Film::Pixel& p = result.film->pixel(x, y);
                uint32_t v = channel[size_t(y) * w + x];
                // Even channels hold a double's high word, odd ones its low word.
                if (c < 2 * kAccDoubles) {
                    setWord(pixelDouble(p, c / 2), c % 2 == 0, v);
                } else if (c == 2 * kAccDoubles) {
                    p.samples = v;
                } else {
                    p.nonFinite = v;
                }
            }
    }
    for (int i = 0; i < layout.stride(); ++i)
        for (bool high : {true, false}) {
            const std::string name = aovChannel(i, high);
            const int c = spec.channelindex(name);
            if (c < 0) fail(path, "partial file lacks the accumulator channel " + name);
            if (!in->read_image(0, 0, c, c + 1, OIIO::TypeUInt32, channel.data()))
                fail(path, "cannot read the partial file's pixels: " + in->geterror());
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    setWord(&result.film->aovSums(x, y)[i], high, channel[size_t(y) * w + x]);
        }
    in->close();
    return result;
}

PartialFilmWriter::PartialFilmWriter(std::string path, int tileSize, const Mat3& toWorking,
                                     std::map<std::string, std::string> metadata, double minSeconds,
                                     double costFactor)
    : mPath(std::move(path)),
      mTileSize(tileSize),
      mToWorking(toWorking),
      mMetadata(std::move(metadata)),
      mMinSeconds(minSeconds),
      mCostFactor(costFactor),
      mStart(nowSeconds()) {}

void PartialFilmWriter::tileFinished(const Film& film, const std::vector<uint8_t>& done) {
    double now = nowSeconds() - mStart;
    if (now - mLastWrite < std::max(mMinSeconds, mCostFactor * mLastCost)) return;
    write(film, done);
}

void PartialFilmWriter::write(const Film& film, const std::vector<uint8_t>& done) {
    double t0 = nowSeconds();
    writePartialFilm(mPath, film, mTileSize, done, mToWorking, mMetadata);
    double t1 = nowSeconds();
    mLastCost = t1 - t0;
    mWriteSeconds += mLastCost;
    mLastWrite = t1 - mStart;
    ++mWrites;
}

}  // namespace mirage
