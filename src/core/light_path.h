// The light-path classes of the render passes (AOVs): which kind of vertices the light met on
// its way to the camera. A camera path records its scattering vertices as it walks
// (PathHistory, carried by transport/path_vertex.h's PathThroughput), and every contribution is
// tagged with the class of the path it completes, at the one place it is added; the film sums
// one buffer per class. The classes partition the paths, so the passes sum to the beauty by
// construction (docs/aovs.md).
//
// Counting follows the convention of production renderers (Cycles' direct/indirect passes): a
// path of n scattering vertices between the light and the camera is
//   n = 0   emission         light emitted by a medium or surface, seen directly
//   n = 1   *_direct         scattered once, * the kind of that vertex (volume or surface)
//   n ≥ 2   *_indirect       * the kind of the vertex nearest the camera
// and, among the surface paths, `caustic` those whose light passed a specular vertex (mirror,
// glass) after the first diffuse one (Heckbert's L S+ D … E). Mirrors and glass in front of the
// first scattering vertex only move the view: they are not counted.
#pragma once

#include <cstdint>

namespace mirage {

enum class LightPath : uint8_t {
    Emission,
    VolumeDirect,
    VolumeIndirect,
    SurfaceDirect,
    SurfaceIndirect,
    Caustic
};
constexpr int kLightPathCount = 6;

// The pass names, as the scene file and the EXR layers spell them.
inline const char* lightPathName(LightPath p) {
    static const char* const names[kLightPathCount] = {"emission",         "volume_direct",
                                                       "volume_indirect",  "surface_direct",
                                                       "surface_indirect", "caustic"};
    return names[int(p)];
}

// What a camera path has met so far: its scattering vertices (saturating count), the kind of
// the first, and whether a specular vertex followed it.
struct PathHistory {
    uint8_t vertices = 0;
    bool surfaceFirst = false;
    bool specularAfterFirst = false;

    // A scattering vertex (volume scattering, fluorescent re-emission, a diffuse surface).
    void scatter(bool surface) {
        if (vertices == 0) surfaceFirst = surface;
        if (vertices < 255) ++vertices;
    }
    // A mirror or glass vertex.
    void specular() {
        if (vertices > 0) specularAfterFirst = true;
    }

    // The class of light emitted where the path is now (a medium's or a surface's emission).
    LightPath emitted() const { return classify(vertices, surfaceFirst); }
    // The class of light gathered by next-event estimation at a scattering vertex of kind
    // `surface` that the path is at now (recorded with scatter() after the estimate).
    LightPath gathered(bool surface) const {
        return classify(vertices + 1, vertices == 0 ? surface : surfaceFirst);
    }

private:
    LightPath classify(int n, bool surface) const {
        if (n == 0) return LightPath::Emission;
        if (surface && specularAfterFirst) return LightPath::Caustic;
        if (n == 1) return surface ? LightPath::SurfaceDirect : LightPath::VolumeDirect;
        return surface ? LightPath::SurfaceIndirect : LightPath::VolumeIndirect;
    }
};

}  // namespace mirage
