// A volume shader: the description of a medium as a sum of components. Each component is a
// concentration field (a grid, scaled, or a constant) times cross-sections σa(λ), σs(λ)
// (1/m per unit concentration) with a Henyey–Greenstein phase function; a shader may also emit
// as a blackbody at the temperature of a grid (Kirchhoff: a medium at temperature T emits
// σa·B(λ,T)). Shaders are written in TOML (shaders/*.toml) and parsed by scene/.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "spectrum/spectrum.h"

namespace mirage {

struct MediumComponent {
    std::string name;
    std::string grid;          // grid slot the component reads; "" = homogeneous
    float concentration = 1;   // scale applied to grid values, or the constant value
    Spectrum sigmaA, sigmaS;   // 1/m per unit concentration
    float g = 0;               // HG asymmetry
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

    // Grid slots the shader reads, in a stable order.
    std::vector<std::string> gridSlots() const;
    // True when some σ varies with wavelength.
    bool spectralCoefficients() const;
};

}  // namespace mirage
