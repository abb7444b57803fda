// Perspective pinhole camera. Raster (0,0) is the top-left corner of the image; the vertical
// field of view is in degrees, as in most DCC applications.
#pragma once

#include <vector>

#include "core/math.h"
#include "core/rng.h"

namespace mirage {

// Where the camera stands and looks at one time.
struct CameraPose {
    Vec3 position{0, 0, 5};
    Vec3 lookAt{0, 0, 0};
    Vec3 up{0, 1, 0};
    float fovDeg = 40.f;  // vertical
};

// A keyed pose (`[[camera.key]]`): `time` in seconds relative to the frame being rendered.
struct CameraKey {
    float time = 0.f;
    CameraPose pose;
};

struct CameraDesc : CameraPose {
    // The shutter, in seconds relative to the frame's time (motion blur): each camera sample
    // draws its time uniformly in [shutterOpen, shutterClose]. Equal: no blur.
    float shutterOpen = 0.f, shutterClose = 0.f;
    // Camera motion within the shutter. `keys` (sorted by time; empty: the pose above holds at
    // every time) are interpolated piecewise linearly and held beyond the first and last; a
    // turntable then turns the pose about `up` through `lookAt` by orbitDegrees +
    // orbitDegreesPerSecond · Δt. The pose above is always the one at Δt = 0.
    std::vector<CameraKey> keys;
    float orbitDegrees = 0.f, orbitDegreesPerSecond = 0.f;

    bool motionBlur() const { return shutterClose != shutterOpen; }
    // Whether camera rays depend on the sample's time.
    bool moves() const { return motionBlur() && (keys.size() > 1 || orbitDegreesPerSecond != 0.f); }
    // The pose at time offset Δt (seconds) from the frame.
    CameraPose poseAt(float dt) const;
};

// The time offset (seconds) of camera sample `sample` of pixel `pixel`, uniform in the shutter.
// It comes from a stream of its own, keyed like the sample's, so that every other dimension of
// the path is the one a still render draws (a blur of a still medium gives the still image).
inline float shutterTime(const CameraDesc& c, uint64_t seed, uint64_t pixel, uint64_t sample) {
    constexpr uint64_t kShutterStream = 0x5b7e1f3a9c2d4e61ull;
    Sampler t(hashCombine(seed, kShutterStream), pixel, sample);
    return c.shutterOpen + (c.shutterClose - c.shutterOpen) * t.get1D();
}

class PerspectiveCamera {
public:
    PerspectiveCamera(const CameraPose& d, int width, int height)
        : mPos(d.position), mWidth(width), mHeight(height) {
        mForward = normalize(d.lookAt - d.position);
        mRight = normalize(cross(mForward, d.up));
        mUp = cross(mRight, mForward);
        mTanHalf = std::tan(radians(d.fovDeg) * 0.5f);
        mAspect = float(width) / float(height);
    }
    // Ray through raster position (px, py) in pixels.
    Ray generate(float px, float py) const {
        float sx = (2.f * px / mWidth - 1.f) * mTanHalf * mAspect;
        float sy = (1.f - 2.f * py / mHeight) * mTanHalf;
        return {mPos, normalize(mForward + mRight * sx + mUp * sy), kInfinity};
    }

private:
    Vec3 mPos, mForward, mRight, mUp;
    int mWidth, mHeight;
    float mTanHalf, mAspect;
};

// Camera orbit for turntables: rotates the camera position about the vertical axis (up)
// through lookAt by `degrees`.
CameraPose orbitCamera(const CameraPose& base, float degrees);

// The turntable of frame `frame` with `frames` frames per turn, frame 1 where `base` stands:
// the frame's pose, and the turn's rate so that a shutter blurs along the orbit.
void setTurntable(CameraDesc* camera, int frame, int frames, double fps);

}  // namespace mirage
