// `emission_matrix` → EmissionMatrix (emission_matrix_loader.h says what is accepted).
#include "scene/emission_matrix_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/path_check.h"
#include "core/spectral.h"

namespace mirage {

namespace {

namespace fs = std::filesystem;

// The matrix's numbers before they become spectra, and the one check of them.
struct MatrixTable {
    std::vector<double> excitation, emission;
    std::vector<std::vector<double>> values;
};

// The first problem of a table, or "".
std::string tableProblem(const MatrixTable& m) {
    auto increasing = [](const std::vector<double>& v) {
        for (size_t i = 1; i < v.size(); ++i)
            if (!(v[i] > v[i - 1])) return false;
        return true;
    };
    if (m.excitation.empty()) return "expected at least one excitation wavelength";
    if (m.emission.size() < 2) return "expected at least two emission wavelengths";
    if (!increasing(m.excitation)) return "excitation wavelengths must increase strictly";
    if (!increasing(m.emission)) return "emission wavelengths must increase strictly";
    if (m.values.size() != m.excitation.size())
        return "expected one row per excitation wavelength (" +
               std::to_string(m.excitation.size()) + "), got " + std::to_string(m.values.size());
    for (size_t r = 0; r < m.values.size(); ++r) {
        const std::string row = "row " + std::to_string(r + 1) + " (excitation " +
                                std::to_string(int(m.excitation[r])) + " nm)";
        if (m.values[r].size() != m.emission.size())
            return row + " has " + std::to_string(m.values[r].size()) +
                   " values; expected one per emission wavelength (" +
                   std::to_string(m.emission.size()) + ")";
        for (double v : m.values[r])
            if (!(std::isfinite(v) && v >= 0)) return row + " has a value that is not finite ≥ 0";
    }
    return "";
}

// A row as a spectrum: linear between its emission wavelengths and 0 outside them (a scan says
// nothing of light it did not measure; Spectrum::fromTable would hold its end values instead).
Spectrum rowSpectrum(const std::vector<double>& emission, const std::vector<double>& row) {
    std::vector<float> dense(Spectrum::kDenseSamples, 0.f);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        const double l = kLambdaMin + float(i);
        if (l < emission.front() || l > emission.back()) continue;
        size_t k = size_t(std::upper_bound(emission.begin(), emission.end(), l) - emission.begin());
        k = std::min(k, emission.size() - 1);
        const double t = (l - emission[k - 1]) / (emission[k] - emission[k - 1]);
        dense[size_t(i)] = float((1 - t) * row[k - 1] + t * row[k]);
    }
    return Spectrum::fromDense(std::move(dense));
}

// The rows as spectra; a row without emission within 360–830 nm is a problem too.
std::shared_ptr<const EmissionMatrix> toMatrix(const MatrixTable& m, std::string* problem) {
    auto out = std::make_shared<EmissionMatrix>();
    for (size_t r = 0; r < m.values.size(); ++r) {
        Spectrum row = rowSpectrum(m.emission, m.values[r]);
        if (!(row.maxValue() > 0.f)) {
            *problem = "row " + std::to_string(r + 1) + " emits nothing within 360–830 nm";
            return nullptr;
        }
        out->excitationNm.push_back(float(m.excitation[r]));
        out->rows.push_back(std::move(row));
    }
    return out;
}

// A number from a CSV cell, the whole cell.
bool parseCell(const std::string& cell, double* v) {
    const char* begin = cell.c_str();
    char* end = nullptr;
    *v = std::strtod(begin, &end);
    while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
    return end != begin && *end == '\0';
}

// The CSV's cells, line by line (blank and '#' lines skipped), with their line numbers.
MatrixTable readCsv(const fs::path& file, const TableReader& c, const std::string& key) {
    if (const std::string problem = pathProblem(file); !problem.empty())
        c.fail(key, "the emission matrix file " + problem + ": " + file.string());
    std::ifstream in(file);
    MatrixTable m;
    std::string line;
    bool header = true;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
        std::stringstream cells(line);
        std::string cell;
        std::vector<double> numbers;
        for (int col = 0; std::getline(cells, cell, ','); ++col) {
            if (header && col == 0) continue;  // the label
            double v;
            if (!parseCell(cell, &v))
                throw MirageError(file.string() + ":" + std::to_string(lineNo) + ": " + key +
                                  ": expected a number in column " + std::to_string(col + 1) +
                                  ", got '" + cell + "'");
            numbers.push_back(v);
        }
        if (header) {
            m.emission = numbers;
        } else if (!numbers.empty()) {
            m.excitation.push_back(numbers.front());
            m.values.emplace_back(numbers.begin() + 1, numbers.end());
        }
        header = false;
    }
    return m;
}

// The inline form: { excitation, emission, values }.
MatrixTable readInline(const TableReader& t) {
    MatrixTable m;
    m.excitation = t.getNumbers("excitation", 1, 100000);
    m.emission = t.getNumbers("emission", 2, 100000);
    const toml::node* values = t.node("values");
    const toml::array* rows = values ? values->as_array() : nullptr;
    if (!rows) t.fail("values", "expected an array of rows, one per excitation wavelength");
    for (const toml::node& row : *rows) {
        const toml::array* cells = row.as_array();
        if (!cells) t.fail("values", "expected every row to be an array of numbers");
        std::vector<double> r;
        for (const toml::node& v : *cells) {
            const std::optional<double> x = v.value<double>();
            if (!x) t.fail("values", "expected every row to be an array of numbers");
            r.push_back(*x);
        }
        m.values.push_back(std::move(r));
    }
    t.finish();
    return m;
}

}  // namespace

std::shared_ptr<const EmissionMatrix> readEmissionMatrix(const TableReader& c,
                                                         const std::string& key) {
    const toml::node* n = c.node(key);
    if (!n) return nullptr;
    MatrixTable m;
    std::string where;
    if (n->is_string()) {
        fs::path file(c.getString(key));
        if (file.is_relative()) file = fs::path(c.file()).parent_path() / file;
        m = readCsv(file, c, key);
        where = " in " + file.string();
    } else if (n->is_table()) {
        m = readInline(*c.optionalTable(key));
    } else {
        c.fail(key, "expected a CSV file name or { excitation, emission, values }");
    }
    std::string problem = tableProblem(m);
    std::shared_ptr<const EmissionMatrix> matrix =
        problem.empty() ? toMatrix(m, &problem) : nullptr;
    if (!problem.empty())
        c.fail(key, "malformed excitation–emission matrix" + where + ": " + problem);
    return matrix;
}

}  // namespace mirage
