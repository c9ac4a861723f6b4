# The scene file's sections, each declared by the capability that owns it (docs/architecture.md,
# "How to add a section"), relative to the project's root. Included by coupling/CMakeLists.txt
# and by the fuzzer's build (tests/fuzz/CMakeLists.txt), which compiles them with its sanitizers.
set(UPGRAIN_SCENE_SECTION_SOURCES
  coupling/input/entry.cc
  coupling/input/scene_sections.cc
  coupling/input/sections/simulation.cc
  coupling/input/sections/effects.cc
  coupling/input/sections/particles.cc
  coupling/input/sections/contact.cc
  coupling/input/sections/container.cc
  coupling/input/sections/lid.cc
  coupling/input/sections/fill.cc
  coupling/input/sections/insertion.cc
  coupling/input/sections/output.cc
  coupling/input/sections/checkpoint.cc
  coupling/input/sections/parallel.cc
  coupling/input/sections/stress.cc
  coupling/input/sections/strain.cc
  coupling/input/sections/study.cc
  coupling/input/sections/coarse_graining.cc
  coupling/input/sections/continuum.cc
  coupling/accuracy/accuracy_section.cc
  coupling/calibration/calibration_section.cc)
