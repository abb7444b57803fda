#include "scene/output_loader.h"

#include <algorithm>

#include "film/aov.h"
#include "film/cryptomatte.h"

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

void readCryptomatte(const TableReader& o, Scene* scene) {
    for (const std::string& kind : o.getStrings("cryptomatte")) {
        const std::string pass = cryptomattePass(kind);
        if (pass.empty())
            o.fail("cryptomatte", "unknown Cryptomatte '" + kind + "'; expected volume or shape");
        std::vector<std::string>& aovs = scene->settings.aovs;
        if (std::find(aovs.begin(), aovs.end(), pass) == aovs.end()) aovs.push_back(pass);
    }
}

std::string readObjectName(const TableReader& t, const std::string& fallback) {
    const std::string name = t.getString("name", fallback);
    if (!validCryptomatteName(name))
        t.fail("name", "'" + name +
                           "': an object's name takes letters, digits and _ - . / : (it is "
                           "what Cryptomatte calls it)");
    return name;
}

void checkAovs(const TableReader& top, const Scene& scene) {
    try {
        AovLayout(scene.settings.aovs, scene.render.lightGroupNames(), scene.render.cryptoObjects);
    } catch (const MirageError& e) {
        if (auto o = top.optionalTable("output"))
            o->fail(o->has("aovs") ? "aovs" : "cryptomatte", e.what());
        throw;
    }
}

}  // namespace mirage
