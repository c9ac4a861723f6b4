#include "coupling/studies/continuum/coarse_graining_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "upscale/cg/coarse_grained_fields.h"
#include "upscale/cg/state_distribution.h"

namespace upgrain::coupling {

namespace {

using upscale::cg::CoarseGrainedFields;
using upscale::cg::GrainState;
using upscale::cg::Vec3;

constexpr const char* kAxes[3] = {"x", "y", "z"};
constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

// The mean diameter of the grains' volume-equivalent spheres.
double mean_diameter(const GrainState& s) {
  double sum = 0.0;
  for (double v : s.volume) sum += std::cbrt(6.0 * v / std::numbers::pi);
  return s.grains() ? sum / static_cast<double>(s.grains()) : 0.0;
}

void add_vector(upscale::PointValues& out, const std::string& name, const std::vector<Vec3>& v) {
  for (int d = 0; d < 3; ++d) {
    out.names.push_back(name + "_" + kAxes[d]);
    std::vector<double> c(v.size());
    for (std::size_t q = 0; q < v.size(); ++q) c[q] = v[q][d];
    out.values.push_back(std::move(c));
  }
}

void add_tensor(upscale::PointValues& out, const std::string& prefix, const std::vector<upscale::cg::Mat3>& m,
                bool symmetric_part_only) {
  for (int e = 0; e < 9; ++e) {
    if (symmetric_part_only && e / 3 > e % 3) continue;
    out.names.push_back(prefix + kComponents[e]);
    std::vector<double> c(m.size());
    for (std::size_t q = 0; q < m.size(); ++q) c[q] = m[q](e / 3, e % 3);
    out.values.push_back(std::move(c));
  }
}

double largest_norm(const std::vector<Vec3>& v) {
  double x = 0.0;
  for (const Vec3& a : v) x = std::max(x, a.norm());
  return x;
}

}  // namespace

double CoarseGrainingOutcome::largest_level_spread() const {
  double s = 0.0;
  for (std::size_t l = 0; l < comparison.level_z.size(); ++l)
    if (comparison.level_z[l] < bed_top - cutoff) s = std::max(s, comparison.level_spread[l]);
  return s;
}

CoarseGrainingOutcome coarse_grain_on_mesh(const SceneInput& in, const RunResult& r,
                                           const fem::ColumnProblem& problem, const fem::ColumnSolution& sol,
                                           MPI_Comm comm, const std::filesystem::path& folder) {
  const auto t0 = std::chrono::steady_clock::now();
  const CoarseGrainingOptions& o = in.study.coarse_graining;
  CoarseGrainingOutcome out;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const CapturedStates& states = r.coarse_graining;
  const GrainState empty;
  const GrainState& whole = rank == 0 && states.final_state ? *states.final_state : empty;
  const GrainState& later = rank == 0 && states.later_state ? *states.later_state : empty;
  double figures[6] = {mean_diameter(whole),
                       states.sampling_interval,
                       static_cast<double>(whole.grains()),
                       static_cast<double>(whole.branches()),
                       static_cast<double>(whole.wall_contacts()),
                       r.bed.surface_height};
  MPI_Bcast(figures, 6, MPI_DOUBLE, 0, comm);
  out.diameter = figures[0];
  out.sampling_interval = figures[1];
  out.grains = std::lround(figures[2]);
  out.branches = std::lround(figures[3]);
  out.wall_contacts = std::lround(figures[4]);
  out.bed_top = figures[5];
  out.width_in_diameters = o.width;
  out.width = o.width * out.diameter;
  const upscale::cg::KernelChoice kernel{o.kernel, out.width};
  out.kernel = std::string(upscale::cg::name_of(o.kernel));
  out.cutoff = upscale::cg::cutoff_of(kernel);
  out.points = o.at_quadrature_points ? "quadrature points" : "support points";
  const bool differences = o.by_differences;

  auto evaluate = [&](const std::vector<std::array<double, 3>>& at) {
    std::vector<Vec3> points(at.size());
    for (std::size_t q = 0; q < at.size(); ++q) points[q] = Vec3(at[q][0], at[q][1], at[q][2]);
    const GrainState part = upscale::cg::state_for_points(whole, points, out.cutoff, comm);
    const CoarseGrainedFields f = upscale::cg::coarse_grain(part, points, kernel);
    std::vector<Vec3> by_differences;
    if (differences) {
      const GrainState part_later = upscale::cg::state_for_points(later, points, out.cutoff, comm);
      by_differences = upscale::cg::residual_by_differences(
          f, upscale::cg::coarse_grain(part_later, points, kernel), out.sampling_interval);
    }
    double weight = 0.0;
    for (std::size_t q = 0; q < points.size(); ++q)
      weight = std::max(weight, (f.density[q] * part.gravity).norm());
    double figure[4] = {largest_norm(f.residual), largest_norm(f.momentum_rate),
                        differences ? largest_norm(by_differences) : 0.0, weight};
    MPI_Allreduce(MPI_IN_PLACE, figure, 4, MPI_DOUBLE, MPI_MAX, comm);
    out.residual = figure[0] / figure[3];
    out.momentum_rate = figure[1] / figure[3];
    out.residual_by_differences =
        differences ? figure[2] / figure[3] : std::numeric_limits<double>::quiet_NaN();

    upscale::PointValues v;
    add_tensor(v, "s_", f.stress, false);
    if (o.density) {
      v.names.insert(v.names.end(), {"density", "volume_fraction"});
      v.values.push_back(f.density);
      v.values.push_back(f.volume_fraction);
    }
    if (o.velocity) {
      add_vector(v, "velocity", f.velocity);
      add_vector(v, "momentum", f.momentum);
    }
    if (o.stress) add_tensor(v, "kinetic_s_", f.kinetic_stress, true);
    if (o.wall_force_density) add_vector(v, "wall_force_density", f.wall_force_density);
    if (o.displacement) {
      add_vector(v, "displacement", f.displacement);
      add_tensor(v, "displacement_gradient_", f.displacement_gradient, false);
    }
    if (o.momentum_balance) {
      add_vector(v, "residual", differences ? by_differences : f.residual);
      add_vector(v, "momentum_rate", f.momentum_rate);
    }
    return v;
  };

  upscale::MeshBox mesh;
  mesh.lo = {0.0, 0.0, 0.0};
  mesh.hi = {problem.length_x, problem.length_y, problem.height};
  mesh.cells = problem.cells;
  mesh.refinements = problem.refinements;
  mesh.degree = problem.degree;
  const fem::QuadratureStress& q = sol.quadrature_stress;
  const upscale::StressAtPoints continuum{q.x, q.weight, q.sigma};
  out.comparison = upscale::write_point_fields_on_mesh(
      mesh, o.at_quadrature_points ? upscale::MeshPoints::quadrature : upscale::MeshPoints::support,
      continuum, evaluate, comm, folder / "mesh", "cg_fields", r.simulated_time, r.steps);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.done = true;
  return out;
}

}  // namespace upgrain::coupling
