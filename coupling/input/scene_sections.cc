#include "coupling/input/scene_sections.h"

#include "coupling/input/scene_input.h"

namespace upgrain::coupling::input {

const std::vector<Section>& scene_sections() {
  static const std::vector<Section> table = {
      simulation_section(),  effects_section(), particles_section(),  contact_section(),
      container_section(),   cell_section(),    lid_section(),        fill_section(),
      insertion_section(),   output_section(),  checkpoint_section(), parallel_section(),
      stress_section(),      strain_section(),  study_section(),      accuracy_section(),
      calibration_section(), element_section(), femxdem_section(),    coarse_graining_section(),
      continuum_section()};
  return table;
}

std::vector<std::string> section_names() {
  std::vector<std::string> out;
  for (const Section& s : scene_sections()) out.push_back(s.name);
  return out;
}

std::vector<std::string> entry_names(const std::string& section) {
  std::vector<std::string> out;
  for (const Section& s : scene_sections())
    if (s.name == section)
      for (const Entry& e : s.entries) out.push_back(e.name);
  return out;
}

void check_sections(SceneInput& in, const std::string& where) {
  for (const Section& s : scene_sections())
    if (s.check) s.check(in, where);
}

std::string default_value(const Entry& entry) {
  SceneInput defaults;
  return entry.write(defaults);
}

}  // namespace upgrain::coupling::input
