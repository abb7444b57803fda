// The dome light: radiance arriving from infinitely far away in every direction, a constant
// colour (a sky fill) or a latitude–longitude HDR image (an environment map), rotatable about
// the vertical axis (+y). It lights a point by next-event estimation (directions drawn in
// proportion to the image's luminance), shows itself to rays that leave the scene (the camera's
// and those after mirrors and glass: Light::escapedRadiance), and emits photons from a disc
// facing the scene's bounding sphere, as the distant light does.
//
// Image convention: row 0 is the zenith (+y), the last row the nadir; the image's centre
// (u = ½) looks along −z and u grows towards +x (so a camera looking along −z sees the middle of
// the image, left to right). `rotation` turns the dome by that many degrees about +y,
// counter-clockwise seen from above. The pixels are RGB in the scene's working space (like every
// `color` key), scene-linear radiance: a pixel (1, 1, 1) is seen by the camera as (1, 1, 1).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/matrix.h"
#include "light/light.h"

namespace mirage {

// A latitude–longitude image: width × height RGB pixels, row-major from the top row.
struct LatLongImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 × width × height
};

// Reads an image file (anything OpenImageIO reads: .hdr, .exr, …) as RGB (a grey image as
// grey, extra channels ignored); Radiance .hdr pictures through light/radiance_hdr.h, the same
// values faster. Throws MirageError naming the file when it cannot.
LatLongImage readLatLongImage(const std::string& path);

struct DomeSettings {
    float rotationDeg = 0.f;    // about +y
    bool cameraVisible = true;  // false: camera rays see black where they leave the scene
};

// A dome of constant spectral radiance L(λ) (W·m⁻²·sr⁻¹·nm⁻¹).
std::unique_ptr<Light> makeDomeLight(const Spectrum& radiance, const DomeSettings& settings);
// A dome showing `image` (working-space RGB, xyzToWorking of the scene's colour pipeline)
// times `intensity`. Throws MirageError for an empty image or non-finite pixels.
std::unique_ptr<Light> makeDomeLight(const LatLongImage& image, float intensity,
                                     const Mat3& xyzToWorking, const DomeSettings& settings,
                                     const std::string& source = "");

}  // namespace mirage
