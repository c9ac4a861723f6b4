#include "dem/scene/insertion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "dem/core/error.h"
#include "dem/neighbor/cell_grid.h"
#include "dem/scene/gradation.h"
#include "dem/scene/grain_shape.h"

namespace upgrain::dem {

namespace {

// SplitMix64 (Steele, Lea and Flood 2014): a seed per batch from the scene's and the batch
// index, so that neighbouring batches draw unrelated streams.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::string vec(const Vec3& v) {
  std::ostringstream m;
  m << v.x() << ", " << v.y() << ", " << v.z();
  return m.str();
}

}  // namespace

void validate_insertion(const SceneConfig& s) {
  const InsertionSpec& in = s.insertion;
  if (in.count < 0)
    throw Error("Insertion/count = " + std::to_string(in.count) + " must be >= 0 (0: no insertion)");
  if (!in.enabled()) return;
  std::ostringstream m;
  m << "Insertion: ";
  if (!(in.rate > 0.0) && !(in.mass_rate > 0.0)) {
    m << "Insertion/rate = " << in.rate << " grains/s and Insertion/mass rate = " << in.mass_rate
      << " kg/s: give a rate > 0 (grains per second) or a mass rate > 0 (kg per second)";
    throw Error(m.str());
  }
  if (in.rate > 0.0 && in.mass_rate > 0.0) {
    m << "Insertion/rate = " << in.rate << " grains/s and Insertion/mass rate = " << in.mass_rate
      << " kg/s are both set; give one of them (the other 0)";
    throw Error(m.str());
  }
  if (!(in.interval >= s.time_step)) {
    m << "Insertion/interval = " << in.interval << " s is shorter than one time step (" << s.time_step
      << " s)";
    throw Error(m.str());
  }
  if (!(in.start_time >= 0.0) || in.start_time >= s.end_time) {
    m << "Insertion/start time = " << in.start_time
      << " s must lie in [0, Simulation/end time = " << s.end_time << " s)";
    throw Error(m.str());
  }
  if (!in.velocity.allFinite()) throw Error("Insertion/velocity is not finite");
  const Vec3 lo = in.inlet_lo, hi = in.inlet_hi;
  const Vec3 room(s.container.fill_length_x(), s.container.ly, 0.0);
  for (int d = 0; d < 3; ++d) {
    const bool outside = lo[d] < 0.0 || (d < 2 && hi[d] > room[d]);
    if (outside || !(hi[d] > lo[d])) {
      m << "the inlet (Insertion/inlet min = " << vec(lo) << ", inlet max = " << vec(hi) << " m) ";
      if (!(hi[d] > lo[d]))
        m << "is empty along "
          << "xyz"[d] << ": inlet max must exceed inlet min";
      else
        m << "is outside the container along "
          << "xyz"[d] << " (x in [0, " << room.x() << "], y in [0, " << room.y() << "], z >= 0 m"
          << (s.container.has_gate() ? ", behind the gate" : "") << ")";
      throw Error(m.str());
    }
  }
  const double r_max = s.particles.largest_radius();
  const double narrowest = (hi - lo).minCoeff();
  if (narrowest < 2.0 * r_max) {
    m << "the inlet (Insertion/inlet min = " << vec(lo) << ", inlet max = " << vec(hi) << " m) is "
      << narrowest << " m across at its narrowest, too small for one grain of the largest diameter "
      << 2.0 * r_max << " m";
    throw Error(m.str());
  }
  const InletLoad load = inlet_load(s);
  if (load.batch > kBatchFillLimit) {
    m.precision(3);
    m << "a batch (" << load.grains_per_batch
      << " grains: the rate times Insertion/interval = " << in.interval << " s) fills " << load.batch
      << " of the inlet's volume " << (hi - lo).prod()
      << " m^3; random placement jams near 0.38 and takes at most " << kBatchFillLimit
      << "; enlarge the inlet or shorten the interval";
    throw Error(m.str());
  }
}

InletLoad inlet_load(const SceneConfig& s) {
  const InsertionSpec& in = s.insertion;
  InletLoad load;
  if (!in.enabled()) return load;
  // The volume the first batch brings against the inlet's.
  const PourPlan plan = plan_pour(s);
  load.grains_per_batch = std::max(1L, grains_due(in, plan, 0));
  double volume = 0.0;
  for (long k = 0; k < load.grains_per_batch && k < static_cast<long>(plan.radius.size()); ++k)
    volume += plan.cumulative_mass[k] - (k > 0 ? plan.cumulative_mass[k - 1] : 0.0);
  volume /= s.particles.material.density;
  const Vec3 size = in.inlet_hi - in.inlet_lo;
  load.batch = volume / size.prod();
  // How long a grain placed at the inlet's top takes to fall out of it: h = v t + g t^2 / 2
  // with v the downward speed; the batches of that time lie in the inlet together.
  const double g = s.effects.gravity ? s.gravity : 0.0;
  const double v = std::max(0.0, -in.velocity.z());
  const double h = size.z();
  const double t = g > 0.0   ? (std::sqrt(v * v + 2.0 * g * h) - v) / g
                   : v > 0.0 ? h / v
                             : std::numeric_limits<double>::infinity();
  load.held = load.batch * (1.0 + std::floor(t / in.interval));
  return load;
}

PourPlan plan_pour(const SceneConfig& s) {
  const InsertionSpec& in = s.insertion;
  PourPlan plan;
  if (!in.enabled()) return plan;
  // Streams of their own, apart from the fill's (fill.cc): the initial grains do not change
  // when a pour is added.
  std::mt19937_64 radii_rng(mix(s.fill.seed ^ 0x706f7572ULL));
  if (s.particles.gradation.empty())
    plan.radius.assign(static_cast<std::size_t>(in.count), s.particles.radius);
  else
    plan.radius = sample_radii(s.particles.gradation, in.count, radii_rng);
  const std::vector<GrainShape>& shapes = s.particles.shapes;
  if (!shapes.empty()) {
    std::mt19937_64 shape_rng(mix(s.fill.seed ^ 0x73686170ULL));
    plan.shape = assign_shapes(shapes, in.count, shape_rng);
  }
  plan.cumulative_mass.resize(plan.radius.size());
  double total = 0.0;
  for (std::size_t k = 0; k < plan.radius.size(); ++k) {
    const double a = plan.radius[k];
    const GrainShape g = shapes.empty() ? GrainShape{} : shapes[static_cast<std::size_t>(plan.shape[k])];
    total += s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * a * a * a * scales(g).volume;
    plan.cumulative_mass[k] = total;
    plan.largest_radius = std::max(plan.largest_radius, a);
  }
  return plan;
}

long grains_due(const InsertionSpec& in, const PourPlan& plan, long batch) {
  const double elapsed = static_cast<double>(batch + 1) * in.interval;
  if (in.mass_rate > 0.0) {
    // Grain k is due once the mass allowed reaches the middle of its own.
    const double allowed = in.mass_rate * elapsed;
    long n = 0;
    const long count = static_cast<long>(plan.cumulative_mass.size());
    while (n < count) {
      const double before = n > 0 ? plan.cumulative_mass[n - 1] : 0.0;
      if (0.5 * (before + plan.cumulative_mass[n]) > allowed) break;
      ++n;
    }
    return n;
  }
  return std::min(in.count, static_cast<long>(std::floor(in.rate * elapsed + 0.5)));
}

double last_batch_time(const SceneConfig& s, const PourPlan& plan) {
  const InsertionSpec& in = s.insertion;
  long b = 0;
  while (grains_due(in, plan, b) < in.count) ++b;
  return in.start_time + static_cast<double>(b) * in.interval;
}

std::uint64_t batch_seed(const SceneConfig& s, long batch) {
  return mix(mix(s.fill.seed ^ 0x696e6c6574ULL) + static_cast<std::uint64_t>(batch));
}

std::vector<Vec3> place_in_inlet(const Box& inlet, std::span<const double> radii,
                                 std::span<const BoundingSphere> obstacles, std::uint64_t seed,
                                 int attempts) {
  std::vector<Vec3> placed;
  if (radii.empty()) return placed;
  double r_max = *std::max_element(radii.begin(), radii.end());
  for (const BoundingSphere& o : obstacles) r_max = std::max(r_max, o.radius);
  // Cells of a largest diameter: two bounding spheres that overlap lie in the same or adjacent
  // cells. Obstacles outside the box are clamped into its border cells, where they stay
  // adjacent to the candidates they can touch (cell_grid.h).
  const CellGrid grid(inlet.lo, inlet.hi, 2.0 * r_max);
  std::vector<std::vector<BoundingSphere>> cells(static_cast<std::size_t>(grid.num_cells()));
  for (const BoundingSphere& o : obstacles)
    cells[static_cast<std::size_t>(grid.cell_index(o.x))].push_back(o);
  const auto& dims = grid.dims();
  auto free = [&](const Vec3& x, double r) {
    const auto c = grid.cell_coords(x);
    for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
        for (int xx = std::max(c[0] - 1, 0); xx <= std::min(c[0] + 1, dims[0] - 1); ++xx)
          for (const BoundingSphere& o : cells[static_cast<std::size_t>(grid.flat(xx, y, z))]) {
            const double d = r + o.radius;
            if ((o.x - x).squaredNorm() < d * d) return false;
          }
    return true;
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (const double r : radii) {
    const Vec3 lo = inlet.lo + Vec3::Constant(r), span = inlet.hi - inlet.lo - Vec3::Constant(2.0 * r);
    if ((span.array() < 0.0).any()) return placed;
    bool found = false;
    for (int a = 0; a < attempts && !found; ++a) {
      const Vec3 x(lo.x() + span.x() * u01(rng), lo.y() + span.y() * u01(rng), lo.z() + span.z() * u01(rng));
      if (!free(x, r)) continue;
      placed.push_back(x);
      cells[static_cast<std::size_t>(grid.cell_index(x))].push_back({x, r});
      found = true;
    }
    if (!found) return placed;
  }
  return placed;
}

}  // namespace upgrain::dem
