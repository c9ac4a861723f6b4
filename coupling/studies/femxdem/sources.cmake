# The FEM x DEM study (docs/femxdem.md): its DEM cells (coupling/femxdem/) are plain C++ over the
# engine; the study drives the deal.II continuum (fem/quasi_static/) with them.
list(APPEND UPGRAIN_STUDY_INPUT_SOURCES
  coupling/studies/femxdem/femxdem_section.cc
  coupling/studies/femxdem/femxdem_checks.cc
  coupling/studies/femxdem/cell_choice.cc)
list(APPEND UPGRAIN_STUDY_SOURCES
  coupling/studies/femxdem/cell_snapshots.cc
  coupling/studies/femxdem/femxdem_checkpoints.cc
  coupling/studies/femxdem/femxdem_study.cc)
