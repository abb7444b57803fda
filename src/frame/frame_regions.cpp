#include "frame/frame_regions.h"

#include <cstdint>
#include <cstdio>

#include "core/error.h"

namespace mirage {

PixelWindow parsePixelWindow(const std::string& text, int width, int height) {
    PixelWindow w;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &w.x0, &w.y0, &w.x1, &w.y1, &tail) != 4)
        throw MirageError("--region '" + text +
                          "': expected X0,Y0,X1,Y1 (pixel bounds, X1 and Y1 exclusive), e.g. "
                          "0,0,320,180");
    if (w.x0 < 0 || w.y0 < 0 || w.x1 > width || w.y1 > height || w.empty())
        throw MirageError("--region '" + text + "': expected 0 ≤ X0 < X1 ≤ " +
                          std::to_string(width) + " and 0 ≤ Y0 < Y1 ≤ " + std::to_string(height) +
                          " (the frame is " + std::to_string(width) + "x" + std::to_string(height) +
                          ")");
    return w;
}

std::string formatPixelWindow(const PixelWindow& w) {
    return std::to_string(w.x0) + "," + std::to_string(w.y0) + "," + std::to_string(w.x1) + "," +
           std::to_string(w.y1);
}

TileGrid parseTileGrid(const std::string& text) {
    TileGrid g;
    char x = 0, tail = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &g.columns, &x, &g.rows, &tail) != 3 || x != 'x' ||
        g.columns < 1 || g.rows < 1 || g.columns > 64 || g.rows > 64)
        throw MirageError("--tiles '" + text +
                          "': expected CxR, columns by rows of tiles, each 1 to 64, e.g. 2x2");
    return g;
}

PixelWindow tileWindow(const TileGrid& grid, int tile, int width, int height) {
    if (width < grid.columns || height < grid.rows)
        throw MirageError("--tiles " + std::to_string(grid.columns) + "x" +
                          std::to_string(grid.rows) + ": the " + std::to_string(width) + "x" +
                          std::to_string(height) + " frame has fewer pixels than tiles");
    const int c = tile % grid.columns, r = tile / grid.columns;
    auto edge = [](int i, int n, int size) { return int(int64_t(i) * size / n); };
    return {edge(c, grid.columns, width), edge(r, grid.rows, height),
            edge(c + 1, grid.columns, width), edge(r + 1, grid.rows, height)};
}

}  // namespace mirage
