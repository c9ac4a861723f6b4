# The accuracy study (docs/accuracy.md).
list(APPEND UPGRAIN_STUDY_INPUT_SOURCES
  coupling/studies/accuracy/accuracy_section.cc
  coupling/studies/accuracy/accuracy_knobs.cc
  coupling/studies/accuracy/accuracy_checks.cc)
list(APPEND UPGRAIN_STUDY_SOURCES
  coupling/studies/accuracy/bed_measures.cc
  coupling/studies/accuracy/collision_reference.cc
  coupling/studies/accuracy/contact_solver_reference.cc
  coupling/studies/accuracy/accuracy_study.cc)
