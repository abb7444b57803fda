#include "render/integrator.h"

#include "core/error.h"

namespace mirage {

std::vector<std::string> integratorNames() { return {"single", "volpath"}; }

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth) {
    if (name == "single") return makeSingleScatterIntegrator();
    if (name == "volpath") return makeVolPathIntegrator(maxDepth);
    std::string list;
    for (const auto& n : integratorNames()) list += (list.empty() ? "" : ", ") + n;
    throw MirageError("unknown integrator '" + name + "'; expected one of: " + list);
}

}  // namespace mirage
