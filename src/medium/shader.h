// A volume shader: the description of a medium as a sum of components. Each component is a
// concentration field (a grid, scaled, or a constant) times cross-sections σa(λ), σs(λ)
// (1/m per unit concentration) with a phase lobe (Henyey–Greenstein or the sea-water lobe;
// non-linear sea-water kinds: ComponentKind); a shader may also emit
// as a blackbody at the temperature of a grid (Kirchhoff: a medium at temperature T emits
// σa·B(λ,T)). Shaders are written in TOML (shaders/*.toml) and parsed by scene/.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "medium/fluorescence.h"
#include "medium/phase.h"
#include "spectrum/spectrum.h"

namespace mirage {

// What a component is, as written in the shader (`kind = …`). The scene loader turns every
// kind into spectra below; medium/component.h turns it into the law of its concentration
// (ComponentModel::make), which decides everything the medium does with it.
//  - Linear: σ = C · σ_c(λ), the cross-section model of smoke and fog.
//  - Water: pure sea water, σa = a_w(λ) (Pope & Fry 1997), σs = b_w(λ) (Morel 1974), water lobe.
//  - Cdom: dissolved organic matter, σa = a_y(440) · exp(−S(λ − 440)), C = a_y(440) in 1/m.
//  - Chlorophyll: phytoplankton at C mg/m³, σa = A(λ) C^(1−B(λ)) (Bricaud et al. 1995) and
//    σs = b_p(λ) = 0.30 C^0.62 (550/λ) (Gordon & Morel 1983, Morel 1988), HG g = 0.924.
enum class ComponentKind { Linear, Water, Cdom, Chlorophyll };

struct MediumComponent {
    std::string name;
    std::string grid;          // grid slot the component reads; "" = homogeneous
    float concentration = 1;   // scale applied to grid values, or the constant value
    Spectrum sigmaA, sigmaS;   // 1/m per unit concentration (Chlorophyll: per unit C^exponent)
    float g = 0;               // HG asymmetry (Schlick: the g it imitates; DoubleHG: lobe 1)
    ComponentKind kind = ComponentKind::Linear;
    PhaseKind phase = PhaseKind::HenyeyGreenstein;
    float g2 = 0;              // DoubleHG: the second lobe's asymmetry
    float phaseWeight = 1;     // DoubleHG: the first lobe's weight w (medium/phase.h)
    // Chlorophyll only: σa = sigmaA(λ) · C^sigmaAExponent(λ), σs = sigmaS(λ) · C^sigmaSExponent,
    // with C = concentration × density scale × grid value. Both exponents are ≥ 0 (1 − B ∈
    // [0.62, 1.02] for Bricaud's B), so σ grows with C and the majorant bounds it at the
    // largest C of a cell.
    Spectrum sigmaAExponent{1.f};
    float sigmaSExponent = 1;
    // Cdom only: the chlorophyll component whose concentration sets a_y(440), Case-1 water
    // (medium/ocean_components.h, applyCase1Cdom); "" = a_y(440) is `concentration` (Case 2).
    std::string covariesWith;

    // Fluorescence (Gutierrez et al. 2005): a photon absorbed by this component is re-emitted
    // with probability Γ (a quantum yield: photons out per photon absorbed), isotropically, at a
    // wavelength drawn from the Gaussian η(λ) of the given peak and FWHM, or from the
    // excitation–emission matrix, restricted to λ ≥ λ_absorbed (Stokes shift) unless antiStokes.
    float quantumEfficiency = 0;  // Γ, 0..1
    float emissionPeakNm = 685;   // chlorophyll a (Gutierrez et al. 2005; field data 683–687 nm)
    float emissionFwhmNm = 25;
    // η as an excitation–emission matrix instead of the band (medium/fluorescence.h); null:
    // the band.
    std::shared_ptr<const EmissionMatrix> emissionMatrix;
    bool antiStokes = false;
    bool fluorescent() const { return quantumEfficiency > 0.f; }
};

struct EmissionSpec {
    std::string temperatureGrid;  // grid slot holding temperature
    float temperatureScale = 1;   // K per grid unit
    float temperatureOffset = 0;  // K added after scaling
    // Multiplies Planck radiance. 1 is physical; artists raise or lower it like an exposure
    // (intensity = 2^stops) without changing the colour, which the temperature alone sets.
    float intensity = 1;
    float minTemperature = 500;   // K; below this B(λ,T) is negligible in the visible (< 1e-9 of
                                  // its 1500 K value), so cooler voxels skip the Planck work
};

struct ShaderDesc {
    std::string name;
    std::string source;  // file it came from (for messages)
    std::vector<MediumComponent> components;
    std::optional<EmissionSpec> emission;
    // An OpenVDB AX snippet over the shader's grid slots (`expression`), run on every volume's
    // grids before they become NanoVDB (volume/grid_expression.h); "" = none.
    std::string expression;
    FileLoc expressionLoc;  // where it is written, for error messages

    // Grid slots the shader reads, in a stable order.
    std::vector<std::string> gridSlots() const;
    // True when some σ varies with wavelength.
    bool spectralCoefficients() const;
    // True when some component re-emits absorbed light at another wavelength.
    bool fluorescent() const;
};

}  // namespace mirage
