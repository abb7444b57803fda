#include "spectrum/ocean_spectra.h"

#include <cmath>
#include <vector>

namespace mirage::ocean {

namespace {

// Pure-water absorption a_w(λ), 1/m. 380–700 nm: Pope, R. M. & Fry, E. S., "Absorption spectrum
// (380–700 nm) of pure water. II. Integrating cavity measurements", Appl. Opt. 36, 8710–8723
// (1997), every second row of their 2.5 nm table. 350–370 nm and 710–800 nm: the rows that
// extend the table in ../shared/data/spectra (other sources, as that file says: Pope & Fry
// measured 380–700 nm only). Linear interpolation of this
// 5 nm table reproduces the 2.5 nm one within 4.8 % (worst at 397.5 nm, a shoulder; 1 % rms);
// a 10 nm step would leave 8.4 % (2.5 % rms).
constexpr TableRow kWaterAbsorption[] = {
    {350, 0.0204}, {360, 0.0156}, {370, 0.0114}, {380, 0.01137}, {385, 0.00941}, {390, 0.00851},
    {395, 0.00813}, {400, 0.00663}, {405, 0.0053}, {410, 0.00473}, {415, 0.00444}, {420, 0.00454},
    {425, 0.00478}, {430, 0.00495}, {435, 0.0053}, {440, 0.00635}, {445, 0.00751}, {450, 0.00922},
    {455, 0.00962}, {460, 0.00979}, {465, 0.01011}, {470, 0.0106}, {475, 0.0114}, {480, 0.0127},
    {485, 0.0136}, {490, 0.015}, {495, 0.0173}, {500, 0.0204}, {505, 0.0256}, {510, 0.0325},
    {515, 0.0396}, {520, 0.0409}, {525, 0.0417}, {530, 0.0434}, {535, 0.0452}, {540, 0.0474},
    {545, 0.0511}, {550, 0.0565}, {555, 0.0596}, {560, 0.0619}, {565, 0.0642}, {570, 0.0695},
    {575, 0.0772}, {580, 0.0896}, {585, 0.11}, {590, 0.1351}, {595, 0.1672}, {600, 0.2224},
    {605, 0.2577}, {610, 0.2644}, {615, 0.2678}, {620, 0.2755}, {625, 0.2834}, {630, 0.2916},
    {635, 0.3012}, {640, 0.3108}, {645, 0.325}, {650, 0.34}, {655, 0.371}, {660, 0.41},
    {665, 0.429}, {670, 0.439}, {675, 0.448}, {680, 0.465}, {685, 0.486}, {690, 0.516},
    {695, 0.559}, {700, 0.624}, {710, 0.827}, {720, 1.231}, {730, 1.799}, {740, 2.38}, {750, 2.47},
    {760, 2.55}, {770, 2.51}, {780, 2.36}, {790, 2.16}, {800, 2.07},
};

// Bricaud, A., Babin, M., Morel, A. & Claustre, H., "Variability in the chlorophyll-specific
// absorption coefficients of natural phytoplankton: analysis and parameterization", J. Geophys.
// Res. 100(C7), 13321–13332 (1995), Table 2: a*_ph = A·Chl^(−B), A in m²/mg. Every second row
// (8 nm) up to 664 nm, every row from 668 nm (the red chlorophyll-a peak at 675 nm, which is
// narrow and excites the 685 nm fluorescence). Linear interpolation reproduces the full table
// within 3.9 % in A (at 660 nm) and 0.0065 in B, 5.6 % in a_ph for Chl in 0.05–10 mg/m³.
constexpr TableRow kBricaud[] = {
    {400, 0.0263, 0.282}, {408, 0.0301, 0.282}, {416, 0.0342, 0.293}, {424, 0.0362, 0.313},
    {432, 0.0391, 0.318}, {440, 0.0403, 0.332}, {448, 0.0375, 0.360}, {456, 0.0354, 0.367},
    {464, 0.0343, 0.368}, {472, 0.0325, 0.371}, {480, 0.0301, 0.377}, {488, 0.0279, 0.369},
    {496, 0.0249, 0.341}, {504, 0.0209, 0.300}, {512, 0.0171, 0.249}, {520, 0.0143, 0.196},
    {528, 0.0121, 0.151}, {536, 0.0104, 0.109}, {544, 0.0090, 0.073}, {552, 0.0076, 0.044},
    {560, 0.0062, 0.016}, {568, 0.0054, 0.007}, {576, 0.0052, 0.022}, {584, 0.0055, 0.050},
    {592, 0.0057, 0.081}, {600, 0.0054, 0.092}, {608, 0.0056, 0.076}, {616, 0.0062, 0.063},
    {624, 0.0067, 0.071}, {632, 0.0073, 0.080}, {640, 0.0077, 0.098}, {648, 0.0081, 0.123},
    {656, 0.0095, 0.122}, {664, 0.0144, 0.131}, {668, 0.0176, 0.143}, {672, 0.0197, 0.153},
    {675, 0.0201, 0.158}, {678, 0.0193, 0.158}, {682, 0.0166, 0.148}, {686, 0.0124, 0.124},
    {690, 0.0083, 0.086}, {694, 0.0054, 0.042}, {698, 0.0036, -0.016},
};

template <size_t N>
Spectrum tableSpectrum(const TableRow (&rows)[N], float TableRow::*field) {
    std::vector<float> lambda, value;
    for (const TableRow& r : rows) {
        lambda.push_back(r.lambdaNm);
        value.push_back(r.*field);
    }
    return Spectrum::fromTable(lambda, value);
}

}  // namespace

EmbeddedTable waterAbsorptionTable() {
    return {kWaterAbsorption, int(std::size(kWaterAbsorption))};
}
EmbeddedTable bricaudTable() { return {kBricaud, int(std::size(kBricaud))}; }

const Spectrum& waterAbsorption() {
    static const Spectrum s = tableSpectrum(kWaterAbsorption, &TableRow::a);
    return s;
}
const Spectrum& bricaudA() {
    static const Spectrum s = tableSpectrum(kBricaud, &TableRow::a);
    return s;
}
const Spectrum& bricaudB() {
    static const Spectrum s = tableSpectrum(kBricaud, &TableRow::b);
    return s;
}

float waterScattering(float lambdaNm) {
    return kWaterScattering500 * std::pow(lambdaNm / 500.f, -kWaterScatteringExponent);
}

Spectrum waterScatteringSpectrum() {
    std::vector<float> v(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) v[i] = waterScattering(kLambdaMin + float(i));
    return Spectrum::fromDense(std::move(v));
}

Spectrum cdomShapeSpectrum(float slope) {
    std::vector<float> v(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i)
        v[i] = cdomShape(kLambdaMin + float(i), slope);
    return Spectrum::fromDense(std::move(v));
}

}  // namespace mirage::ocean
