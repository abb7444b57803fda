// The procedural fire in a scene: the built-in `fire` shader on `mirage make-asset fire`, the
// per-volume `emission_intensity` exposure control, and what `mirage info` says about it.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "film/color.h"
#include "photon/medium_emitter.h"
#include "scene/scene.h"
#include "test_support.h"
#include "tools/asset_writer.h"

using namespace mirage;

namespace {

std::string writeFireScene(const std::string& dir, const std::string& volumeExtra,
                           const std::string& shader = "fire") {
    const std::string scene =
        dir + "/fire_" + std::to_string(volumeExtra.size()) + shader + ".toml";
    std::ofstream f(scene);
    f << "[film]\nresolution = [16, 16]\nspp = 1\n[render]\nintegrator = \"photon\"\n"
         "[[volume]]\nfile = \"fire.vdb\"\nshader = \""
      << shader << "\"\ndensity_scale = 6.0\n"
      << volumeExtra << "\n";
    return scene;
}

}  // namespace

TEST(FireScene, EmissionIntensityScalesThePowerAndNothingElse) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fire", dir + "/fire.vdb", 32, 3);
    ColorPipeline color;
    Scene base = loadScene(writeFireScene(dir, ""), LoadOptions{}, color);
    Scene bright = loadScene(writeFireScene(dir, "emission_intensity = 4.0"), LoadOptions{}, color);
    const double p1 = MediumEmitter(*base.render.media[0]).tablePower();
    const double p4 = MediumEmitter(*bright.render.media[0]).tablePower();
    EXPECT_GT(p1, 0.0);
    EXPECT_NEAR(p4 / p1, 4.0, 1e-4);
    EXPECT_EQ(bright.render.media[0]->shader().emission->intensity, 4.f);

    // A shader without emission has nothing to scale: an error naming the key.
    try {
        loadScene(writeFireScene(dir, "emission_intensity = 2.0", "smoke"), LoadOptions{}, color);
        FAIL() << "expected an error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("emission_intensity"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no [emission] table"), std::string::npos) << e.what();
    }

    // `mirage info` reports the emitted power and that emitted light scatters.
    std::string out;
    ASSERT_EQ(0, test::runMirage("info '" + writeFireScene(dir, "") + "'", &out)) << out;
    EXPECT_NE(out.find("the photon pass emits ∝ this"), std::string::npos) << out;
    EXPECT_NE(out.find("emitted light included"), std::string::npos) << out;
    // The fire shader's σ are grey: its coefficients take the grey path (emission stays
    // spectral, Planck at each wavelength).
    EXPECT_NE(out.find("coefficients: grey path"), std::string::npos) << out;
}
