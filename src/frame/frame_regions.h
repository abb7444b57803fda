// Regions of a shot (its frames: parseFrameRange, scene/scene.h): the text of `--region
// X0,Y0,X1,Y1` and the split of a frame into C × R tiles that `mirage farm` renders as separate
// tasks (and `mirage assemble` joins again).
#pragma once

#include <string>
#include <vector>

#include "render/renderer.h"

namespace mirage {

// "X0,Y0,X1,Y1": pixel bounds of the full width × height frame, X0 < X1 ≤ width and
// Y0 < Y1 ≤ height (X1, Y1 exclusive). Throws MirageError naming the option and the frame.
PixelWindow parsePixelWindow(const std::string& text, int width, int height);
std::string formatPixelWindow(const PixelWindow& w);

// "CxR" (columns × rows of tiles), each from 1 to 64. Throws MirageError.
struct TileGrid {
    int columns = 1, rows = 1;
    int count() const { return columns * rows; }
};
TileGrid parseTileGrid(const std::string& text);

// Tile i of the grid (row-major from the top-left): column edges at ⌊c·width/C⌋, row edges at
// ⌊r·height/R⌋, so the tiles cover the frame exactly once. Throws MirageError when the frame
// has fewer pixels than tiles along an axis.
PixelWindow tileWindow(const TileGrid& grid, int tile, int width, int height);

}  // namespace mirage
