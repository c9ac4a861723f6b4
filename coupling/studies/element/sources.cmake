# The element study (docs/element-tests.md): its tests on the periodic cell are plain C++ over
# the engine.
list(APPEND UPGRAIN_STUDY_RUN_SOURCES
  coupling/studies/element/element_cell.cc
  coupling/studies/element/element_run.cc)
list(APPEND UPGRAIN_STUDY_INPUT_SOURCES
  coupling/studies/element/element_section.cc
  coupling/studies/element/element_checks.cc)
list(APPEND UPGRAIN_STUDY_SOURCES
  coupling/studies/element/element_study.cc)
