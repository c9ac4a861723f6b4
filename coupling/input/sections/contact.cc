// The Contact section: friction, damping, rolling resistance, the ellipsoid contact solver, and the
// contact law with its own parameters from the law table (dem/contact/contact_laws.h).
#include <algorithm>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "dem/contact/contact_laws.h"

namespace upgrain::coupling::input {

namespace {

// Contact/law: a name of the law table, with each law's description in the entry's doc.
Entry law() {
  std::vector<std::pair<std::string, std::string>> names;
  std::string doc = "Contact law (docs/contact-law.md).";
  for (const dem::LawInfo& law : dem::contact_law_table()) {
    names.emplace_back(law.name, law.name);
    doc += std::string(" ") + law.name + ": " + law.description;
  }
  return choice("law", at(&SceneInput::scene, &dem::SceneConfig::contact_law), names, doc);
}

// A parameter of one or more laws, declared once (its default is the law table's): kept in
// SceneConfig::law_parameters when the scene's law declares it.
Entry law_parameter(const dem::LawParameter& p) {
  const std::string name = p.name;
  auto declares = [name](const std::string& law_name) {
    for (const dem::LawInfo& law : dem::contact_law_table())
      if (law.name == law_name)
        for (const dem::LawParameter& q : law.parameters)
          if (q.name == name) return true;
    return false;
  };
  return {p.name,
          Kind::real,
          p.min,
          p.max,
          "",
          p.unit,
          p.doc,
          [name, declares](SceneInput& in, const EntryValue& v, const std::string&) {
            if (declares(in.scene.contact_law))
              in.scene.law_parameters.push_back({name, std::get<double>(v)});
          },
          [name, fallback = std::string(p.default_value)](SceneInput& in) {
            for (const dem::NamedValue& v : in.scene.law_parameters)
              if (v.name == name) return format_real(v.value);
            return fallback;
          }};
}

}  // namespace

Section contact_section() {
  Section section{
      "Contact",
      {real("friction coefficient", at(&SceneInput::scene, &dem::SceneConfig::friction), 0.0, 10.0, "-",
            "Coulomb coefficient between particles."),
       real("damping ratio", at(&SceneInput::scene, &dem::SceneConfig::damping_ratio), 0.0, 10.0, "-",
            "zeta in c_n = 2 zeta sqrt(m* k_n) (paper eq. 21)."),
       real("rolling friction coefficient", at(&SceneInput::scene, &dem::SceneConfig::rolling_friction), 0.0,
            1.0, "-",
            "mu_r of the rolling resistance (Effects/rolling resistance): plastic limit mu_r R* F_n, "
            "rolling stiffness 2.25 k_n mu_r^2 R*^2. Particle-particle and particle-wall."),
       real("rolling damping ratio", at(&SceneInput::scene, &dem::SceneConfig::rolling_damping_ratio), 0.0,
            10.0, "-",
            "eta_r of the rolling dashpot C_r = eta_r 2 sqrt(I_r k_r), active below the plastic limit."),
       real("solver gradient tolerance",
            at(&SceneInput::scene, &dem::SceneConfig::contact_solver,
               &dem::ContactSolverSettings::gradient_tolerance),
            16.0, 1e12, "eps x size",
            "Ellipsoid contact solver: Newton stops when the gradient of the support-function gap is "
            "below this many machine epsilons times the pair's size (16: round-off; "
            "docs/ellipsoid-contact.md, \"Stopping rules\"). Scenes of spheres do not use it."),
       integer("solver iterations",
               at(&SceneInput::scene, &dem::SceneConfig::contact_solver,
                  &dem::ContactSolverSettings::max_iterations),
               1, 1000, "-",
               "Ellipsoid contact solver: Newton steps per start before it gives up (a warm start takes "
               "2-3; the force loop's straight-line path at most min(4, this)).")},
      nullptr};
  // The law, then every law's own parameters (read after it, so each knows the scene's law).
  section.entries.push_back(law());
  for (const dem::LawInfo& law : dem::contact_law_table())
    for (const dem::LawParameter& p : law.parameters) {
      const bool known = std::any_of(section.entries.begin(), section.entries.end(),
                                     [&](const Entry& e) { return e.name == p.name; });
      if (!known) section.entries.push_back(law_parameter(p));
    }
  return section;
}

}  // namespace upgrain::coupling::input
