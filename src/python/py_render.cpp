// mirage.render and mirage.Image (py_render.h).
#include "python/py_render.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "core/text.h"
#include "film/exr_header.h"
#include "frame/frame_output.h"
#include "python/py_scene.h"

namespace mirage::python {

namespace py = pybind11;

namespace {

// "WxH" from a str or a (width, height) pair; "X0,Y0,X1,Y1" from a str or four numbers.
std::string joined(py::handle v, const char* separator) {
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    std::string out;
    for (py::handle e : v) out += (out.empty() ? "" : separator) + std::to_string(e.cast<int>());
    return out;
}

// The keyword arguments of a render: the options of `mirage render` that set a frame's render
// (docs/cli.md names them with dashes), each onto the frame request.
using Setter = void (*)(RenderCall*, py::handle);
const std::vector<std::pair<std::string, Setter>>& renderArguments() {
    static const std::vector<std::pair<std::string, Setter>> table = {
        {"spp", [](RenderCall* c, py::handle v) { c->request.spp = v.cast<int>(); }},
        {"seed", [](RenderCall* c, py::handle v) { c->request.seed = v.cast<int64_t>(); }},
        {"time_limit",
         [](RenderCall* c, py::handle v) { c->request.timeLimit = v.cast<double>(); }},
        {"passes", [](RenderCall* c, py::handle v) { c->request.passes = v.cast<int>(); }},
        {"noise_threshold",
         [](RenderCall* c, py::handle v) { c->request.noiseThreshold = v.cast<double>(); }},
        {"coarse", [](RenderCall* c, py::handle v) { c->request.coarseSpp = v.cast<int>(); }},
        {"threads", [](RenderCall* c, py::handle v) { c->threads = v.cast<int>(); }},
        {"integrator",
         [](RenderCall* c, py::handle v) { c->request.integrator = v.cast<std::string>(); }},
        {"quality",
         [](RenderCall* c, py::handle v) { c->request.quality = v.cast<std::string>(); }},
        {"resolution", [](RenderCall* c, py::handle v) { c->request.resolution = joined(v, "x"); }},
        {"region", [](RenderCall* c, py::handle v) { c->request.region = joined(v, ","); }},
        {"aovs",
         [](RenderCall* c, py::handle v) { c->request.aovs = v.cast<std::vector<std::string>>(); }},
        {"shutter", [](RenderCall* c, py::handle v) { c->request.shutter = v.cast<double>(); }},
        {"motion_blur",
         [](RenderCall* c, py::handle v) { c->request.motionBlur = v.cast<bool>(); }},
        {"float_exr", [](RenderCall* c, py::handle v) { c->request.floatExr = v.cast<bool>(); }},
        {"quiet", [](RenderCall* c, py::handle v) { c->request.quiet = v.cast<bool>(); }},
    };
    return table;
}

py::array_t<float> array(int height, int width, size_t channels, const float* data) {
    py::array_t<float> a({size_t(height), size_t(width), channels});
    std::memcpy(a.mutable_data(), data, sizeof(float) * size_t(height) * size_t(width) * channels);
    return a;
}

}  // namespace

std::vector<std::string> renderArgumentNames() {
    std::vector<std::string> names;
    for (const auto& [name, set] : renderArguments()) names.push_back(name);
    return names;
}

RenderCall renderCall(const PyScene& scene, const py::kwargs& kwargs,
                      const std::vector<std::string>& set) {
    RenderCall call;
    call.request = scene.request();
    for (const std::string& s : set) call.request.overrides.push_back(s);
    py::list items;  // sorted, for the key
    for (const auto& [k, v] : kwargs) {
        const std::string name = py::str(k);
        const auto& table = renderArguments();
        auto it = std::find_if(table.begin(), table.end(),
                               [&](const auto& row) { return row.first == name; });
        if (it == table.end())
            throw py::type_error("unexpected keyword argument '" + name + "'; a render takes " +
                                 joinList(renderArgumentNames()));
        if (v.is_none()) continue;
        try {
            it->second(&call, v);
        } catch (const py::cast_error&) {
            throw py::type_error("'" + name + "' cannot be " +
                                 std::string(py::str(py::type::of(v).attr("__name__"))));
        }
        items.append(py::make_tuple(name, v));
    }
    items.attr("sort")();
    call.key = std::string(py::repr(py::make_tuple(items, py::cast(set))));
    checkFrameRequest(call.request);
    return call;
}

void runInterruptible(const std::function<void()>& work, CancelToken& cancel) {
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::exception_ptr error;
    std::thread worker([&] {
        try {
            work();
        } catch (...) {
            error = std::current_exception();
        }
        std::lock_guard<std::mutex> lock(mutex);
        done = true;
        finished.notify_all();
    });
    for (;;) {
        {
            py::gil_scoped_release release;
            std::unique_lock<std::mutex> lock(mutex);
            // A tile takes milliseconds: 20 ms keeps Ctrl-C within a tile's time of the stop.
            if (finished.wait_for(lock, std::chrono::milliseconds(20), [&] { return done; })) break;
        }
        if (PyErr_CheckSignals() != 0) {
            cancel.cancel();
            {
                py::gil_scoped_release release;
                worker.join();
            }
            throw py::error_already_set();
        }
    }
    worker.join();
    if (error) std::rethrow_exception(error);
}

void inArena(int threads, const std::function<void()>& work) {
    tbb::task_arena arena(threads > 0 ? threads : int(tbb::task_arena::automatic));
    arena.execute(work);
}

PyImage::PyImage(const LoadedFrame& frame, std::shared_ptr<const ColorPipeline> color,
                 const RenderedFrame& rendered)
    : mColor(std::move(color)),
      mOutputSpace(frame.scene.output.colorSpace),
      mImage(rendered.image),
      mFinal(true) {
    mHeader = frameHeader(frame, rendered, *mColor);
    for (const auto& [key, value] : mHeader->metadata) mMetadata["mirage:" + key] = value;
    mMetadata["mirage:colorSpace"] = mHeader->colorSpace;
}

PyImage::PyImage(Image image, std::map<std::string, std::string> metadata, int generation)
    : mImage(std::move(image)), mMetadata(std::move(metadata)), mGeneration(generation) {}

py::array PyImage::beauty() const {
    return array(mImage.height, mImage.width, 4, mImage.rgba.data());
}

py::dict PyImage::aovs() const {
    py::dict d;
    for (const ImageLayer& l : mImage.layers)
        d[py::str(l.name)] = array(mImage.height, mImage.width, l.channels.size(), l.pixels.data());
    return d;
}

py::dict PyImage::channels() const {
    py::dict d;
    for (const ImageLayer& l : mImage.layers) d[py::str(l.name)] = py::cast(l.channels);
    return d;
}

py::dict PyImage::metadata() const { return py::cast(mMetadata); }

void PyImage::write(const std::string& path) const {
    if (!mHeader)
        throw MirageError(path +
                          ": a pass of a session is not a finished frame; write the session's "
                          "result (Session.result) once it is done");
    py::gil_scoped_release release;
    // What writeFrame (frame/frame_output.h) writes: the image in the output colour space.
    Image out = mImage;
    convertToOutputSpace(*mColor, mOutputSpace, &out);
    writeExr(path, out, *mHeader);
}

std::shared_ptr<PyImage> render(PyScene& scene, const py::kwargs& kwargs) {
    const RenderCall call = renderCall(scene, kwargs);
    CancelToken cancel;
    std::shared_ptr<PyImage> image;
    runInterruptible(
        [&] {
            inArena(call.threads, [&] {
                std::shared_ptr<const LoadedFrame> frame = scene.frameFor(call.request, call.key);
                const RenderedFrame rendered =
                    renderFrame(frame->scene, *scene.color(), {nullptr, nullptr, &cancel});
                if (rendered.stats.interrupted && cancel.requested()) return;
                image = std::make_shared<PyImage>(*frame, scene.color(), rendered);
            });
        },
        cancel);
    return image;
}

}  // namespace mirage::python
