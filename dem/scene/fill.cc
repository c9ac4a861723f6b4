#include "dem/scene/fill.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "dem/core/error.h"
#include "dem/neighbor/cell_grid.h"
#include "dem/scene/gradation.h"

namespace upgrain::dem {

namespace {

struct LatticeShape {
  double pitch, margin_x, margin_y;
  long nx, ny, layers;
};

LatticeShape lattice_shape(const SceneConfig& s, double r_max) {
  LatticeShape l{};
  l.pitch = s.fill.lattice_spacing * 2.0 * r_max;
  const double gap = l.pitch - 2.0 * r_max;
  const double usable_x = s.container.fill_length_x() - 2.0 * r_max - gap;
  const double usable_y = s.container.ly - 2.0 * r_max - gap;
  l.nx = usable_x >= 0.0 ? static_cast<long>(std::floor(usable_x / l.pitch)) + 1 : 0;
  l.ny = usable_y >= 0.0 ? static_cast<long>(std::floor(usable_y / l.pitch)) + 1 : 0;
  if (l.nx < 1 || l.ny < 1) {
    std::ostringstream m;
    m << "Fill: the container (" << s.container.fill_length_x() << " x " << s.container.ly
      << " m) is narrower than one lattice pitch (" << l.pitch << " m)";
    throw Error(m.str());
  }
  l.margin_x = 0.5 * (s.container.fill_length_x() - (l.nx - 1) * l.pitch);
  l.margin_y = 0.5 * (s.container.ly - (l.ny - 1) * l.pitch);
  l.layers = (s.particles.count + l.nx * l.ny - 1) / (l.nx * l.ny);
  return l;
}

double random_fill_height(const SceneConfig& s, const std::vector<double>& radii) {
  double volume = 0.0;
  for (double r : radii) volume += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double r_max = *std::max_element(radii.begin(), radii.end());
  return std::max(volume / (s.fill.solid_fraction * s.container.fill_length_x() * s.container.ly),
                  2.0 * r_max);
}

}  // namespace

FillPlan plan_fill(const SceneConfig& s) {
  FillPlan plan;
  if (s.particles.packing) {
    // The grains of an initial packing, as they lie.
    const ParticleStore& p = *s.particles.packing;
    plan.radii = p.radius;
    for (std::size_t i = 0; i < p.size(); ++i)
      plan.top = std::max(plan.top, p.x[i].z() + p.reach(i, Vec3::UnitZ()));
    return plan;
  }
  // An empty container is for a pour to fill (docs/insertion.md).
  if (s.particles.count == 0 && s.insertion.enabled()) return plan;
  if (s.particles.count < 1) throw Error("Particles/count must be at least 1 (or 0 with an Insertion/count)");
  if (s.particles.gradation.empty()) {
    plan.radii.assign(static_cast<std::size_t>(s.particles.count), s.particles.radius);
  } else {
    std::mt19937_64 rng(s.fill.seed);
    plan.radii = sample_radii(s.particles.gradation, s.particles.count, rng);
  }
  const double r_max = *std::max_element(plan.radii.begin(), plan.radii.end());
  if (s.fill.method == FillMethod::lattice) {
    const LatticeShape l = lattice_shape(s, r_max);
    plan.top = s.fill.bottom_gap + 2.0 * r_max + (l.layers - 1) * l.pitch +
               s.fill.position_jitter * (l.pitch - 2.0 * r_max);
  } else {
    plan.top = s.fill.bottom_gap + random_fill_height(s, plan.radii);
  }
  return plan;
}

double fill_top_height(const SceneConfig& s) { return plan_fill(s).top; }

ParticleStore fill_container(const SceneConfig& s) {
  if (s.particles.packing) return *s.particles.packing;
  const FillPlan plan = plan_fill(s);
  if (plan.radii.empty()) return {};
  const std::vector<double>& radii = plan.radii;
  const double r_max = *std::max_element(radii.begin(), radii.end());
  const double density = s.particles.material.density;
  // A separate stream for positions and velocities, so radii do not depend on the fill.
  std::mt19937_64 rng(s.fill.seed ^ 0x5bd1e995ULL);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto velocity = [&]() {
    Vec3 v = s.fill.velocity;
    if (s.fill.velocity_jitter > 0.0) v += s.fill.velocity_jitter * Vec3(u(rng), u(rng), u(rng));
    return v;
  };

  ParticleStore p;
  p.reserve(radii.size());
  const long n = static_cast<long>(radii.size());
  // Shapes and orientations from a stream of their own: the positions and velocities of a
  // scene do not change when its shapes do.
  std::mt19937_64 shape_rng(s.fill.seed ^ 0x9e3779b97f4a7c15ULL);
  const std::vector<GrainShape>& shapes = s.particles.shapes;
  const bool shaped = has_shapes(shapes);
  const std::vector<int> shape_of = assign_shapes(shapes, n, shape_rng);
  auto add = [&](long k, const Vec3& x) {
    if (!shaped) {
      p.add_sphere(k, radii[k], density, x, velocity(), Vec3::Zero());
      return;
    }
    // A sphere in a mixed scene draws an orientation too, so the stream does not depend on
    // which grains are spheres.
    const Eigen::Quaterniond q = random_orientation(shape_rng);
    add_grain(p, shapes[shape_of[k]], k, radii[k], density, q, {x, velocity(), Vec3::Zero()});
  };
  if (s.fill.method == FillMethod::lattice) {
    const LatticeShape l = lattice_shape(s, r_max);
    const double gap = l.pitch - 2.0 * r_max;
    const double jitter = 0.5 * s.fill.position_jitter * gap;
    for (long k = 0; k < n; ++k) {
      const long layer = k / (l.nx * l.ny);
      const long in_layer = k % (l.nx * l.ny);
      Vec3 x(l.margin_x + (in_layer % l.nx) * l.pitch, l.margin_y + (in_layer / l.nx) * l.pitch,
             s.fill.bottom_gap + r_max + jitter + layer * l.pitch);
      if (jitter > 0.0) x += jitter * Vec3(u(rng), u(rng), u(rng));
      add(k, x);
    }
    return p;
  }

  // Random sequential addition, largest grains first, against a cell grid of the grains
  // already placed.
  const double height = random_fill_height(s, radii);
  const Vec3 lo(0.0, 0.0, s.fill.bottom_gap);
  const Vec3 hi(s.container.fill_length_x(), s.container.ly, s.fill.bottom_gap + height);
  CellGrid grid(lo, hi, 2.0 * r_max);
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(grid.num_cells()));
  std::vector<long> order(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](long a, long b) { return radii[a] > radii[b]; });
  std::vector<Vec3> pos(static_cast<std::size_t>(n));
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  constexpr int kMaxAttempts = 2000;
  const auto& dims = grid.dims();
  for (long k : order) {
    const double r = radii[k];
    bool placed = false;
    for (int attempt = 0; attempt < kMaxAttempts && !placed; ++attempt) {
      const Vec3 x(r + (s.container.fill_length_x() - 2 * r) * u01(rng),
                   r + (s.container.ly - 2 * r) * u01(rng), lo.z() + r + (height - 2 * r) * u01(rng));
      const auto c = grid.cell_coords(x);
      bool free = true;
      for (int z = std::max(c[2] - 1, 0); free && z <= std::min(c[2] + 1, dims[2] - 1); ++z)
        for (int y = std::max(c[1] - 1, 0); free && y <= std::min(c[1] + 1, dims[1] - 1); ++y)
          for (int xx = std::max(c[0] - 1, 0); free && xx <= std::min(c[0] + 1, dims[0] - 1); ++xx)
            for (int other : cells[grid.flat(xx, y, z)]) {
              const double d = r + radii[other];
              if ((pos[other] - x).squaredNorm() < d * d) {
                free = false;
                break;
              }
            }
      if (free) {
        pos[k] = x;
        cells[grid.flat(c[0], c[1], c[2])].push_back(static_cast<int>(k));
        placed = true;
      }
    }
    if (!placed) {
      std::ostringstream m;
      m << "Fill: could not place particle " << k << " (radius " << r << " m) without overlap in "
        << kMaxAttempts << " attempts; lower Fill/solid fraction (now " << s.fill.solid_fraction
        << ") or use the lattice fill";
      throw Error(m.str());
    }
  }
  for (long k = 0; k < n; ++k) add(k, pos[k]);
  return p;
}

}  // namespace upgrain::dem
