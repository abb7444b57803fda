# The seconds the slow tests took in a run of ctest -j2 -LE gallery (pipeline/test.sh) on the
# shared 2-core machine, as their COST (tests/CMakeLists.txt): ctest starts the costliest first
# when it has no record of past runs (Testing/Temporary/CTestCostData.txt, which replaces these
# where it has one); only their order matters. Unit tests are named by suite
# (support/suite_tests.cmake); a parameterised test's name ends with its parameter, as
# gtest_discover_tests names it. Names that no longer exist are ignored.
foreach(cost IN ITEMS
    # physics
    "FluorescencePhotonMap.AgreesWithVolPathOnTheFluorescentBand|76"
    "PhotonConvergence.PhotonMapConvergesToVolPath|62"
    "VolumeMotionBlur.KeyedTranslationIsTheMeanOfTranslatedStills|53"
    "PhotonColour.CurvedCameraRaysAttenuatePhotonsAtTheirWavelength|51"
    "FluorescencePhotonMap.PowerLeavingTheCubeAgreesWithVolPath|49"
    "PhotonConvergence.BothEstimatesUnbiasedOnTheMeanInAHeterogeneousMedium|43"
    "CurvedPhotons.WeakFieldGivesThePhotonMapImageOfStraightLight|43"
    "GalleryScenes.VolumeCausticConeGlowsGreen|37"
    "ProgressivePhoton.PassesConvergeToVolPathPerChannel|35"
    "ProgressivePhoton.ASmallerFirstPassConvergesLikeEqualPasses|34"
    "OceanColour.Case1ClearWaterBandRatioFollowsTheOc4Model|28"
    "PhotonColour.DispersiveBallKeepsTheHeroWavelengthsLight|24"
    "ProgressivePhoton.FurnacePassesAverageToLe|22"
    "RefractionScene.ChordByChordMediaMatchTheStraightRender|22"
    "Slab.AddingDoublingSemiInfiniteConservativeSlab|20"
    "ShippedScenes.EachRendersFiniteAndLitWithoutSharedData|19"
    "FirePhotons.PhotonMapOfGlowingSmokeAgreesWithVolPath|18"
    "MotionBlur.BlurredPuffIsTheMeanOfTranslatedStillsSingleScatter|17"
    "GalleryScenes.CornellWaterSeriesBloomIsGreener|17"
    "Slab.AddingDoublingThinForwardScatteringSlab|16"
    "OceanColour.ChlorophyllMovesTheSeaFromBlueTowardsGreen|16"
    "UnderwaterPair.HigherChlorophyllIsGreenerAndHazier|15"
    "ErrorEstimate.VolPathReadsLowAtFewSamplesAndClosesIn|15"
    "CameraMotionBlur.PanningCameraIsTheMeanOfStills|15"
    "Furnace/LitBox.VolPathLobeWalksFindTheWallsRadiance/WithAWhiteBall  # GetParam() = true|33"
    "Furnace/LitBox.VolPathLobeWalksFindTheWallsRadiance/MediumAlone  # GetParam() = false|30"
    "CameraMotionBlur.TurntableBlursAlongItsOrbit|14"
    # unit suites
    "KilledRenderCli|56"
    "Tradeoff|49"
    "RegionCli|43"
    "GridExpression|35"
    "CurvedScenes|35"
    "EndToEnd|32"
    "CliOutput|29"
    "Tracking|27"
    "PassesCli|24"
    "LightEmission|23"
    "AssembleCli|22"
    "BeamEstimate|22"
    "FramePipeline|20"
    "IntegratorChoice|20"
    "RefractionScene|20"
    "BadInput|19"
    "PhotonFileCli|18"
    "Raypath|16"
    "Passes|16")
  string(REPLACE "|" ";" cost "${cost}")
  list(GET cost 0 name)
  list(GET cost 1 seconds)
  set_tests_properties(${name} PROPERTIES COST ${seconds})
endforeach()
