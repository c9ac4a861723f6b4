# The scene's own study, DEM against the continuum (docs/study.md).
list(APPEND UPGRAIN_STUDY_INPUT_SOURCES
  coupling/studies/continuum/study_section.cc
  coupling/studies/continuum/coarse_graining_section.cc
  coupling/studies/continuum/continuum_section.cc
  coupling/studies/continuum/continuum_checks.cc)
list(APPEND UPGRAIN_STUDY_SOURCES
  coupling/studies/continuum/continuum_study.cc
  coupling/studies/continuum/study_report.cc
  coupling/studies/continuum/dem_fem_comparison.cc
  coupling/studies/continuum/strain_report.cc
  coupling/studies/continuum/coarse_graining_study.cc)
