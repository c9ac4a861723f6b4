// The Particles section: the grains of the fill (count, size, gradation, shapes) or an initial
// packing, and their material.
#include <sstream>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "dem/scene/gradation.h"
#include "dem/scene/grain_shape.h"

namespace upgrain::coupling::input {

namespace {

template <class... Members>
auto particles(Members... m) {
  return at(&SceneInput::scene, &dem::SceneConfig::particles, m...);
}

std::vector<dem::GradationPoint> parse_gradation(const std::string& text) {
  std::vector<dem::GradationPoint> curve;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto colon = item.find(':');
    dem::GradationPoint p{};
    std::istringstream r(colon == std::string::npos ? "" : item.substr(0, colon));
    std::istringstream f(colon == std::string::npos ? "" : item.substr(colon + 1));
    std::string rest_r, rest_f;
    if (colon == std::string::npos || !(r >> p.radius) || (r >> rest_r) || !(f >> p.fraction_passing) ||
        (f >> rest_f))
      throw Error("Particles/gradation: cannot read the point '" + item +
                  "'; write 'radius:fraction passing' pairs separated by commas, e.g. '1e-3:0, 2.5e-3:1'");
    curve.push_back(p);
  }
  return curve;
}

// "1:0.8:0.6@0.5, 1:0.6:0.4" -> shapes, each read by its row of the shape table.
std::vector<dem::GrainShape> parse_shapes(const std::string& text) {
  std::vector<dem::GrainShape> shapes;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    try {
      shapes.push_back(dem::read_grain_shape(item));
    } catch (const Error& e) {
      throw Error(std::string("Particles/shapes: ") + e.what());
    }
  }
  return shapes;
}

Entry gradation(std::string doc) {
  return {"gradation",
          Kind::text,
          0,
          0,
          "",
          "m : -",
          std::move(doc),
          [](SceneInput& in, const EntryValue& v, const std::string&) {
            in.scene.particles.gradation = parse_gradation(std::get<std::string>(v));
          },
          [](SceneInput& in) {
            std::vector<std::string> points;
            for (const dem::GradationPoint& p : in.scene.particles.gradation)
              points.push_back(format_real(p.radius) + ":" + format_real(p.fraction_passing));
            return join(points);
          }};
}

Entry shapes(std::string doc) {
  return {"shapes",
          Kind::text,
          0,
          0,
          "",
          "-",
          std::move(doc),
          [](SceneInput& in, const EntryValue& v, const std::string&) {
            in.scene.particles.shapes = parse_shapes(std::get<std::string>(v));
          },
          [](SceneInput& in) {
            std::vector<std::string> items;
            for (const dem::GrainShape& s : in.scene.particles.shapes)
              items.push_back(dem::format_grain_shape(s, format_real) + "@" + format_real(s.number_fraction));
            return join(items);
          }};
}

}  // namespace

Section particles_section() {
  Section section{
      "Particles",
      {integer("count", particles(&dem::ParticleSpec::count), 0, 1e9, "-",
               "Number of grains of the initial fill (0: an empty container, for a pour: Insertion/count)."),
       real("radius", particles(&dem::ParticleSpec::radius), 1e-9, 10.0, "m",
            "Radius of monodisperse spheres (used when 'gradation' is empty)."),
       gradation("Gradation curve as comma-separated 'radius:fraction passing' points by mass, e.g. "
                 "'1.0e-3:0, 1.5e-3:0.4, 2.5e-3:1'. Empty: monodisperse."),
       shapes("Grain shapes as comma-separated aspect ratios 1:b/a:c/a, each with an optional number "
              "fraction after '@' (equal shares without), e.g. '1:1:1, 1:0.8:0.6, 1:0.8:0.4, 1:0.6:0.4' "
              "(Yan and Regueiro's four, docs/ellipsoids.md). Empty: spheres. The radius (or gradation) is "
              "each grain's major "
              "semi-axis a; orientations are uniformly random."),
       text("initial packing", at(&SceneInput::initial_packing), "-",
            "Start from the grains of this file instead of a fill: a text table (CSV or whitespace; "
            "columns id, x, y, z, r or d or a, b, c, optional qw, qx, qy, qz, vx, vy, vz, wx, wy, wz), "
            "a LAMMPS/LIGGGHTS data file (atom_style sphere or granular) or an Upgrain snapshot (HDF5)."
            " A relative path starts at the scene file's folder. count, radius, gradation, shapes and "
            "the Fill section are then not used; the grains take this section's material. Empty: fill "
            "the container (docs/input.md)."),
       real("density", particles(&dem::ParticleSpec::material, &dem::Material::density), 1.0, 1e5, "kg/m^3",
            "Grain density (specific gravity 2.65 in Yan and Regueiro's beds, docs/stress.md)."),
       real("youngs modulus", particles(&dem::ParticleSpec::material, &dem::Material::youngs_modulus), 1e3,
            1e13, "Pa", "Young's modulus of the grains and walls."),
       real("poisson ratio", particles(&dem::ParticleSpec::material, &dem::Material::poisson_ratio), 0.0,
            0.49, "-", "Poisson's ratio of the grains and walls.")},
      nullptr};
  section.check = [](SceneInput& in, const std::string& where) {
    const dem::ParticleSpec& p = in.scene.particles;
    try {
      if (!p.gradation.empty()) dem::validate_gradation(p.gradation);
    } catch (const Error& e) {
      throw Error(where + "Particles/gradation: " + e.what());
    }
    try {
      dem::validate_shapes(p.shapes);
    } catch (const Error& e) {
      throw Error(where + "Particles/shapes: " + e.what());
    }
  };
  return section;
}

}  // namespace upgrain::coupling::input
