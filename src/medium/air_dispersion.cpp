// The dispersion formulas of air (air_dispersion.h says which and where they are published).
#include "medium/air_dispersion.h"

#include "medium/air_index.h"

namespace mirage {

namespace {

// The reference temperature of Edlén's and Ciddor's standard air: 15 °C.
constexpr double kStandardAirTemperature = 288.15;  // K

// 1/λ² in 1/µm² for λ in nm.
double wavenumberSquared(double lambdaNm) {
    const double um = lambdaNm * 1e-3;
    return 1.0 / (um * um);
}

}  // namespace

const char* airDispersionName(AirDispersion kind) {
    switch (kind) {
        case AirDispersion::Cauchy:
            return "cauchy";
        case AirDispersion::Edlen1966:
            return "edlen";
        case AirDispersion::Ciddor1996:
            return "ciddor";
    }
    return "?";
}

double referenceRefractivity(AirDispersion kind, double lambdaNm) {
    const double s2 = wavenumberSquared(lambdaNm);
    switch (kind) {
        case AirDispersion::Edlen1966:
            return 1e-8 * (8342.13 + 2406030.0 / (130.0 - s2) + 15997.0 / (38.9 - s2));
        case AirDispersion::Ciddor1996:
            return 1e-8 * (5792105.0 / (238.0185 - s2) + 167917.0 / (57.362 - s2));
        case AirDispersion::Cauchy:
            break;
    }
    return airRefractivity(lambdaNm);
}

double referenceDensity(AirDispersion kind) {
    static const double cauchy = airDensity(air::kRefPressure, air::kRefTemperature);
    static const double standard = airDensity(air::kRefPressure, kStandardAirTemperature);
    return kind == AirDispersion::Cauchy ? cauchy : standard;
}

}  // namespace mirage
