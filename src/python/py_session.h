// mirage.Session: a progressive render of a scene, rendered in passes on a thread of its own
// while Python iterates over one image per pass (render/passes.h: each pass adds samples to every
// pixel, so each image is the render so far). cancel() stops it between tiles, keeping the whole
// passes; update({key: value}) lays --set keys over the scene and restarts, its grids kept
// (volume/grid_cache.h) unless the edit changed which are read; a KeyboardInterrupt while
// waiting for an image cancels the render and propagates.
#pragma once

#include <pybind11/pybind11.h>

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "python/py_render.h"

namespace mirage::python {

class PyScene;

class PySession {
public:
    // The render's keyword arguments are mirage.render's. Without passes, time_limit or
    // noise_threshold, the session renders film.spp (or spp=) in passes of [render] pass_spp.
    // Loads the frame (errors raise here) and starts rendering.
    PySession(std::shared_ptr<PyScene> scene, pybind11::kwargs kwargs);
    ~PySession();

    // The next pass's image, waiting for it (the GIL released); StopIteration once the render
    // is finished or cancelled and every image was taken. A render's error raises here.
    std::shared_ptr<PyImage> next();
    void cancel();                           // stops the render; waits for its thread
    void update(const pybind11::dict& set);  // --set keys over the scene's; restarts
    std::shared_ptr<PyImage> result();       // the finished frame; waits for it; None if cancelled
    bool done();                             // the render has stopped
    int generation() const { return mGeneration; }  // updates so far

private:
    void start(std::shared_ptr<const LoadedFrame> frame);
    void stop();  // cancel and join; with the GIL released
    void renderThread(std::shared_ptr<const LoadedFrame> frame, int generation);
    void push(std::shared_ptr<PyImage> image);

    std::shared_ptr<PyScene> mScene;
    pybind11::kwargs mKwargs;
    std::vector<std::string> mSet;  // update()'s --set keys, in order
    RenderCall mCall;
    CancelToken mCancel;
    std::thread mThread;
    int mGeneration = 0;

    std::mutex mMutex;
    std::condition_variable mChanged;
    std::deque<std::shared_ptr<PyImage>> mImages;
    std::shared_ptr<PyImage> mResult;
    std::exception_ptr mError;
    bool mDone = false;
};

}  // namespace mirage::python
