# The input layer's sources without deal.II, relative to the project's root: the scene file's
# sections, each declared by the capability that owns it (docs/architecture.md, "How to add a
# section"), its syntax and its checks across sections, and each study's section and checks
# (coupling/studies/sources.cmake). Included by coupling/CMakeLists.txt and by the fuzzer's build
# (tests/fuzz/CMakeLists.txt), which compiles them with its sanitizers.
include(${CMAKE_CURRENT_LIST_DIR}/../studies/sources.cmake)
set(UPGRAIN_INPUT_SOURCES
  coupling/input/entry.cc
  coupling/input/scene_sections.cc
  coupling/input/sections/simulation.cc
  coupling/input/sections/effects.cc
  coupling/input/sections/particles.cc
  coupling/input/sections/contact.cc
  coupling/input/sections/cell.cc
  coupling/input/sections/container.cc
  coupling/input/sections/lid.cc
  coupling/input/sections/fill.cc
  coupling/input/sections/insertion.cc
  coupling/input/sections/output.cc
  coupling/input/sections/checkpoint.cc
  coupling/input/sections/parallel.cc
  coupling/input/sections/stress.cc
  coupling/input/sections/strain.cc
  coupling/input/prm_syntax.cc
  coupling/input/scene_text.cc
  coupling/input/scene_validation.cc
  coupling/input/scene_limits.cc
  coupling/input/memory_estimate.cc
  ${UPGRAIN_STUDY_INPUT_SOURCES})
