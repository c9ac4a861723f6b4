#pragma once
// The sections of a scene file, each a table of entries its capability declares in its own file
// (docs/architecture.md, "How to add a section"). From this one table come the deal.II
// ParameterHandler declarations and the extraction (input/parameter_file.cc), `upgrain
// --print-parameters`, docs/parameters.md and the unknown-entry diagnostics (prm_syntax.h).
#include <string>
#include <vector>

#include "coupling/input/entry.h"

namespace upgrain::coupling::input {

struct Section {
  std::string name;  // the subsection's name in a scene file (one level)
  std::vector<Entry> entries;
  // The section's own checks, among its entries, when the scene's command uses the section;
  // throws upgrain::Error starting with `where` ("<file>: "). Empty: its entries' ranges suffice.
  // Checks across sections are in scene_validation.cc.
  std::function<void(SceneInput&, const std::string& where)> check;
};

// Each section, from the file that owns it.
Section simulation_section();
Section effects_section();
Section particles_section();
Section contact_section();
Section container_section();
Section lid_section();
Section cell_section();
Section fill_section();
Section insertion_section();
Section output_section();
Section checkpoint_section();
Section parallel_section();
Section stress_section();
Section strain_section();
Section study_section();
Section accuracy_section();
Section calibration_section();
Section element_section();
Section femxdem_section();
Section coarse_graining_section();
Section continuum_section();

// Every section, in the order a parameter file lists them.
const std::vector<Section>& scene_sections();

// The names of the sections, and of the entries of one, for "did you mean" diagnostics.
std::vector<std::string> section_names();
std::vector<std::string> entry_names(const std::string& section);

// Every section's own checks, in the table's order (validate_scene).
void check_sections(SceneInput& in, const std::string& where);

// Every entry's value in a default-constructed SceneInput: the built-in default scene.
std::string default_value(const Entry& entry);

}  // namespace upgrain::coupling::input
