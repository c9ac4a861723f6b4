// The Continuum section: the continua solved beside the DEM, their material and mesh (docs/fem.md,
// docs/calibration.md).
#include <cmath>
#include <optional>
#include <sstream>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto continuum(Member m) {
  return at(&SceneInput::study, &StudyOptions::continuum, m);
}

// Continuum/wall friction and floor friction: "auto" (empty optional) or a Coulomb
// coefficient in [0, 10], the range of the Container's.
std::optional<double> friction_entry(const std::string& entry, const std::string& name,
                                     const std::string& where) {
  std::string text = entry;
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  if (text == "auto") return std::nullopt;
  std::istringstream in(text);
  double mu = 0.0;
  std::string rest;
  if (!(in >> mu) || (in >> rest) || !std::isfinite(mu) || mu < 0.0 || mu > 10.0)
    throw Error(where + "Continuum/" + name + " = '" + entry +
                "': give auto (the Container's coefficients) or a Coulomb coefficient in [0, 10]");
  return mu;
}

}  // namespace

Section continuum_section() {
  Section section{
      "Continuum",
      {real("youngs modulus", continuum(&ContinuumOptions::youngs_modulus), 1.0, 1e13, "Pa",
            "Young's modulus of every continuum (the stresses of the confined column do not depend on "
            "it, nor, without cohesion, those of the frictional continua; the displacements do)."),
       real("poisson ratio", continuum(&ContinuumOptions::poisson_ratio), 0.0, 0.499, "-",
            "Poisson's ratio of every continuum; it sets K0 = nu / (1 - nu), and the lateral ratio of "
            "the Janssen line."),
       choice("material from", continuum(&ContinuumOptions::material_from),
              {{"auto", ContinuumOptions::MaterialSource::automatic},
               {"calibration", ContinuumOptions::MaterialSource::calibration},
               {"entries", ContinuumOptions::MaterialSource::entries}},
              "Where the continua's youngs modulus, poisson ratio, friction angle and dilatancy angle "
              "come from. calibration: measured on the study's own bed after the DEM run, by the "
              "oedometric and friction-angle tests of docs/calibration.md (Calibration section; written "
              "to calibration/ in the output folder, their time in the report); entries: the Continuum "
              "entries as set; auto: calibration where those tests can load the bed (Hertz–Mindlin, a "
              "closed box, no Lid section), the entries otherwise. With a material file, leave it at "
              "auto: the file supplies the values it sets."),
       text("material file", continuum(&ContinuumOptions::material_file), "-",
            "A calibrated material file (calibration/material.prm of `upgrain --study calibration` or "
            "of an earlier study, docs/calibration.md) whose youngs modulus, poisson ratio, friction "
            "angle and dilatancy angle replace the entries of this section it sets; a relative path is "
            "taken from the scene file's folder. Empty: no file."),
       integer("refinements", continuum(&ContinuumOptions::refinements), 0, 6, "-",
               "Global refinements of the mesh whose coarse cells are the stress grid's cells."),
       integer("degree", continuum(&ContinuumOptions::degree), 1, 4, "-",
               "Polynomial degree of the displacement element (Q2 reproduces the analytic column exactly)."),
       subset("variants", continuum(&ContinuumOptions::variants),
              {{"elastic friction", ContinuumVariant::elastic_friction},
               {"drucker prager", ContinuumVariant::drucker_prager}},
              "Continua solved beside the elastic column on frictionless rollers (which always runs), "
              "each in a rigid box whose walls carry Coulomb friction ('wall friction', 'floor "
              "friction'): elastic friction is linear elastic, drucker prager elastoplastic with the "
              "strength below (docs/fem.md). Empty: the rollers column only."),
       text("wall friction", continuum(&ContinuumOptions::wall_friction_entry), "-",
            "Coulomb coefficient of the frictional continua's side walls: auto = each wall's Container "
            "coefficient as the DEM applies it (0 when Effects/wall friction is off), or one number in "
            "[0, 10] for all four."),
       text("floor friction", continuum(&ContinuumOptions::floor_friction_entry), "-",
            "Coulomb coefficient of the frictional continua's floor: auto = Container/floor friction as"
            " the DEM applies it, or a number in [0, 10]; 0 makes the floor a roller, as for the "
            "elastic column."),
       real("friction angle", continuum(&ContinuumOptions::friction_angle_deg), 0.1, 89.0, "degrees",
            "Mohr–Coulomb friction angle phi of the Drucker–Prager continuum."),
       real("dilatancy angle", continuum(&ContinuumOptions::dilatancy_angle_deg), 0.0, 89.0, "degrees",
            "Dilatancy angle psi of the Drucker–Prager continuum, at most the friction angle; psi = phi"
            " is associated flow."),
       real("cohesion", continuum(&ContinuumOptions::cohesion), 0.0, 1e9, "Pa",
            "Cohesion c of the Drucker–Prager continuum (the DEM's grains have none)."),
       choice("cone matching", continuum(&ContinuumOptions::cone_matching),
              {{"outer cone", fem::ConeMatching::outer},
               {"inner cone", fem::ConeMatching::inner},
               {"plane strain", fem::ConeMatching::plane_strain}},
              "How the Drucker–Prager cone is fitted to Mohr–Coulomb (phi, c): outer cone, through the "
              "triaxial-compression corners (exact for a column compressed axially, as at rest); inner "
              "cone, through the extension corners; plane strain, the same plane-strain collapse load "
              "(docs/fem.md)."),
       integer("load steps", continuum(&ContinuumOptions::load_steps), 1, 1000, "-",
               "Steps in which gravity is raised on the frictional continua, with Newton's method in each."
               " Without cohesion the answer does not depend on them (the problem is homogeneous in g; "
               "docs/fem.md)."),
       boolean("staged construction", continuum(&ContinuumOptions::staged_construction),
               "Build the frictional continua layer by layer (one layer of fine cells per step, each "
               "placed stress-free on the deformed column below) instead of raising gravity on the whole "
               "column; it changes the lateral stresses near the walls (docs/fem.md).")},
      nullptr};
  // The frictional continua's entries, against each other; when the scene's run compares with the
  // continuum.
  section.check = [](SceneInput& in, const std::string& where) {
    if (!compares_with_continuum(in)) return;
    ContinuumOptions& c = in.study.continuum;
    c.wall_friction = friction_entry(c.wall_friction_entry, "wall friction", where);
    c.floor_friction = friction_entry(c.floor_friction_entry, "floor friction", where);
    if (c.dilatancy_angle_deg > c.friction_angle_deg) {
      std::ostringstream m;
      m << where << "Continuum/dilatancy angle = " << c.dilatancy_angle_deg
        << " degrees exceeds Continuum/friction angle = " << c.friction_angle_deg
        << " degrees; a Drucker–Prager flow that dilates more than its friction allows is not admissible";
      throw Error(m.str());
    }
  };
  return section;
}

}  // namespace upgrain::coupling::input
