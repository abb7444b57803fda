// mirage.Scene: a scene file, or a dict of its keys, with its --set keys and frame, loaded once
// (so that a bad scene raises where it is loaded, and scene.info() describes it) and again for
// each render whose settings differ, through one GridCache (volume/grid_cache.h), so that grids
// are read from disk once per scene.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <string>

#include "film/color.h"
#include "frame/frame_load.h"
#include "python/py_grids.h"
#include "volume/grid_cache.h"

namespace mirage::python {

class PyScene {
public:
    // `request` names the scene (input, or sceneText with input its name), its overrides and
    // frame. Loads it (the GIL released); throws MirageError as `mirage render` would.
    // `memoryGrids`: the files of the request's in-memory grids, kept as long as the scene.
    PyScene(FrameRequest request, const std::string& ocioConfig,
            std::shared_ptr<MemoryGrids> memoryGrids = nullptr);

    // mirage.load(path, set=, frame=, ocio=) and mirage.Scene.from_dict(dict, set=, frame=,
    // base_dir=, ocio=): the dict's relative paths resolve from base_dir; its volumes may hold
    // their grids in memory (py_grids.h), written to files this scene keeps while it lives.
    static std::shared_ptr<PyScene> load(const std::string& path, const pybind11::dict& set,
                                         int frame, const std::string& ocio);
    static std::shared_ptr<PyScene> fromDict(const pybind11::dict& scene, const pybind11::dict& set,
                                             int frame, const std::string& baseDir,
                                             const std::string& ocio);

    pybind11::dict info() const;  // the record of `mirage info`
    const FrameRequest& request() const { return mRequest; }
    const std::shared_ptr<const ColorPipeline>& color() const { return mColor; }
    GridCache& grids() { return mGrids; }

    // The frame of `request` (this scene's, with a render's settings over it): the loaded one
    // when `key` (those settings) is the last render's, else loaded again. Thread-safe; call
    // without the GIL.
    std::shared_ptr<const LoadedFrame> frameFor(const FrameRequest& request,
                                                const std::string& key);

private:
    std::shared_ptr<MemoryGrids> mMemoryGrids;  // first: its files outlive every load
    FrameRequest mRequest;
    std::shared_ptr<const ColorPipeline> mColor;
    GridCache mGrids;
    std::shared_ptr<const LoadedFrame> mBase;  // the scene's own settings: info()
    std::mutex mMutex;
    std::shared_ptr<const LoadedFrame> mFrame;  // the last render's
    std::string mFrameKey;                      // its settings ("" = the scene's own)
};

// Loads `request` through the cache; a request for a complete output that --skip-existing
// skips cannot come from Python (it never sets it).
std::shared_ptr<const LoadedFrame> loadShared(const FrameRequest& request,
                                              const ColorPipeline& color, GridCache* grids);

}  // namespace mirage::python
