// mirage.render and mirage.Image: a render's settings as keyword arguments (the options of
// `mirage render` that a render, not a scene, takes), the render run with the GIL released on a
// thread of its own while the caller's thread watches for KeyboardInterrupt, and its result: the
// beauty and passes as numpy arrays, the EXR header, and write(), which writes the EXR of
// `mirage render`.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/cancel.h"
#include "film/image_io.h"
#include "frame/frame_load.h"
#include "frame/render_frame.h"

namespace mirage::python {

class PyScene;

// A render's settings: the scene's request with the keyword arguments laid over it, and the
// threads it may use (0: every core). `key` identifies the arguments (PyScene::frameFor).
struct RenderCall {
    FrameRequest request;
    int threads = 0;
    std::string key;
};
// Throws TypeError for an unknown argument and MirageError for a bad value. `set` adds --set
// keys after the scene's own (Session.update).
RenderCall renderCall(const PyScene& scene, const pybind11::kwargs& kwargs,
                      const std::vector<std::string>& set = {});
// The names renderCall takes, for messages and documentation.
std::vector<std::string> renderArgumentNames();

// Runs `work` on a thread of its own, the GIL released, while this thread (holding the GIL)
// polls Python's signal handlers: a KeyboardInterrupt (any exception they raise) raises `cancel`,
// waits for `work` to stop and propagates. Exceptions of `work` propagate (MirageError becomes
// mirage.Error). Call with the GIL held.
void runInterruptible(const std::function<void()>& work, CancelToken& cancel);

// Runs `work` inside a TBB arena of `threads` threads (0: every core): a cap on this render's
// threads alone, not the process's.
void inArena(int threads, const std::function<void()>& work);

// One image of a render: the finished frame (with its EXR header) or, in a session, a pass.
class PyImage {
public:
    // The finished frame: header and image as `mirage render` writes them.
    PyImage(const LoadedFrame& frame, std::shared_ptr<const ColorPipeline> color,
            const RenderedFrame& rendered);
    // A pass of a session (the film developed, and how far the render is), or an EXR read.
    PyImage(Image image, std::map<std::string, std::string> metadata, int generation);

    pybind11::array beauty() const;   // H×W×4 float32, the working space
    pybind11::dict aovs() const;      // pass name → H×W×C float32
    pybind11::dict channels() const;  // pass name → its channel names
    pybind11::dict metadata() const;  // the EXR header's attributes (a pass: its progress)
    bool final() const { return mFinal; }
    int generation() const { return mGeneration; }
    int width() const { return mImage.width; }
    int height() const { return mImage.height; }
    // Writes the EXR `mirage render` writes; a pass image has no header to write.
    void write(const std::string& path) const;

private:
    // Not the frame: an image keeps no scene (and no grid) alive.
    std::shared_ptr<const ColorPipeline> mColor;
    std::string mOutputSpace;  // [output] color_space
    Image mImage;              // working space
    std::optional<ExrOptions> mHeader;
    std::map<std::string, std::string> mMetadata;
    bool mFinal = false;
    int mGeneration = 0;
};

// mirage.render(scene, **kwargs).
std::shared_ptr<PyImage> render(PyScene& scene, const pybind11::kwargs& kwargs);

}  // namespace mirage::python
