// A fluorescent component's `emission_matrix` (medium/fluorescence.h): η(λi → λ) tabulated as
// an excitation–emission matrix, written either inline,
//   emission_matrix = { excitation = [350, 400], emission = [400, 450, 500],
//                       values = [[0.2, 1.0, 0.4], [0.0, 1.0, 0.6]] }
// (one row per excitation wavelength, one value per emission wavelength, nm), or as a CSV file
// next to the shader file, `emission_matrix = "cdom_eem.csv"`: its first line a label and the
// emission wavelengths, each next line an excitation wavelength and its row (the layout
// fluorometers export); blank lines and lines starting with '#' are skipped. Wavelengths must
// increase strictly, values be finite and ≥ 0, and every row have some emission within
// 360–830 nm. A malformed table is refused with one line naming the key (and the file and
// line of a CSV).
#pragma once

#include <memory>

#include "medium/fluorescence.h"
#include "scene/toml_reader.h"

namespace mirage {

std::shared_ptr<const EmissionMatrix> readEmissionMatrix(const TableReader& component,
                                                         const std::string& key);

}  // namespace mirage
