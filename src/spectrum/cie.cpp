// CIE 1931 2° colour-matching functions and the spectral → XYZ estimator every pixel sample
// goes through.
//
// The table holds the CIE 2018 open data set values (DOI 10.25039/CIE.DS.xvudnb9b: "CIE 1931
// colour-matching functions, 2 degree observer"), every 5th row of the 1 nm table, 360–830 nm.
// Published values are facts; this is the same data at a coarser step.
//
// Linear interpolation of the 5 nm rows is not good enough: z̄ rises steeply around 415 nm and
// the chord misses the 1 nm table by 0.9 % of z̄'s peak there. The 5 nm rows are therefore
// refined to 1 nm at compile time by Sprague interpolation, the CIE's recommended method for
// 5 nm spectral data (CIE 167:2005; a quintic through six neighbours that passes through every
// row), and evaluated by linear interpolation between the 1 nm values. The refined table matches
// the CIE 1 nm table to 2.7e-4 of each function's peak (tests/unit/spectrum_test.cpp measures it
// against ../shared/data when that is present).

#include "spectrum/cie.h"

#include <algorithm>
#include <array>

namespace mirage {

namespace {

constexpr int kCmfRows = 95;                                  // (830 − 360) / 5 + 1
constexpr int kRefinedRows = 471;                             // (830 − 360) / 1 + 1
constexpr int kRefine = (kRefinedRows - 1) / (kCmfRows - 1);  // 5 sub-steps per row

// x̄, ȳ, z̄ at 360, 365, …, 830 nm (CIE 2018, DOI 10.25039/CIE.DS.xvudnb9b).
constexpr float kCmf[kCmfRows][3] = {
    {0.000129900000f, 0.0000039170000f, 0.000606100000f},  // 360
    {0.000232100000f, 0.0000069650000f, 0.001086000000f},  // 365
    {0.000414900000f, 0.0000123900000f, 0.001946000000f},  // 370
    {0.000741600000f, 0.0000220200000f, 0.003486000000f},  // 375
    {0.001368000000f, 0.0000390000000f, 0.006450001000f},  // 380
    {0.002236000000f, 0.0000640000000f, 0.010549990000f},  // 385
    {0.004243000000f, 0.0001200000000f, 0.020050010000f},  // 390
    {0.007650000000f, 0.0002170000000f, 0.036210000000f},  // 395
    {0.014310000000f, 0.0003960000000f, 0.067850010000f},  // 400
    {0.023190000000f, 0.0006400000000f, 0.110200000000f},  // 405
    {0.043510000000f, 0.0012100000000f, 0.207400000000f},  // 410
    {0.077630000000f, 0.0021800000000f, 0.371300000000f},  // 415
    {0.134380000000f, 0.0040000000000f, 0.645600000000f},  // 420
    {0.214770000000f, 0.0073000000000f, 1.039050100000f},  // 425
    {0.283900000000f, 0.0116000000000f, 1.385600000000f},  // 430
    {0.328500000000f, 0.0168400000000f, 1.622960000000f},  // 435
    {0.348280000000f, 0.0230000000000f, 1.747060000000f},  // 440
    {0.348060000000f, 0.0298000000000f, 1.782600000000f},  // 445
    {0.336200000000f, 0.0380000000000f, 1.772110000000f},  // 450
    {0.318700000000f, 0.0480000000000f, 1.744100000000f},  // 455
    {0.290800000000f, 0.0600000000000f, 1.669200000000f},  // 460
    {0.251100000000f, 0.0739000000000f, 1.528100000000f},  // 465
    {0.195360000000f, 0.0909800000000f, 1.287640000000f},  // 470
    {0.142100000000f, 0.1126000000000f, 1.041900000000f},  // 475
    {0.095640000000f, 0.1390200000000f, 0.812950100000f},  // 480
    {0.057950010000f, 0.1693000000000f, 0.616200000000f},  // 485
    {0.032010000000f, 0.2080200000000f, 0.465180000000f},  // 490
    {0.014700000000f, 0.2586000000000f, 0.353300000000f},  // 495
    {0.004900000000f, 0.3230000000000f, 0.272000000000f},  // 500
    {0.002400000000f, 0.4073000000000f, 0.212300000000f},  // 505
    {0.009300000000f, 0.5030000000000f, 0.158200000000f},  // 510
    {0.029100000000f, 0.6082000000000f, 0.111700000000f},  // 515
    {0.063270000000f, 0.7100000000000f, 0.078249990000f},  // 520
    {0.109600000000f, 0.7932000000000f, 0.057250010000f},  // 525
    {0.165500000000f, 0.8620000000000f, 0.042160000000f},  // 530
    {0.225749900000f, 0.9148501000000f, 0.029840000000f},  // 535
    {0.290400000000f, 0.9540000000000f, 0.020300000000f},  // 540
    {0.359700000000f, 0.9803000000000f, 0.013400000000f},  // 545
    {0.433449900000f, 0.9949501000000f, 0.008749999000f},  // 550
    {0.512050100000f, 1.0000000000000f, 0.005749999000f},  // 555
    {0.594500000000f, 0.9950000000000f, 0.003900000000f},  // 560
    {0.678400000000f, 0.9786000000000f, 0.002749999000f},  // 565
    {0.762100000000f, 0.9520000000000f, 0.002100000000f},  // 570
    {0.842500000000f, 0.9154000000000f, 0.001800000000f},  // 575
    {0.916300000000f, 0.8700000000000f, 0.001650001000f},  // 580
    {0.978600000000f, 0.8163000000000f, 0.001400000000f},  // 585
    {1.026300000000f, 0.7570000000000f, 0.001100000000f},  // 590
    {1.056700000000f, 0.6949000000000f, 0.001000000000f},  // 595
    {1.062200000000f, 0.6310000000000f, 0.000800000000f},  // 600
    {1.045600000000f, 0.5668000000000f, 0.000600000000f},  // 605
    {1.002600000000f, 0.5030000000000f, 0.000340000000f},  // 610
    {0.938400000000f, 0.4412000000000f, 0.000240000000f},  // 615
    {0.854449900000f, 0.3810000000000f, 0.000190000000f},  // 620
    {0.751400000000f, 0.3210000000000f, 0.000100000000f},  // 625
    {0.642400000000f, 0.2650000000000f, 0.000049999990f},  // 630
    {0.541900000000f, 0.2170000000000f, 0.000030000000f},  // 635
    {0.447900000000f, 0.1750000000000f, 0.000020000000f},  // 640
    {0.360800000000f, 0.1382000000000f, 0.000010000000f},  // 645
    {0.283500000000f, 0.1070000000000f, 0.000000000000f},  // 650
    {0.218700000000f, 0.0816000000000f, 0.000000000000f},  // 655
    {0.164900000000f, 0.0610000000000f, 0.000000000000f},  // 660
    {0.121200000000f, 0.0445800000000f, 0.000000000000f},  // 665
    {0.087400000000f, 0.0320000000000f, 0.000000000000f},  // 670
    {0.063600000000f, 0.0232000000000f, 0.000000000000f},  // 675
    {0.046770000000f, 0.0170000000000f, 0.000000000000f},  // 680
    {0.032900000000f, 0.0119200000000f, 0.000000000000f},  // 685
    {0.022700000000f, 0.0082100000000f, 0.000000000000f},  // 690
    {0.015840000000f, 0.0057230000000f, 0.000000000000f},  // 695
    {0.011359160000f, 0.0041020000000f, 0.000000000000f},  // 700
    {0.008110916000f, 0.0029290000000f, 0.000000000000f},  // 705
    {0.005790346000f, 0.0020910000000f, 0.000000000000f},  // 710
    {0.004109457000f, 0.0014840000000f, 0.000000000000f},  // 715
    {0.002899327000f, 0.0010470000000f, 0.000000000000f},  // 720
    {0.002049190000f, 0.0007400000000f, 0.000000000000f},  // 725
    {0.001439971000f, 0.0005200000000f, 0.000000000000f},  // 730
    {0.000999949300f, 0.0003611000000f, 0.000000000000f},  // 735
    {0.000690078600f, 0.0002492000000f, 0.000000000000f},  // 740
    {0.000476021300f, 0.0001719000000f, 0.000000000000f},  // 745
    {0.000332301100f, 0.0001200000000f, 0.000000000000f},  // 750
    {0.000234826100f, 0.0000848000000f, 0.000000000000f},  // 755
    {0.000166150500f, 0.0000600000000f, 0.000000000000f},  // 760
    {0.000117413000f, 0.0000424000000f, 0.000000000000f},  // 765
    {0.000083075270f, 0.0000300000000f, 0.000000000000f},  // 770
    {0.000058706520f, 0.0000212000000f, 0.000000000000f},  // 775
    {0.000041509940f, 0.0000149900000f, 0.000000000000f},  // 780
    {0.000029353260f, 0.0000106000000f, 0.000000000000f},  // 785
    {0.000020673830f, 0.0000074657000f, 0.000000000000f},  // 790
    {0.000014559770f, 0.0000052578000f, 0.000000000000f},  // 795
    {0.000010253980f, 0.0000037029000f, 0.000000000000f},  // 800
    {0.000007221456f, 0.0000026078000f, 0.000000000000f},  // 805
    {0.000005085868f, 0.0000018366000f, 0.000000000000f},  // 810
    {0.000003581652f, 0.0000012934000f, 0.000000000000f},  // 815
    {0.000002522525f, 0.0000009109300f, 0.000000000000f},  // 820
    {0.000001776509f, 0.0000006415300f, 0.000000000000f},  // 825
    {0.000001251141f, 0.0000004518100f, 0.000000000000f},  // 830
};

using RefinedTable = std::array<std::array<float, 3>, kRefinedRows>;

// Sprague interpolation (CIE 167:2005, section 4.3.2) of one column of kCmf to 1 nm. Between rows
// P0 and P1 the curve is the quintic a0 + a1 x + … + a5 x⁵ (x ∈ [0, 1)) fitted to P−2 … P3; two
// extra points are extrapolated at each end of the table with the coefficients below (/ 209).
constexpr RefinedTable spragueRefine() {
    constexpr double kExtrapolate[4][6] = {{884, -1960, 3033, -2648, 1080, -180},
                                           {508, -540, 488, -367, 144, -24},
                                           {-24, 144, -367, 488, -540, 508},
                                           {-180, 1080, -2648, 3033, -1960, 884}};
    RefinedTable out{};
    for (int c = 0; c < 3; ++c) {
        double p[kCmfRows + 4] = {};  // p[k + 2] = row k; p[0], p[1], p[n+2], p[n+3] extrapolated
        for (int k = 0; k < kCmfRows; ++k) p[k + 2] = kCmf[k][c];
        for (int j = 0; j < 6; ++j) {
            p[0] += kExtrapolate[0][j] * kCmf[j][c] / 209.0;
            p[1] += kExtrapolate[1][j] * kCmf[j][c] / 209.0;
            p[kCmfRows + 2] += kExtrapolate[2][j] * kCmf[kCmfRows - 6 + j][c] / 209.0;
            p[kCmfRows + 3] += kExtrapolate[3][j] * kCmf[kCmfRows - 6 + j][c] / 209.0;
        }
        for (int k = 0; k + 1 < kCmfRows; ++k) {
            const double* q = &p[k];  // q[0..5] = P−2, P−1, P0, P1, P2, P3
            double a0 = q[2];
            double a1 = (2 * q[0] - 16 * q[1] + 16 * q[3] - 2 * q[4]) / 24;
            double a2 = (-q[0] + 16 * q[1] - 30 * q[2] + 16 * q[3] - q[4]) / 24;
            double a3 = (-9 * q[0] + 39 * q[1] - 70 * q[2] + 66 * q[3] - 33 * q[4] + 7 * q[5]) / 24;
            double a4 =
                (13 * q[0] - 64 * q[1] + 126 * q[2] - 124 * q[3] + 61 * q[4] - 12 * q[5]) / 24;
            double a5 = (-5 * q[0] + 25 * q[1] - 50 * q[2] + 50 * q[3] - 25 * q[4] + 5 * q[5]) / 24;
            for (int s = 0; s < kRefine; ++s) {
                double x = double(s) / kRefine;
                double v = a0 + x * (a1 + x * (a2 + x * (a3 + x * (a4 + x * a5))));
                // The quintic can dip a hair below 0 where z̄ ends; the functions cannot.
                out[k * kRefine + s][c] = float(std::max(v, 0.0));
            }
        }
        out[kRefinedRows - 1][c] = kCmf[kCmfRows - 1][c];
    }
    return out;
}

constexpr RefinedTable kCmf1nm = spragueRefine();

}  // namespace

Vec3 cieXyz(float lambdaNm) {
    // The negated test also sends NaN to 0.
    if (!(lambdaNm >= kLambdaMin && lambdaNm <= kLambdaMax)) return Vec3(0.f);
    float t = lambdaNm - kLambdaMin;  // 1 nm rows
    int i = std::min(int(t), kRefinedRows - 2);
    float f = t - float(i);
    const auto& a = kCmf1nm[i];
    const auto& b = kCmf1nm[i + 1];
    return {lerp(f, a[0], b[0]), lerp(f, a[1], b[1]), lerp(f, a[2], b[2])};
}

// Monte Carlo estimate of XYZ = ∫ L(λ) cmf(λ) dλ / ∫ȳ with the path's N wavelengths drawn from
// pdf(λ): each sample contributes L cmf / pdf, averaged over N. Dividing by ∫ȳ makes a constant
// spectrum of radiance 1 come out as Y = 1, so Y is in the units of L (W·m⁻²·sr⁻¹·nm⁻¹ averaged
// over the eye's response) rather than in lumens. A wavelength with pdf 0 (outside the sampled
// range) contributes nothing; it was never drawn.
Vec3 spectrumToXyz(const SampledSpectrum& L, const SampledWavelengths& w) {
    return SampleXyz(w)(L);
}

// The weights cmf(λ_i) / (pdf(λ_i) · N · ∫ȳ) are computed once per sample: the beauty and each
// of its render passes then cost four multiply-adds.
SampleXyz::SampleXyz(const SampledWavelengths& w) {
    const float norm = float(kSpectrumSamples) * kCieYIntegral;
    for (int i = 0; i < kSpectrumSamples; ++i)
        mWeight[i] = w.pdf[i] == 0.f ? Vec3(0.f) : cieXyz(w.lambda[i]) / (w.pdf[i] * norm);
}

}  // namespace mirage
