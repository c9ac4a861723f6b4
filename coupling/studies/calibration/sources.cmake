# The calibration study (docs/calibration.md); its oedometric and triaxial runs are plain C++
# that the physics tests run alone.
list(APPEND UPGRAIN_STUDY_RUN_SOURCES
  coupling/studies/calibration/oedometer_run.cc
  coupling/studies/calibration/periodic_cell_tests.cc
  coupling/studies/calibration/triaxial_run.cc)
list(APPEND UPGRAIN_STUDY_INPUT_SOURCES
  coupling/studies/calibration/calibration_section.cc
  coupling/studies/calibration/calibration_checks.cc)
list(APPEND UPGRAIN_STUDY_SOURCES
  coupling/studies/calibration/bed_calibration.cc
  coupling/studies/calibration/calibration_study.cc)
