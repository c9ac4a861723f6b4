#include "coupling/studies/accuracy/contact_solver_reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/ellipsoid_reference.h"

namespace upgrain::coupling {

namespace ref = dem::reference;

ContactSolverError contact_solver_error(const dem::SceneConfig& scene,
                                        const dem::ContactSolverSettings& settings, int pairs,
                                        double depth_over_c, double warm_angle) {
  const std::vector<dem::GrainShape>& shapes = scene.particles.shapes;
  std::vector<std::pair<dem::Vec3, dem::Vec3>> kinds;
  // The semi-axes over a of each shape the reference constructs: the ellipsoid's, and the
  // sphere's as the ellipsoid of equal axes (another shape's contacts have references of their own).
  auto axes = [](const dem::GrainShape& g) -> std::optional<dem::Vec3> {
    if (g.is_sphere()) return dem::Vec3::Ones();
    if (g.kind == dem::ShapeKind::ellipsoid) return dem::Vec3(1.0, g.ratios[0], g.ratios[1]);
    return std::nullopt;
  };
  for (std::size_t i = 0; i < shapes.size(); ++i)
    for (std::size_t j = i; j < shapes.size(); ++j)
      if (!(shapes[i].is_sphere() && shapes[j].is_sphere()) && axes(shapes[i]) && axes(shapes[j]))
        kinds.emplace_back(*axes(shapes[i]), *axes(shapes[j]));
  ContactSolverError e;
  if (kinds.empty() || pairs < 1) return e;
  std::mt19937_64 rng(20261203);
  std::vector<ref::ConstructedPair> cases;
  std::vector<dem::Vec3> starts;
  const double a_min = scene.particles.smallest_radius(), a_max = scene.particles.largest_radius();
  for (int k = 0; k < pairs; ++k) {
    const auto& [r1, r2] = kinds[static_cast<std::size_t>(k) % kinds.size()];
    cases.push_back(ref::constructed_pair(rng, r1, r2, ref::Orientation::random, depth_over_c, a_min, a_max));
    // The warm start: the exact normal turned by warm_angle about a random axis across it.
    const dem::Vec3 n = cases.back().normal.cast<double>().normalized();
    const dem::Vec3 axis = n.cross(ref::random_unit(rng)).normalized();
    starts.push_back(Eigen::AngleAxisd(warm_angle, axis) * n);
  }
  std::vector<dem::PosedEllipsoid> posed;
  for (const ref::ConstructedPair& c : cases) {
    posed.push_back(dem::PosedEllipsoid::from(c.e1));
    posed.push_back(dem::PosedEllipsoid::from(c.e2));
  }
  std::vector<dem::PairContact> cold(cases.size()), warm(cases.size());
  dem::ContactSolverStats cold_stats, warm_stats;
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  for (std::size_t k = 0; k < cases.size(); ++k)
    dem::posed_contact(posed[2 * k], posed[2 * k + 1], nullptr, true, settings, cold_stats, cold[k]);
  const auto t1 = clock::now();
  for (std::size_t k = 0; k < cases.size(); ++k)
    dem::posed_contact(posed[2 * k], posed[2 * k + 1], &starts[k], false, settings, warm_stats, warm[k]);
  const auto t2 = clock::now();
  e.pairs = pairs;
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (const dem::PairContact* c : {&cold[k], &warm[k]}) {
      const double depth = static_cast<double>(std::abs(static_cast<ref::Real>(c->depth) - cases[k].depth));
      e.depth = std::max(e.depth, depth / cases[k].c_min);
      e.normal = std::max(e.normal, static_cast<double>(ref::angle(c->normal, cases[k].normal)));
    }
  e.cold_iterations = static_cast<double>(cold_stats.newton_iterations) / pairs;
  e.warm_iterations = static_cast<double>(warm_stats.newton_iterations) / pairs;
  e.cold_ns = std::chrono::duration<double, std::nano>(t1 - t0).count() / pairs;
  e.warm_ns = std::chrono::duration<double, std::nano>(t2 - t1).count() / pairs;
  e.failures = cold_stats.failures + warm_stats.failures;
  return e;
}

}  // namespace upgrain::coupling
