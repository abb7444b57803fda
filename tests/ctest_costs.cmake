# The seconds the slow tests take (ctest -j2 -LE gallery on 2 cores, pipeline/test.sh), as their
# COST (tests/CMakeLists.txt): ctest starts the costliest first when it has no record of past
# runs (Testing/Temporary/CTestCostData.txt, which replaces these where it has one). Unit tests
# are named by suite (support/suite_tests.cmake). Names that no longer exist are ignored.
foreach(cost IN ITEMS
    # physics
    "FluorescencePhotonMap.AgreesWithVolPathOnTheFluorescentBand 34"
    "VolumeMotionBlur.KeyedTranslationIsTheMeanOfTranslatedStills 17"
    "FirePhotons.PhotonMapOfGlowingSmokeAgreesWithVolPath 16"
    "PhotonConvergence.PhotonMapConvergesToVolPath 15"
    "FluorescencePhotonMap.PowerLeavingTheCubeAgreesWithVolPath 14"
    "CurvedPhotons.WeakFieldGivesThePhotonMapImageOfStraightLight 14"
    "PhotonColour.CurvedCameraRaysAttenuatePhotonsAtTheirWavelength 13"
    "PhotonConvergence.BothEstimatesUnbiasedOnTheMeanInAHeterogeneousMedium 13"
    "GalleryScenes.VolumeCausticConeGlowsGreen 12"
    "ShippedScenes.EachRendersFiniteAndLitWithoutSharedData 10"
    "CameraMotionBlur.PanningCameraIsTheMeanOfStills 9"
    "CameraMotionBlur.TurntableBlursAlongItsOrbit 9"
    "MotionBlur.BlurredPuffIsTheMeanOfTranslatedStillsSingleScatter 9"
    "OceanColour.ChlorophyllMovesTheSeaFromBlueTowardsGreen 9"
    "CurvedCameraBlur.BentCameraRaysSeeTheMovingPuffAtTheirTime 8"
    "MotionBlur.BlurredPuffIsTheMeanOfTranslatedStillsVolpath 8"
    "OceanColour.Case1ClearWaterBandRatioFollowsTheOc4Model 8"
    "ProgressivePhoton.PassesConvergeToVolPathPerChannel 7"
    "ProgressivePhoton.ASmallerFirstPassConvergesLikeEqualPasses 7"
    "PhotonColour.DispersiveBallKeepsTheHeroWavelengthsLight 7"
    # unit suites
    "KilledRenderCli 43"
    "Tradeoff 20"
    "CurvedScenes 18"
    "EndToEnd 16"
    "LightEmission 15"
    "GridExpression 14"
    "PassesCli 14"
    "RegionCli 13"
    "IntegratorChoice 13"
    "Aov 13"
    "BadInput 12"
    "CliOutput 12"
    "Slab 11"
    "Passes 11"
    "FramePipeline 10"
    "PhotonFileCli 10")
  string(REPLACE " " ";" cost "${cost}")
  list(GET cost 0 name)
  list(GET cost 1 seconds)
  set_tests_properties(${name} PROPERTIES COST ${seconds})
endforeach()
