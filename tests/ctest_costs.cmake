# The seconds the slow tests take (ctest -j2 -LE gallery on 2 cores, pipeline/test.sh), as their
# COST (tests/CMakeLists.txt): ctest starts the costliest first when it has no record of past
# runs (Testing/Temporary/CTestCostData.txt, which replaces these where it has one). Unit tests
# are named by suite (support/suite_tests.cmake). Names that no longer exist are ignored.
foreach(cost IN ITEMS
    "FluorescencePhotonMap.AgreesWithVolPathOnTheFluorescentBand 34"
    "VolumeMotionBlur.KeyedTranslationIsTheMeanOfTranslatedStills 17"
    "PhotonConvergence.PhotonMapConvergesToVolPath 18"
    "KilledRenderCli 45")
  string(REPLACE " " ";" cost "${cost}")
  list(GET cost 0 name)
  list(GET cost 1 seconds)
  set_tests_properties(${name} PROPERTIES COST ${seconds})
endforeach()
