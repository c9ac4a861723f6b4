// The Strain section: finite strain and objective stress rates on the stress grid (docs/strain.md).
#include "coupling/input/formula_choices.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class... Members>
auto strain(Members... m) {
  return at(&SceneInput::output, &OutputOptions::grid_strain, m...);
}

}  // namespace

Section strain_section() {
  Section section{
      "Strain",
      {boolean("enabled", strain(&upscale::GridStrainOutputOptions::enabled),
               "Write finite-strain measures per cell of the stress grid (F, L, J, ln J, E, e, Hencky "
               "strain, equivalent shear strain, D, W, R, increment from the previous evaluation; "
               "docs/strain.md), at the grid-stress evaluations and on their grid (Stress/grid cells and "
               "box). Needs Stress/formulas."),
       real("reference time", strain(&upscale::GridStrainOutputOptions::reference_time), 0.0, 1e6, "s",
            "t0, where F = 1: 0 = the initial state; otherwise the first grid-stress evaluation at or "
            "after t0 (no strain is written before it). The end of deposition cannot be the reference "
            "of a deposition run."),
       choice("set", strain(&upscale::GridStrainOutputOptions::kernel, &upscale::GridStrainOptions::set),
              {{"lagrangian", upscale::StrainSet::lagrangian}, {"eulerian", upscale::StrainSet::eulerian}},
              "Particles of a cell: lagrangian = those in the cell at t0 (on the grid of t0), followed by"
              " global id; eulerian = those in the cell now, with their positions at t0."),
       flags("definitions",
             {{"best fit",
               [](SceneInput& in) -> bool& {
                 return in.output.grid_strain.kernel
                     .definitions[static_cast<int>(upscale::StrainDefinition::best_fit)];
               }},
              {"tessellation",
               [](SceneInput& in) -> bool& {
                 return in.output.grid_strain.kernel
                     .definitions[static_cast<int>(upscale::StrainDefinition::tessellation)];
               }}},
             "How F and L are taken from a cell's particles: best fit = least-squares affine map; "
             "tessellation = volume average over the Delaunay tessellation of the centroids (Bagi 1996),"
             " comma-separated."),
       choice("rate formula", strain(&upscale::GridStrainOutputOptions::rate_formula),
              stress_formula_choices(),
              "Grid-stress formula whose cell series gives the Jaumann, Green-Naghdi, Truesdell and "
              "Oldroyd rates written with the strain (backward differences over the last outputs; "
              "docs/strain.md). Must be in Stress/formulas.")},
      nullptr};
  // The definitions, when strain is written; its needs of the Stress section are checked across
  // sections (scene_validation.cc).
  section.check = [](SceneInput& in, const std::string& where) {
    const upscale::GridStrainOutputOptions& st = in.output.grid_strain;
    if (st.enabled && !st.kernel.definitions[0] && !st.kernel.definitions[1])
      throw Error(where + "Strain/definitions is empty; name 'best fit', 'tessellation' or both");
  };
  return section;
}

}  // namespace upgrain::coupling::input
