// Cost of one partial-file write (film/partial_film.h) for a 1920×1080 frame, every pixel
// finished, by OpenEXR compression: the figure that sets how often a render may checkpoint.
// Usage: bench_partial_write [WIDTH HEIGHT] — prints seconds per write and file size.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/rng.h"
#include "film/partial_film.h"

using namespace mirage;

int main(int argc, char** argv) {
    int w = argc > 2 ? std::atoi(argv[1]) : 1920, h = argc > 2 ? std::atoi(argv[2]) : 1080;
    const int tile = 32;
    Film film(w, h);
    // Sums like a render's: smooth image plus noise, so compression sees realistic mantissas.
    Sampler rng(1, 0, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Film::Pixel& p = film.pixel(x, y);
            double base = 16.0 * (0.5 + 0.4 * std::sin(x * 0.01) * std::cos(y * 0.013));
            for (double& c : p.xyz) c = base * (1.0 + 0.2 * (rng.get1Dd() - 0.5));
            p.alpha = 16.0 * rng.get1Dd();
            p.samples = 16;
        }
    std::vector<uint8_t> done(size_t((w + tile - 1) / tile) * ((h + tile - 1) / tile), 1);
    const std::string path =
        (std::filesystem::temp_directory_path() / "bench_partial_write.exr.partial").string();
    std::printf("%dx%d, tiles of %d\ncompression,seconds_per_write,megabytes\n", w, h, tile);
    for (const char* c : {"none", "rle", "zips", "zip", "piz"}) {
        const int runs = 3;
        auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < runs; ++i) writePartialFilm(path, film, tile, done, Mat3(), {}, c);
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("%s,%.3f,%.1f\n", c, s / runs, std::filesystem::file_size(path) / 1048576.0);
    }
    std::filesystem::remove(path);
    return 0;
}
