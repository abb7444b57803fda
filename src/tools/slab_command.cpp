// `mirage slab`: total reflectance and transmittance of a plane-parallel slab by photon tracing,
// the instrument that checks the photon pass's transport against published adding-doubling
// values (Prahl's iadpython tests; ../shared/data/README.md).
//
//   mirage slab --albedo A --tau T [--g G] [--n N] [--n-outside M] [--incidence normal|diffuse]
//               [--photons P] [--seed S] [--max-events E] [--threads K] [--json] [-q]
//   mirage slab --shader FILE [--set NAME=C …] [--thickness METRES] [--spectral] [same options]
//
// With --shader the slab is that shader made homogeneous: every component's grid is dropped
// and its concentration is the constant C (`--set chlorophyll=5` sets the component named
// chlorophyll to 5 mg/m³; `--set NAME.quantum_efficiency=Γ` its fluorescence). --thickness is in
// metres; without it the slab is a deep water column (1e5 m: optically infinite for every
// sea water at every visible wavelength). --spectral draws each photon's wavelength uniformly
// over 380–780 nm (a spectrally flat, normally incident source) and adds, per 5 nm bin of the
// wavelength the light *leaves* with, `reflectance` and `transmittance` (power out in the bin
// over power in the bin; fluorescence moves power from the blue into its band), next to the
// `wavelength_nm` bin centres, and `fluorescence`: `absorbed` and `reemitted` (events per
// incident photon) and `mean_shift_nm` (mean λo − λi of the re-emissions). Without --spectral a
// shader slab is measured at 550 nm.
//
// The slab: a homogeneous medium of single-scattering albedo A and optical thickness T with a
// Henyey–Greenstein phase function (g = G) and refractive index N, between two smooth
// interfaces with a medium of index M (both faces alike). Light arrives on the top face
// either collimated along the normal, or diffuse (Lambertian: directions cosine-weighted).
//
// Output (JSON with --json, else a table), each a fraction of the incident power with its
// sample standard error (`_stderr`; the photons are equal, so it is the binomial one):
//   reflectance                total reflected: specular at entry + everything leaving the top
//   transmittance              total transmitted: unscattered + diffuse, leaving the bottom
//   reflectance_diffuse        reflected after at least one scattering event
//   reflectance_specular       reflected without scattering (entry + internal reflections)
//   transmittance_unscattered  transmitted without scattering (Beer–Lambert, with reflections)
//   absorbed, capped           absorbed; stopped by --max-events (a bias: should be ~0)
//   photons, seconds
//
// Geometry. The slab is 1 m thick with σt = T/m. It is invariant under translations
// parallel to its faces, so a photon's lateral position is irrelevant: every flight starts at
// x = y = 0, and the medium is a box of ±1e6 m laterally only so that a single flight stays
// inside it. A flight that still leaves through a side (a grazing flight longer than 1e6 m,
// |cos θ| < 1e-6) is continued from x = y = 0 at the height where it left: free paths are
// memoryless, so this is exact. T = inf (or T ≥ 1e6) is simulated as T = 1e6: for A < 1 the
// light reaching depth τ falls like exp(−τ √(3(1 − A)(1 − A g))) (diffusion theory), and for
// A = 1 a walk ~1e6 events long reaches ~1e3 mean free paths deep, so no photon meets the
// bottom face. A conservative semi-infinite walk returns with certainty but after a
// heavy-tailed number of events (P(n > N) ∝ N^(−1/2)), so --max-events bounds it and the
// capped fraction is reported.
//
// The walk inside is the photon pass's (photon/photon_walk.h): delta tracking, albedo
// roulette, phase sampling. The faces are handled here: at each crossing the unpolarised
// Fresnel reflectance of a smooth dielectric interface decides by roulette between specular
// reflection and Snell refraction, with total internal reflection past the critical angle.
// Parallel over blocks of photons, each photon's random numbers keyed by (seed, index), the
// tallies summed in block order: the output depends on the seed only, not on the threads.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/clock.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/text.h"
#include "core/thread_limit.h"
#include "geometry/material.h"
#include "medium/ocean_components.h"
#include "photon/photon_blocks.h"
#include "photon/photon_walk.h"
#include "scene/shader_loader.h"
#include "tools/json_report.h"
#include "tools/tools.h"

namespace mirage {

namespace {

constexpr double kInfiniteTau = 1e6;  // T ≥ this is "semi-infinite" (see the header)
constexpr float kThickness = 1.f;     // m
constexpr float kHalfWidth = 1e6f;    // m, lateral half-size of the medium box

constexpr float kLambdaNm = 550.f;  // any for a grey slab; a shader slab's single wavelength
constexpr double kDeepColumn = 1e5;  // m: the default thickness of a shader slab
// --spectral: 80 bins of 5 nm over 380–780 nm.
constexpr float kSpectralMinNm = 380.f, kBinNm = 5.f;
constexpr int kSpectralBins = 80;

// Reflectance of a slab face from index n1 to n2 at incidence cosine cosI: the renderer's own
// dielectric Fresnel term (geometry/material.h), so the slab's faces are a scene's glass.
// *cosT is the refracted cosine (Snell), 0 past the critical angle, where R = 1.
double fresnel(double cosI, double n1, double n2, double* cosT) {
    const double sinT2 = (n1 / n2) * (n1 / n2) * std::max(0.0, 1.0 - cosI * cosI);
    *cosT = sinT2 >= 1.0 ? 0.0 : std::sqrt(1.0 - sinT2);
    if (n1 == n2) return 0.0;
    return double(fresnelDielectric(float(cosI), float(n2 / n1)));
}

enum Outcome {
    kReflSpecular,
    kReflDiffuse,
    kTransUnscattered,
    kTransDiffuse,
    kAbsorbed,
    kCapped,
    kOutcomes
};
const char* const kOutcomeNames[kOutcomes] = {"reflectance_specular",
                                              "reflectance_diffuse",
                                              "transmittance_unscattered",
                                              "transmittance_diffuse",
                                              "absorbed",
                                              "capped"};

// Σw and Σw² of each outcome, w the photon's final power relative to its initial power (1
// for a single HG lobe and no fluorescence; λi/λo per re-emission). With --spectral, Σw per
// bin of the leaving wavelength, for the reflected and the transmitted light.
struct Tally {
    double sum[kOutcomes] = {}, sum2[kOutcomes] = {};
    std::vector<double> reflected, transmitted;
    uint64_t absorptions = 0, reemissions = 0;  // absorption events, Γ re-emissions among them
    double shiftSum = 0;                        // Σ (λo − λi) over re-emissions, nm
    void add(Outcome o, double w) {
        sum[o] += w;
        sum2[o] += w * w;
    }
    void addSpectral(Outcome o, double w, float lambdaNm) {
        if (reflected.empty()) return;
        int b = int(std::floor((lambdaNm - kSpectralMinNm) / kBinNm));
        if (b < 0 || b >= kSpectralBins) return;
        if (o == kReflSpecular || o == kReflDiffuse) reflected[size_t(b)] += w;
        if (o == kTransUnscattered || o == kTransDiffuse) transmitted[size_t(b)] += w;
    }
    void add(const Tally& t) {
        for (int i = 0; i < kOutcomes; ++i) {
            sum[i] += t.sum[i];
            sum2[i] += t.sum2[i];
        }
        for (size_t b = 0; b < reflected.size() && b < t.reflected.size(); ++b) {
            reflected[b] += t.reflected[b];
            transmitted[b] += t.transmitted[b];
        }
        absorptions += t.absorptions;
        reemissions += t.reemissions;
        shiftSum += t.shiftSum;
    }
};

struct Slab {
    double nIn, nOut;
    bool diffuse;
    int64_t maxEvents;
    float thickness;  // m
    bool spectral;
};

// One photon, from the top face to its outcome.
void tracePhoton(const Slab& slab, uint64_t index, uint64_t seed, PhotonWalk& walk, Tally* t) {
    Sampler s(seed, index, 0);
    // The photon's wavelength: uniform over the spectral range (a flat source), else fixed.
    // Drawn from its own stream so that the grey slab's numbers are those it always had.
    float lambda = kLambdaNm;
    if (slab.spectral) {
        Sampler ls(seed, index, 1);
        lambda = kSpectralMinNm + kBinNm * kSpectralBins * ls.get1D();
    }
    if (walk.wavelength() != lambda) walk.setWavelength(lambda);
    auto score = [&](Outcome o, double w) {
        t->add(o, w);
        t->addSpectral(o, w, walk.wavelength());
    };
    // Incident direction (travelling +z into the slab, whose top face is z = 0).
    Vec3 d(0.f, 0.f, 1.f);
    if (slab.diffuse) {
        float u1 = s.get1D(), u2 = s.get1D();
        d = sampleCosineHemispherePolar(u1, u2);
    }
    double cosT;
    if (s.get1D() < fresnel(d.z, slab.nOut, slab.nIn, &cosT)) {
        score(kReflSpecular, 1.0);
        return;
    }
    // Snell: the tangential component scales by n_out/n_in, the normal one becomes cosT.
    float eta = float(slab.nOut / slab.nIn);
    d = normalize(Vec3(d.x * eta, d.y * eta, float(cosT)));
    Vec3 p(0.f, 0.f, 0.f);
    double w = 1.0;
    bool scattered = false;

    for (int64_t events = 0;;) {
        FlightEvent ev = walk.fly(Ray{p, d, kInfinity}, kInfinity, s);
        if (ev.end == FlightEnd::Absorbed) {
            ++t->absorptions;
            score(kAbsorbed, w);
            return;
        }
        if (ev.end == FlightEnd::Reemitted) {
            // Absorbed, then re-emitted at the walk's new wavelength (λi/λo of the power).
            ++t->absorptions;
            ++t->reemissions;
            t->shiftSum += double(ev.lambdaOut) - double(ev.lambdaIn);
        }
        if (ev.end == FlightEnd::Scattered || ev.end == FlightEnd::Reemitted) {
            scattered = true;
            w *= ev.weight;
            p = Vec3(0.f, 0.f, clamp(ev.p.z, 0.f, slab.thickness));
            d = ev.wo;
        } else {
            // Left the box: through a face, or (grazing) through a side, whichever is nearer.
            float tFace = d.z > 0.f ? (slab.thickness - p.z) / d.z
                                    : (d.z < 0.f ? -p.z / d.z : kInfinity);
            float tSide = std::min(std::abs(d.x) > 0.f ? kHalfWidth / std::abs(d.x) : kInfinity,
                                   std::abs(d.y) > 0.f ? kHalfWidth / std::abs(d.y) : kInfinity);
            if (tSide < tFace) {
                p = Vec3(0.f, 0.f, clamp(p.z + d.z * tSide, 0.f, slab.thickness));
                continue;  // memoryless: the flight goes on from the same height
            }
            bool bottom = d.z > 0.f;
            if (s.get1D() >= fresnel(std::abs(d.z), slab.nIn, slab.nOut, &cosT)) {
                if (bottom)
                    score(scattered ? kTransDiffuse : kTransUnscattered, w);
                else
                    score(scattered ? kReflDiffuse : kReflSpecular, w);
                return;
            }
            // Specular (or total internal) reflection back into the slab.
            p = Vec3(0.f, 0.f, bottom ? slab.thickness : 0.f);
            d.z = -d.z;
        }
        if (++events >= slab.maxEvents) {
            score(kCapped, w);
            return;
        }
    }
}

// The medium of a --shader slab: the shader with every grid dropped (a slab is homogeneous),
// concentrations and quantum efficiencies set by --set NAME=C, NAME.concentration=C or
// NAME.quantum_efficiency=Γ.
ShaderDesc slabShader(const SlabOptions& o) {
    ShaderDesc shader = loadShader(o.shader, "");
    if (shader.emission)
        throw MirageError("slab: shader '" + shader.name +
                          "' emits (an [emission] table needs a temperature grid)");
    for (auto& c : shader.components) c.grid.clear();
    for (const std::string& kv : o.sets) {
        size_t eq = kv.find('=');
        if (eq == std::string::npos)
            throw MirageError("slab: --set expects NAME=value, got '" + kv + "'");
        std::string key = kv.substr(0, eq), field = "concentration";
        if (size_t dot = key.find('.'); dot != std::string::npos) {
            field = key.substr(dot + 1);
            key = key.substr(0, dot);
        }
        char* end = nullptr;
        double v = std::strtod(kv.c_str() + eq + 1, &end);
        if (end == kv.c_str() + eq + 1 || *end != '\0' || !std::isfinite(v) || v < 0.0)
            throw MirageError("slab: --set " + kv + ": expected a number ≥ 0");
        MediumComponent* c = nullptr;
        for (auto& comp : shader.components)
            if (comp.name == key) c = &comp;
        if (!c)
            throw MirageError("slab: --set " + kv + ": shader '" + shader.name +
                              "' has no component '" + key + "' (it has " +
                              joinList(shader.components,
                                       [](const MediumComponent& mc) { return mc.name; }) +
                              ")");
        if (field == "concentration") {
            c->concentration = float(v);
            c->covariesWith.clear();  // a stated a_y(440): Case-2 water
        } else if (field == "quantum_efficiency" && v <= 1.0) {
            c->quantumEfficiency = float(v);
        } else {
            throw MirageError("slab: --set " + kv +
                              ": expected NAME=C, NAME.concentration=C or "
                              "NAME.quantum_efficiency=Γ (0 to 1)");
        }
    }
    applyCase1Cdom(&shader);
    return shader;
}

void validate(const SlabOptions& o) {
    if (!o.shader.empty()) {
        if (o.thickness < 0.0 || !std::isfinite(o.thickness))
            throw MirageError("slab: --thickness must be a positive number of metres");
        if (o.photons == 0) throw MirageError("slab: --photons must be at least 1");
        return;
    }
    if (!o.sets.empty() || o.thickness > 0.0)
        throw MirageError("slab: --set and --thickness need --shader");
    if (o.albedo < 0.0 || o.tau == 0.0)
        throw MirageError("slab: give --albedo and --tau, or a --shader");
    if (!(o.tau > 0.0))
        throw MirageError("slab: --tau must be a positive optical thickness or inf (got " +
                          std::to_string(o.tau) + ")");
    if (!(o.albedo >= 0.0 && o.albedo <= 1.0))
        throw MirageError("slab: --albedo must be in [0, 1]");
    if (!(o.n > 0.0 && o.nOutside > 0.0) || !std::isfinite(o.n) || !std::isfinite(o.nOutside))
        throw MirageError("slab: refractive indices must be positive and finite");
    if (o.incidence != "normal" && o.incidence != "diffuse")
        throw MirageError("slab: --incidence must be normal or diffuse (got '" + o.incidence +
                          "')");
    if (o.photons == 0) throw MirageError("slab: --photons must be at least 1");
}

// The slab of the options: its medium (a shader made homogeneous, or one grey HG component
// of albedo A and optical thickness T over kThickness) and geometry.
struct SlabSetup {
    bool fromShader = false, infinite = false;
    float sigmaT = 0;     // 1/m, the grey slab's
    float thickness = 0;  // m
    ShaderDesc shader;
};

SlabSetup slabSetup(const SlabOptions& o) {
    SlabSetup s;
    s.fromShader = !o.shader.empty();
    s.infinite = s.fromShader ? !(o.thickness > 0.0) : o.tau >= kInfiniteTau;
    s.sigmaT = float(s.infinite ? kInfiniteTau : o.tau) / kThickness;
    if (s.fromShader) {
        s.shader = slabShader(o);
    } else {
        s.shader.name = "slab";
        s.shader.source = "mirage slab";
        MediumComponent c;
        c.name = "slab";
        c.sigmaA = Spectrum(s.sigmaT * float(1.0 - o.albedo));
        c.sigmaS = Spectrum(s.sigmaT * float(o.albedo));
        c.g = float(o.g);
        s.shader.components.push_back(c);
    }
    s.thickness = s.fromShader ? float(s.infinite ? kDeepColumn : o.thickness) : kThickness;
    return s;
}

Tally emptyTally(bool spectral) {
    Tally t;
    if (spectral) {
        t.reflected.assign(kSpectralBins, 0.0);
        t.transmitted.assign(kSpectralBins, 0.0);
    }
    return t;
}

// All photons in blocks of kBlockPhotons, in parallel; the blocks' tallies are added in block
// order, so the sums do not depend on the thread count.
Tally traceSlab(const Slab& slab, const Medium& medium, const SlabOptions& o) {
    const std::vector<const Medium*> media{&medium};
    std::vector<Tally> blockTally(photonBlockCount(o.photons), emptyTally(o.spectral));
    {
        Progress progress("slab", o.photons, "photons",
                          o.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
        forEachPhotonBlock(o.photons, media, progress, /*stopOnInterrupt=*/false,
                           [&](PhotonWalk& walk, uint64_t b, uint64_t first, uint64_t last) {
                               walk.setWavelength(kLambdaNm);
                               for (uint64_t i = first; i < last; ++i)
                                   tracePhoton(slab, i, o.seed, walk, &blockTally[b]);
                           });
    }
    Tally total = emptyTally(o.spectral);
    for (const Tally& t : blockTally) total.add(t);
    return total;
}

// A result with its standard error.
struct SlabRow {
    std::string name;
    std::pair<double, double> v;
};

// Mean and standard error of the per-photon score X (w for the photons with the outcome, 0
// for the others); exclusive outcomes add in both Σw and Σw².
std::vector<SlabRow> slabRows(const Tally& total, uint64_t photons) {
    const double n = double(photons);
    auto stat = [&](std::initializer_list<Outcome> outcomes) {
        double s = 0, s2 = 0;
        for (Outcome oc : outcomes) {
            s += total.sum[oc];
            s2 += total.sum2[oc];
        }
        double mean = s / n;
        return std::make_pair(mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / n));
    };
    std::vector<SlabRow> rows = {{"reflectance", stat({kReflSpecular, kReflDiffuse})},
                                 {"transmittance", stat({kTransUnscattered, kTransDiffuse})}};
    for (int i = 0; i < kOutcomes; ++i) rows.push_back({kOutcomeNames[i], stat({Outcome(i)})});
    return rows;
}

float binCentreNm(int b) { return kSpectralMinNm + kBinNm * (float(b) + 0.5f); }

// Per bin: the power leaving in it over the power arriving in it (n/80 photons of power 1).
double binFraction(const std::vector<double>& v, int b, uint64_t photons) {
    return v[size_t(b)] / (double(photons) / kSpectralBins);
}

double meanShiftNm(const Tally& total) {
    return total.reemissions ? total.shiftSum / double(total.reemissions) : 0.0;
}

void printSlabJson(const SlabOptions& o, const SlabSetup& s, const Tally& total,
                   double seconds) {
    const double n = double(o.photons);
    JsonReport j;
    if (s.fromShader) {
        j["shader"] = s.shader.name;
        j["thickness_m"] = jsonNumber(double(s.thickness), 9);
        j["thickness_infinite"] = s.infinite;
    } else {
        j["albedo"] = jsonNumber(o.albedo, 9);
        j["tau"] = jsonNumber(double(s.sigmaT * kThickness), 9);
        j["tau_infinite"] = s.infinite;
        j["g"] = jsonNumber(o.g, 9);
    }
    j["n"] = jsonNumber(o.n, 9);
    j["n_outside"] = jsonNumber(o.nOutside, 9);
    j["incidence"] = o.incidence;
    if (o.spectral) {
        JsonReport centres = JsonReport::array(), refl = JsonReport::array(),
                   trans = JsonReport::array();
        for (int b = 0; b < kSpectralBins; ++b) {
            centres.push_back(double(binCentreNm(b)));
            refl.push_back(jsonNumber(binFraction(total.reflected, b, o.photons), 6));
            trans.push_back(jsonNumber(binFraction(total.transmitted, b, o.photons), 6));
        }
        j["wavelength_nm"] = centres;
        j["reflectance"] = refl;
        j["transmittance"] = trans;
    }
    j["fluorescence"] = {{"absorbed", jsonNumber(double(total.absorptions) / n, 9)},
                         {"reemitted", jsonNumber(double(total.reemissions) / n, 9)},
                         {"mean_shift_nm", jsonNumber(meanShiftNm(total), 6)}};
    // With --spectral the keys `reflectance` and `transmittance` hold the per-bin arrays
    // (what ocean-colour users read); the totals then go by `_total`, so that every key
    // is unique and a JSON parser keeps both.
    for (const SlabRow& r : slabRows(total, o.photons)) {
        const bool isTotal = o.spectral && (r.name == "reflectance" || r.name == "transmittance");
        const std::string key = isTotal ? r.name + "_total" : r.name;
        j[key] = jsonNumber(r.v.first, 9);
        j[key + "_stderr"] = jsonNumber(r.v.second, 9);
    }
    j["photons"] = o.photons;
    j["seed"] = o.seed;
    j["seconds"] = jsonNumber(seconds, 6);
    std::fputs(formatJsonReport(j).c_str(), stdout);
}

void printSlabTable(const SlabOptions& o, const SlabSetup& s, const Medium& medium,
                    const Tally& total, double seconds) {
    const double n = double(o.photons);
    if (s.fromShader)
        std::printf("slab: shader '%s', thickness %s m, n %g (outside %g), %s incidence%s\n",
                    s.shader.name.c_str(),
                    s.infinite ? "inf" : std::to_string(s.thickness).c_str(), o.n, o.nOutside,
                    o.incidence.c_str(), o.spectral ? ", flat 380-780 nm source" : ", 550 nm");
    else
        std::printf("slab: albedo %g, tau %s, g %g, n %g (outside %g), %s incidence\n",
                    o.albedo, s.infinite ? "inf" : std::to_string(o.tau).c_str(), o.g, o.n,
                    o.nOutside, o.incidence.c_str());
    for (const SlabRow& r : slabRows(total, o.photons))
        std::printf("  %-26s %.6f ± %.6f\n", r.name.c_str(), r.v.first, r.v.second);
    if (total.absorptions > 0 && medium.fluorescent())
        std::printf("  fluorescence: %.6f absorbed, %.6f re-emitted per photon, mean shift "
                    "%.2f nm\n",
                    double(total.absorptions) / n, double(total.reemissions) / n,
                    meanShiftNm(total));
    if (o.spectral) {
        std::printf("  %-8s %-12s %-12s\n", "nm", "reflectance", "transmittance");
        for (int b = 0; b < kSpectralBins; ++b)
            std::printf("  %-8.1f %-12.6f %-12.6f\n", binCentreNm(b),
                        binFraction(total.reflected, b, o.photons),
                        binFraction(total.transmitted, b, o.photons));
    }
    std::printf("  %llu photons in %s (%.3g M photons/s)\n", (unsigned long long)o.photons,
                formatSeconds(seconds).c_str(), n / seconds * 1e-6);
}

}  // namespace

int runSlab(const SlabOptions& o) {
    validate(o);
    const auto threads = limitThreads(o.threads);

    const SlabSetup setup = slabSetup(o);
    Bounds3 box;
    box.lo = Vec3(-kHalfWidth, -kHalfWidth, 0.f);
    box.hi = Vec3(kHalfWidth, kHalfWidth, setup.thickness);
    const Medium medium(setup.shader, box, Transform(), 1.f);
    const Slab slab{o.n,         o.nOutside,      o.incidence == "diffuse",
                    o.maxEvents, setup.thickness, o.spectral};

    const auto start = Clock::now();
    const Tally total = traceSlab(slab, medium, o);
    const double seconds = secondsSince(start);
    if (o.json)
        printSlabJson(o, setup, total, seconds);
    else
        printSlabTable(o, setup, medium, total, seconds);
    return 0;
}

Command addSlabCommand(CLI::App& app) {
    auto o = std::make_shared<SlabOptions>();
    auto* slab = app.add_subcommand(
        "slab", "Reflectance and transmittance of a plane-parallel slab, by photon tracing");
    slab->add_option("--albedo", o->albedo, "Single-scattering albedo σs/σt (without --shader)")
        ->check(CLI::Range(0.0, 1.0));
    slab->add_option("--tau", o->tau,
                     "Optical thickness σt·d; inf for a semi-infinite slab (without --shader)");
    slab->add_option("--shader", o->shader,
                     "Shader (name or .toml) made homogeneous, instead of --albedo/--tau/--g");
    slab->add_option("--set", o->sets,
                     "With --shader: NAME=C sets a component's concentration (e.g. "
                     "chlorophyll=5), NAME.quantum_efficiency=Γ its fluorescence")
        ->take_all();
    slab->add_option("--thickness", o->thickness,
                     "With --shader: slab thickness in metres (default: a deep column)")
        ->check(CLI::Range(1e-9, 1e9));
    slab->add_flag("--spectral", o->spectral,
                   "Flat 380–780 nm source: reflectance, transmittance and fluorescence per 5 nm "
                   "bin (without it: 550 nm)");
    slab->add_option("--g", o->g, "Henyey–Greenstein asymmetry (default 0; without --shader)")
        ->check(CLI::Range(-0.9999, 0.9999));
    slab->add_option("--n", o->n, "Refractive index of the slab (default 1)")->check(CLI::Range(0.01, 100.0));
    slab->add_option("--n-outside", o->nOutside, "Refractive index around the slab (default 1)")
        ->check(CLI::Range(0.01, 100.0));
    slab->add_option("--incidence", o->incidence, "normal (collimated, the default) or diffuse "
                                                  "(Lambertian)")
        ->check(CLI::IsMember({"normal", "diffuse"}));
    slab->add_option("--photons", o->photons, "Photons to trace (default 1000000)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    slab->add_option("--seed", o->seed, "Random seed (default 0)");
    slab->add_option("--max-events", o->maxEvents,
                     "Cap on scatterings + internal reflections per photon (default 1000000; "
                     "capped photons are reported)")
        ->check(CLI::Range(int64_t(1), int64_t(1) << 40));
    slab->add_option("--threads", o->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    slab->add_flag("--json", o->json, "Print the result as JSON");
    slab->add_flag("-q,--quiet", o->quiet, "No progress output");
    return {slab, [o] { return runSlab(*o); }};
}

}  // namespace mirage
