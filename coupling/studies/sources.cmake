# The studies' sources, relative to the project's root: each study's folder lists its own in
# its sources.cmake (docs/architecture.md, "How to add a study"), by the library each joins:
#   UPGRAIN_STUDY_RUN_SOURCES    plain runs of the DEM that tests use alone (upgrain_run);
#   UPGRAIN_STUDY_INPUT_SOURCES  its scene section and its own checks (the input layer, which
#                                the scene-file fuzzer compiles too);
#   UPGRAIN_STUDY_SOURCES        the study itself, with deal.II (upgrain_study).
# The table of studies (study_table.cc) gives each one row; what the studies share of a driver
# run sits beside it: the DEM run, the account of a run, the figure scripts.
set(UPGRAIN_STUDY_RUN_SOURCES)
set(UPGRAIN_STUDY_INPUT_SOURCES)
set(UPGRAIN_STUDY_SOURCES
  coupling/studies/study_table.cc
  coupling/studies/dem_run.cc
  coupling/studies/run_account.cc
  coupling/studies/figure_script.cc
  coupling/studies/plot_script.cc)
file(GLOB upgrain_study_source_lists CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*/sources.cmake)
foreach(list_file IN LISTS upgrain_study_source_lists)
  include(${list_file})
endforeach()
