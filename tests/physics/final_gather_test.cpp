// The photon integrator's final gather (render/photon_integrator.cpp; Jensen 2001, §9) against
// the reference path tracer in a Cornell-like box: an open-fronted 2 m box of Lambertian walls
// (white floor, ceiling and back wall, red left, green right) lit by a point light under the
// ceiling. The camera sees the walls straight; each of a grid of pixels is one fixed ray, so that
// a photon estimate read straight from the global map there is the same number at every sample
// (its blotch), while the gather rays average it over the hemisphere.
//  - Known answer: the gathered image converges to volpath's, per XYZ channel over the grid.
//  - The blotch: the per-pixel relative mean squared error against volpath falls with the
//    gather by a measured factor.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/photon_integrator.h"
#include "spectrum/cie.h"
#include "spectrum/spectrum.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr int kGrid = 6;  // pixels per side

RenderScene cornellBox() {
    RenderScene scene;
    scene.geometry = std::make_unique<GeometryScene>();
    GeometryScene& g = *scene.geometry;
    const int white = g.addMaterial(Material::diffuse("white", Spectrum(0.75f)));
    const int red =
        g.addMaterial(Material::diffuse("red", rgbReflectanceSpectrum(Vec3(0.75f, 0.1f, 0.08f))));
    const int green =
        g.addMaterial(Material::diffuse("green", rgbReflectanceSpectrum(Vec3(0.12f, 0.6f, 0.1f))));
    g.addQuad(Vec3(-1, 0, 1), Vec3(2, 0, 0), Vec3(0, 0, -2), white);  // floor
    g.addQuad(Vec3(-1, 2, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), white);  // ceiling
    g.addQuad(Vec3(-1, 0, -1), Vec3(2, 0, 0), Vec3(0, 2, 0), white);  // back wall
    g.addQuad(Vec3(-1, 0, 1), Vec3(0, 0, -2), Vec3(0, 2, 0), red);    // left wall
    g.addQuad(Vec3(1, 0, -1), Vec3(0, 0, 2), Vec3(0, 2, 0), green);   // right wall
    g.commit();
    scene.lights.push_back(makePointLight(Vec3(0.f, 1.8f, 0.f), 100.f, Spectrum(1.f)));
    return scene;
}

// Pixel p's ray: from the camera in front of the open side to a grid over the box's inside.
Ray pixelRay(int p) {
    const float x = -0.85f + 1.7f * (float(p % kGrid) + 0.5f) / kGrid;
    const float y = 0.15f + 1.7f * (float(p / kGrid) + 0.5f) / kGrid;
    const Vec3 o(0.f, 1.f, 3.7f);
    return Ray{o, normalize(Vec3(x, y, 0.5f) - o), kInfinity};
}

// Each pixel's mean XYZ over n samples (the spectral part filmed as the film does, plus the
// photon estimates' XYZ).
std::vector<Vec3> image(const Integrator& integrator, const RenderScene& scene, int n) {
    ThreadState ts(scene);
    std::vector<Vec3> pixels(kGrid * kGrid, Vec3(0.f));
    for (int p = 0; p < kGrid * kGrid; ++p) {
        for (int i = 0; i < n; ++i) {
            Sampler s(9, uint64_t(p) * uint64_t(n) + uint64_t(i), 0);
            const SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
            ts.tracking.setWavelengths(w);
            const RadianceSample r = integrator.Li(scene, pixelRay(p), w, s, ts);
            pixels[size_t(p)] += spectrumToXyz(r.L, w) + r.xyz;
        }
        pixels[size_t(p)] *= 1.f / float(n);
    }
    return pixels;
}

double relMse(const std::vector<Vec3>& a, const std::vector<Vec3>& ref) {
    double sum = 0;
    for (size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a[p][c]) - double(ref[p][c]);
            sum += d * d / (double(ref[p][c]) * double(ref[p][c]) + 1e-12);
        }
    return sum / double(3 * a.size());
}

Vec3 meanOf(const std::vector<Vec3>& pixels) {
    Vec3 sum(0.f);
    for (const Vec3& v : pixels) sum += v;
    return sum * (1.f / float(pixels.size()));
}

std::vector<Vec3> photonImage(const RenderScene& scene, int finalGather, int n) {
    PhotonIntegratorSettings ps;
    ps.photons = 20000;
    ps.progress = Progress::Mode::Quiet;
    ps.finalGather = finalGather;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(scene);
    return image(*photon, scene, n);
}

}  // namespace

TEST(FinalGather, ConvergesToVolpathWithLessBlotchThanTheGlobalMapRead) {
    const RenderScene scene = cornellBox();
    auto volpath = makeIntegrator("volpath");
    volpath->preprocess(scene);
    const std::vector<Vec3> reference = image(*volpath, scene, 2000);
    const std::vector<Vec3> direct = photonImage(scene, 0, 16);
    const std::vector<Vec3> gathered = photonImage(scene, 16, 16);

    const Vec3 ref = meanOf(reference), fg = meanOf(gathered), dr = meanOf(direct);
    const double eDirect = relMse(direct, reference), eGather = relMse(gathered, reference);
    std::printf(
        "mean XYZ: volpath (%.5g %.5g %.5g), direct read (%.5g %.5g %.5g), "
        "final gather (%.5g %.5g %.5g); relMSE direct %.3g, gather %.3g\n",
        ref.x, ref.y, ref.z, dr.x, dr.y, dr.z, fg.x, fg.y, fg.z, eDirect, eGather);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fg[c], ref[c], 0.04 * ref[c]) << "channel " << c;
    EXPECT_LT(eGather, 0.5 * eDirect);
}
