#include "scene/output_loader.h"

#include "film/aov.h"

namespace mirage {

// [output] deep and its tolerances (film/deep.h).
void readDeepSettings(const TableReader& o,
                      const std::function<std::string(const std::string&)>& resolve, Scene* scene) {
    DeepSettings& deep = scene->settings.deep;
    const std::string path = o.getString("deep", "");
    deep.path = path.empty() ? "" : resolve(path);
    if (!deep.path.empty() && deep.path == scene->output.path)
        o.fail("deep",
               "'" + path + "' is the beauty's path: give the deep image a name of its own");
    deep.alphaTolerance = float(o.getNumber("deep_alpha_tolerance", 0.02, 0.0, 1.0));
    deep.colorTolerance = float(o.getNumber("deep_color_tolerance", 0.02, 0.0, 1.0));
}

void checkAovs(const TableReader& top, const Scene& scene) {
    try {
        AovLayout(scene.settings.aovs, scene.render.lightGroupNames());
    } catch (const MirageError& e) {
        if (auto o = top.optionalTable("output")) o->fail("aovs", e.what());
        throw;
    }
}

}  // namespace mirage
