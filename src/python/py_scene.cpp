// mirage.Scene (py_scene.h).
#include "python/py_scene.h"

#include <filesystem>

#include "core/error.h"
#include "python/py_info.h"
#include "python/py_toml.h"
#include "scene/scene_info.h"

namespace mirage::python {

namespace py = pybind11;

std::shared_ptr<const LoadedFrame> loadShared(const FrameRequest& request,
                                              const ColorPipeline& color, GridCache* grids) {
    std::optional<LoadedFrame> frame = loadFrame(request, color, grids);
    MIRAGE_CHECK(frame.has_value());  // only --skip-existing skips a frame
    return std::make_shared<const LoadedFrame>(std::move(*frame));
}

PyScene::PyScene(FrameRequest request, const std::string& ocioConfig,
                 std::shared_ptr<MemoryGrids> memoryGrids)
    : mMemoryGrids(std::move(memoryGrids)), mRequest(std::move(request)) {
    mRequest.quiet = true;  // a program prints what it wants; the library nothing
    py::gil_scoped_release release;
    mColor = std::make_shared<const ColorPipeline>(ocioConfig);
    mBase = mFrame = loadShared(mRequest, *mColor, &mGrids);
}

std::shared_ptr<PyScene> PyScene::load(const std::string& path, const py::dict& set, int frame,
                                       const std::string& ocio) {
    FrameRequest r;
    r.input = path;
    r.frame = frame;
    r.overrides = overrideAssignments(set);
    return std::make_shared<PyScene>(std::move(r), ocio);
}

std::shared_ptr<PyScene> PyScene::fromDict(const py::dict& scene, const py::dict& set, int frame,
                                           const std::string& baseDir, const std::string& ocio) {
    FrameRequest r;
    // The name messages give the scene; its folder is where relative paths resolve from.
    r.input = baseDir.empty() ? "<dict>" : (std::filesystem::path(baseDir) / "<dict>").string();
    auto memoryGrids = std::make_shared<MemoryGrids>();
    r.sceneText = sceneToml(memoryGrids->resolve(scene));
    r.frame = frame;
    r.overrides = overrideAssignments(set);
    return std::make_shared<PyScene>(std::move(r), ocio,
                                     memoryGrids->empty() ? nullptr : memoryGrids);
}

py::dict PyScene::info() const {
    SceneInfo record;
    {
        py::gil_scoped_release release;
        record = describeScene(mBase->scene, *mColor);
    }
    return infoDict(record);
}

std::shared_ptr<const LoadedFrame> PyScene::frameFor(const FrameRequest& request,
                                                     const std::string& key) {
    std::lock_guard<std::mutex> lock(mMutex);
    if (key != mFrameKey) {
        mFrame = loadShared(request, *mColor, &mGrids);
        mFrameKey = key;
    }
    return mFrame;
}

}  // namespace mirage::python
