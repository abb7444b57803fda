// mirage.Session (py_session.h).
#include "python/py_session.h"

#include <chrono>

#include "film/color.h"
#include "film/exr_header.h"
#include "python/py_scene.h"
#include "python/py_toml.h"

namespace mirage::python {

namespace py = pybind11;

namespace {

// The frame of a session: loaded as a render's, then, when the request asks for no render in
// passes, film.spp in passes of pass_spp, which give the bits of one render of film.spp rounded
// up to whole passes (render/passes.h, "Determinism").
std::shared_ptr<const LoadedFrame> sessionFrame(PyScene& scene, const FrameRequest& request) {
    std::optional<LoadedFrame> frame = loadFrame(request, *scene.color(), &scene.grids());
    MIRAGE_CHECK(frame.has_value());
    PassSettings& passes = frame->scene.passes;
    if (!passes.enabled())
        passes.maxPasses =
            std::max(1, (frame->scene.settings.spp + passes.sppPerPass - 1) / passes.sppPerPass);
    return std::make_shared<const LoadedFrame>(std::move(*frame));
}

// Waits on `changed` until `ready`, the GIL released, 20 ms at a time, running Python's signal
// handlers in between: a KeyboardInterrupt calls `interrupted` and propagates.
template <class Ready>
void waitInterruptible(std::unique_lock<std::mutex>& lock, std::condition_variable& changed,
                       Ready ready, const std::function<void()>& interrupted) {
    for (;;) {
        bool met;
        {
            py::gil_scoped_release release;
            met = changed.wait_for(lock, std::chrono::milliseconds(20), ready);
        }
        if (met) return;
        lock.unlock();
        if (PyErr_CheckSignals() != 0) {
            interrupted();
            throw py::error_already_set();
        }
        lock.lock();
    }
}

}  // namespace

PySession::PySession(std::shared_ptr<PyScene> scene, py::kwargs kwargs)
    : mScene(std::move(scene)), mKwargs(std::move(kwargs)) {
    mCall = renderCall(*mScene, mKwargs);
    std::shared_ptr<const LoadedFrame> frame;
    {
        py::gil_scoped_release release;
        frame = sessionFrame(*mScene, mCall.request);
    }
    start(std::move(frame));
}

PySession::~PySession() {
    mCancel.cancel();
    if (!mThread.joinable()) return;
    py::gil_scoped_release release;
    mThread.join();
}

void PySession::start(std::shared_ptr<const LoadedFrame> frame) {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mImages.clear();
        mResult.reset();
        mError = nullptr;
        mDone = false;
    }
    mCancel.reset();
    mThread =
        std::thread([this, frame, generation = mGeneration] { renderThread(frame, generation); });
}

void PySession::stop() {
    mCancel.cancel();
    if (!mThread.joinable()) return;
    py::gil_scoped_release release;
    mThread.join();
}

void PySession::push(std::shared_ptr<PyImage> image) {
    std::lock_guard<std::mutex> lock(mMutex);
    mImages.push_back(std::move(image));
    mChanged.notify_all();
}

// The render, on its own thread: no Python object is touched here.
void PySession::renderThread(std::shared_ptr<const LoadedFrame> frame, int generation) {
    const std::shared_ptr<const ColorPipeline> color = mScene->color();
    std::shared_ptr<PyImage> result;
    std::exception_ptr error;
    try {
        inArena(mCall.threads, [&] {
            PassCheckpoint passes;
            passes.passFinished = [&](const Film& film, int done, double seconds) {
                std::map<std::string, std::string> progress = {
                    {"mirage:passes", std::to_string(done)},
                    {"mirage:time_spent", headerNumber(seconds)},
                    {"mirage:colorSpace", color->workingSpace()}};
                push(std::make_shared<PyImage>(film.develop(*color), std::move(progress),
                                               generation));
            };
            // A time limit's coarse image comes first (render/passes.h), at once.
            passes.coarseFinished = [&](const Film& film, int spp) {
                std::map<std::string, std::string> progress = {
                    {"mirage:passes", "0"},
                    {"mirage:coarse_spp", std::to_string(spp)},
                    {"mirage:colorSpace", color->workingSpace()}};
                push(std::make_shared<PyImage>(film.develop(*color), std::move(progress),
                                               generation));
            };
            const RenderedFrame rendered =
                renderFrame(frame->scene, *color, {nullptr, &passes, &mCancel});
            if (!mCancel.requested()) result = std::make_shared<PyImage>(*frame, color, rendered);
        });
    } catch (...) {
        error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mMutex);
    mResult = std::move(result);
    mError = error;
    mDone = true;
    mChanged.notify_all();
}

std::shared_ptr<PyImage> PySession::next() {
    std::unique_lock<std::mutex> lock(mMutex);
    waitInterruptible(
        lock, mChanged, [&] { return !mImages.empty() || mDone; }, [&] { stop(); });
    if (!mImages.empty()) {
        std::shared_ptr<PyImage> image = std::move(mImages.front());
        mImages.pop_front();
        return image;
    }
    if (mError) std::rethrow_exception(std::exchange(mError, nullptr));
    throw py::stop_iteration();
}

void PySession::cancel() { stop(); }

bool PySession::done() {
    std::lock_guard<std::mutex> lock(mMutex);
    return mDone;
}

std::shared_ptr<PyImage> PySession::result() {
    std::unique_lock<std::mutex> lock(mMutex);
    waitInterruptible(
        lock, mChanged, [&] { return mDone; }, [&] { stop(); });
    if (mError) std::rethrow_exception(std::exchange(mError, nullptr));
    return mResult;
}

void PySession::update(const py::dict& set) {
    stop();
    const std::vector<std::string> before = mSet;
    for (std::string& s : overrideAssignments(set)) mSet.push_back(std::move(s));
    std::shared_ptr<const LoadedFrame> frame;
    try {
        mCall = renderCall(*mScene, mKwargs, mSet);
        py::gil_scoped_release release;
        frame = sessionFrame(*mScene, mCall.request);
    } catch (...) {
        mSet = before;  // a bad edit leaves the session as it was, stopped
        mCall = renderCall(*mScene, mKwargs, mSet);
        throw;
    }
    ++mGeneration;
    start(std::move(frame));
}

}  // namespace mirage::python
