# The tests that took 15 s or more on the 2-core VM (ctest -j2, 2026-11-28,
# build/Testing/Temporary/CTestCostData.txt): labelled `slow` besides their
# kind, so `ctest -LE slow` is a pass of a few minutes. Included twice: by
# cmake/test_labels.cmake for the tests add_test made, and by ctest (the
# directory's TEST_INCLUDE_FILES) for the ones GoogleTest discovered.
set(KERF_SLOW_TESTS
  [==[install.ExampleProjectBuildsAgainstTheInstalledKerfAndRuns]==]
  [==[mpi.RanksMatchSerial.NodalImplicit]==]
  [==[mpi.RanksMatchSerial.NodalStaticStrip3d]==]
  [==[paraview.OpensEveryOutputChecksItsArraysAndRenders]==]
  [==[study.crack3d]==]
  [==[study.crack3d.one_thread]==]
  [==[study.cut_convergence.one_thread]==]
  [==[study.hertz.one_thread]==]
  [==[study.cut]==]
  [==[study.cut_convergence]==]
  [==[study.hertz]==]
  [==[study.scaling]==]
  [==[study.stability]==])
set(KERF_SLOW_GTESTS
  [==[regression.CrackScenes.SlabOpeningAgreesWithThePlaneStrainPlateWithin3Percent]==]
  [==[regression.CrackScenes.SmoothedNodalIntegrationConvergesWithin3PercentOnBothCracks]==]
  [==[regression.ExplicitIndentation.SettlesWithinTenPercentOfTheStaticAnswer]==]
  [==[regression.InterruptedRun.WhileMeshingShowsProgressStopsWithinTheGraceAndSaysInterrupted]==]
  [==[regression.Meshless/PressedMeshlessBlock.GrowingCutUnderTheSphereEndsWhereTheWholeCutEnds/"efg"]==]
  [==[regression.Meshless/PressedMeshlessBlock.GrowingCutUnderTheSphereEndsWhereTheWholeCutEnds/"nodal"]==])
# When ctest includes it (after the discovered tests are added): their labels,
# their executable's kind and slow.
if(KERF_LABEL_DISCOVERED_SLOW_TESTS)
  foreach(test IN LISTS KERF_SLOW_GTESTS)
    string(REGEX REPLACE "\\..*$" "" kind "${test}")
    set_tests_properties("${test}" PROPERTIES LABELS "${kind};slow")
  endforeach()
endif()
