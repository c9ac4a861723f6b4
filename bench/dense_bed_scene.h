#pragma once
// The dense-bed benchmark scene and the settled-bed files that
// `bench_dense_bed settle` writes, shared by bench_dense_bed and bench_parallel_bed.
// Scene: r = 1.5 mm, 2,650 kg/m^3, E = 29 GPa, nu = 0.25, mu = 0.5 (particles and walls),
// zeta = 0.5, dt = 1e-6 s, gravity on, energy tracking off.
#include <fstream>
#include <optional>
#include <string>

#include "dem/core/particle_store.h"
#include "dem/scene/scene_config.h"

namespace upgrain::bench {

inline dem::SceneConfig benchmark_scene(double side) {
  dem::SceneConfig s;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 29e9, 0.25};
  s.container.lx = s.container.ly = side;
  s.friction = 0.5;
  s.damping_ratio = 0.5;
  s.time_step = 1e-6;
  s.neighbor_skin = 0.05;  // 0.1 diameters in total, as the LIGGGHTS deck
  s.effects.energy_tracking = false;
  return s;
}

struct Bed {
  dem::SceneConfig scene;
  dem::ParticleStore particles;
};

// Reads a bed written by `bench_dense_bed settle` (a LAMMPS/LIGGGHTS data file, ids from
// 1): the benchmark scene in the file's square box, particles at rest. Nothing if the file
// cannot be opened.
inline std::optional<Bed> read_bed(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::string line;
  long n = 0;
  double side = 0.0;
  while (std::getline(in, line)) {
    if (line.find("atoms") != std::string::npos) n = std::stol(line);
    if (line.find("xlo xhi") != std::string::npos) side = std::stod(line.substr(line.find(' ') + 1));
    if (line.rfind("Atoms", 0) == 0) break;
  }
  Bed bed{benchmark_scene(side), {}};
  bed.particles.reserve(static_cast<std::size_t>(n));
  long id, type;
  double d, rho, x, y, z;
  while (in >> id >> type >> d >> rho >> x >> y >> z)
    bed.particles.add_sphere(id - 1, 0.5 * d, rho, dem::Vec3(x, y, z), dem::Vec3::Zero(), dem::Vec3::Zero());
  return bed;
}

}  // namespace upgrain::bench
