#include "scene/shader_loader.h"

#include <cstdlib>
#include <utility>
#include <filesystem>

#include "core/path_check.h"
#include "core/text.h"
#include "medium/ocean_components.h"
#include "medium/rayleigh_particles.h"
#include "scene/emission_matrix_loader.h"
#include "spectrum/ocean_spectra.h"

namespace mirage {

namespace fs = std::filesystem;

std::vector<std::string> builtinShaderNames() {
    std::vector<std::string> names;
    for (const auto& [name, text] : builtinShaders()) names.push_back(name);
    return names;
}

Spectrum readCoefficientSpectrum(const TableReader& t, const std::string& key, float def) {
    const toml::node* n = t.node(key);
    if (!n) return Spectrum(def);
    if (n->is_number()) {
        double v = t.getNumber(key, def, 0.0, 1e12);
        return Spectrum(float(v));
    }
    if (n->is_array()) {
        auto v = t.getNumbers(key, 3, 3);
        for (double c : v)
            if (c < 0) t.fail(key, "RGB values must be ≥ 0");
        if (v[0] == v[1] && v[1] == v[2]) return Spectrum(float(v[0]));  // grey stays constant
        // The basis has peak 1 per channel; scale so the largest channel is preserved.
        double m = std::max({v[0], v[1], v[2]});
        Spectrum s = rgbReflectanceSpectrum(Vec3(float(v[0] / m), float(v[1] / m), float(v[2] / m)));
        return s.scaled(float(m));
    }
    if (n->is_table()) {
        TableReader st = *t.optionalTable(key);
        auto lambda = st.getNumbers("wavelengths", 2, 10000);
        auto values = st.getNumbers("values", 2, 10000);
        st.finish();
        if (lambda.size() != values.size())
            st.fail("values", "expected as many values as wavelengths (" +
                                  std::to_string(lambda.size()) + ")");
        for (size_t i = 1; i < lambda.size(); ++i)
            if (!(lambda[i] > lambda[i - 1])) st.fail("wavelengths", "must increase strictly");
        for (double v : values)
            if (v < 0) st.fail("values", "must be ≥ 0");
        return Spectrum::fromTable(std::vector<float>(lambda.begin(), lambda.end()),
                                   std::vector<float>(values.begin(), values.end()));
    }
    t.fail(key, "expected a number, an [r, g, b] array or a {wavelengths, values} table");
}

namespace {

// A linear component's phase function (medium/phase.h) and its parameters; a parameter the
// chosen lobe does not take is left unread, so that finish() reports it.
void readPhase(const TableReader& c, MediumComponent* mc) {
    static const std::pair<const char*, PhaseKind> kinds[] = {
        {"hg", PhaseKind::HenyeyGreenstein}, {"water", PhaseKind::Water},
        {"schlick", PhaseKind::Schlick},     {"rayleigh", PhaseKind::Rayleigh},
        {"mie_hazy", PhaseKind::MieHazy},    {"mie_murky", PhaseKind::MieMurky},
        {"double_hg", PhaseKind::DoubleHG}};
    const std::string phase = c.getString("phase", "hg");
    std::string names;
    bool found = false;
    for (const auto& k : kinds) {
        names += std::string(names.empty() ? "" : ", ") + "\"" + k.first + "\"";
        if (phase == k.first) {
            mc->phase = k.second;
            found = true;
        }
    }
    if (!found) c.fail("phase", "expected one of " + names);
    switch (mc->phase) {
        case PhaseKind::HenyeyGreenstein:
        case PhaseKind::Schlick: mc->g = float(c.getNumber("g", 0.0, -1.0, 1.0)); break;
        case PhaseKind::DoubleHG:
            mc->g = float(c.getNumber("g", 0.0, -1.0, 1.0));
            mc->g2 = float(c.getNumber("g2", 0.0, -1.0, 1.0));
            mc->phaseWeight = float(c.getNumber("lobe_weight", 0.5, 0.0, 1.0));
            break;
        default: break;
    }
}

// One [[component]]. Its kind (shader.h) decides which keys it takes: a linear component
// gives its cross-sections, the sea-water kinds take theirs from the published laws
// (medium/ocean_components.h), so sigma_a / sigma_s there are reported as unexpected keys.
MediumComponent readComponent(const TableReader& c, size_t index) {
    MediumComponent mc;
    mc.name = c.getString("name", "component" + std::to_string(index));
    mc.grid = c.getString("grid", "");
    mc.concentration = float(c.getNumber("concentration", 1.0, 0.0, 1e12));
    std::string kind = c.getString("kind", "linear");
    if (kind == "linear") {
        mc.sigmaA = readCoefficientSpectrum(c, "sigma_a", 0.f);
        mc.sigmaS = readCoefficientSpectrum(c, "sigma_s", 0.f);
        readPhase(c, &mc);
    } else if (kind == "water") {
        makeWater(&mc);
    } else if (kind == "cdom") {
        makeCdom(&mc, float(c.getNumber("slope", ocean::kCdomSlope, 0.0, 0.1)));
        mc.covariesWith = c.getString("covaries_with", "");
        if (!mc.covariesWith.empty() && c.has("concentration"))
            c.fail("covaries_with",
                   "a cdom component takes a_y(440) either from its chlorophyll "
                   "(covaries_with, Case-1 water) or from 'concentration', not both");
    } else if (kind == "chlorophyll") {
        makeChlorophyll(&mc, float(c.getNumber("g", kParticleG, -1.0, 1.0)));
    } else if (kind == "rayleigh") {
        const double diameter = c.getNumber("diameter_nm", 1.0, 1e-3, 100.0);
        const double particleIndex = c.getNumber("particle_index", 1.33, 1.0, 10.0);
        const double density = c.getNumber("number_density");
        if (!(density >= 0 && density <= 1e35))
            c.fail("number_density", "expected particles per m³ within [0, 1e35]");
        makeRayleighParticles(&mc, diameter, particleIndex, density);
        if (!(mc.sigmaS.maxValue() < 1e12f))
            c.fail("number_density", "σs of these particles exceeds 1e12 1/m; expected fewer");
    } else {
        c.fail("kind", "expected \"linear\", \"water\", \"cdom\", \"chlorophyll\" or \"rayleigh\"");
    }
    mc.quantumEfficiency = float(c.getNumber("quantum_efficiency", 0.0, 0.0, 1.0));
    mc.emissionPeakNm = float(c.getNumber("emission_peak_nm", 685.0, kLambdaMin, kLambdaMax));
    mc.emissionFwhmNm = float(c.getNumber("emission_fwhm_nm", 25.0, 1.0, 500.0));
    mc.emissionMatrix = readEmissionMatrix(c, "emission_matrix");
    if (mc.emissionMatrix && (c.has("emission_peak_nm") || c.has("emission_fwhm_nm")))
        c.fail("emission_matrix",
               "a component re-emits by its band (emission_peak_nm, "
               "emission_fwhm_nm) or by its emission_matrix, not both");
    mc.antiStokes = c.getBool("anti_stokes", false);
    c.finish();
    return mc;
}

}  // namespace

ShaderDesc parseShader(const toml::table& doc, const std::string& file) {
    TableReader top(doc, file, "");
    ShaderDesc s;
    s.source = file;
    s.name = top.getString("name", fs::path(file).stem().string());
    top.getString("description", "");
    s.expression = top.getString("expression", "");
    s.expressionLoc = top.loc("expression");
    auto comps = top.tables("component");
    if (comps.empty())
        throw MirageError(top.tableLoc(), "shader '" + s.name +
                                              "': expected at least one [[component]] table");
    for (const auto& c : comps) s.components.push_back(readComponent(c, s.components.size()));
    if (auto e = top.optionalTable("emission")) {
        EmissionSpec es;
        es.temperatureGrid = e->getString("temperature");
        es.temperatureScale = float(e->getNumber("temperature_scale", 1.0, 0.0, 1e9));
        es.temperatureOffset = float(e->getNumber("temperature_offset", 0.0, -1e9, 1e9));
        es.intensity = float(e->getNumber("intensity", 1.0, 0.0, 1e12));
        es.minTemperature = float(e->getNumber("min_temperature", 500.0, 0.0, 1e9));
        e->finish();
        s.emission = es;
    }
    top.finish();
    return s;
}

ShaderDesc loadShader(const std::string& nameOrPath, const std::string& sceneDir) {
    auto fromFile = [](const fs::path& p) { return parseShader(parseTomlFile(p.string()), p.string()); };
    bool looksLikePath = nameOrPath.find('/') != std::string::npos ||
                         fs::path(nameOrPath).extension() == ".toml";
    if (looksLikePath) {
        fs::path p(nameOrPath);
        if (p.is_relative() && !sceneDir.empty()) p = fs::path(sceneDir) / p;
        if (const std::string problem = pathProblem(p); !problem.empty())
            throw MirageError("shader file " + problem + ": " + p.string());
        return fromFile(p);
    }
    std::vector<fs::path> candidates;
    // No folder (a bare VDB has no scene): only MIRAGE_SHADER_PATH and the built-ins. A scene in
    // the working folder passes "." (scene_loader.cpp).
    if (!sceneDir.empty()) {
        candidates.push_back(fs::path(sceneDir) / (nameOrPath + ".toml"));
        candidates.push_back(fs::path(sceneDir) / "shaders" / (nameOrPath + ".toml"));
    }
    if (const char* env = std::getenv("MIRAGE_SHADER_PATH"))
        candidates.push_back(fs::path(env) / (nameOrPath + ".toml"));
    for (const auto& c : candidates)
        if (pathProblem(c).empty()) return fromFile(c);
    for (const auto& [name, text] : builtinShaders())
        if (name == nameOrPath)
            return parseShader(parseTomlText(text, "<built-in shader " + name + ">"),
                               "<built-in shader " + name + ">");
    throw MirageError("unknown shader '" + nameOrPath + "': not a file next to the scene, and "
                      "not a built-in shader (" + joinList(builtinShaderNames()) + ")");
}

}  // namespace mirage
