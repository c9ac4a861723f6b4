#pragma once
// The exact reference of the contact-solver knobs (docs/accuracy.md): ellipsoid pairs of the
// scene's shapes and sizes placed in long double so that their depth and normal are known
// (dem/contact/ellipsoid_reference.h, docs/ellipsoid-contact.md "Verification"), solved by the
// force loop's two paths with the settings being judged: cold (a pair's first touch, the general
// solver) and warm (a persisting pair, from a normal one small rotation away, the straight-line
// path).
#include "dem/contact/contact_solver_settings.h"
#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

struct ContactSolverError {
  int pairs = 0;        // per path
  double depth = 0.0;   // largest |depth - exact| / c over both paths (c: the pair's smallest semi-axis)
  double normal = 0.0;  // largest angle between the normal and the exact one (rad)
  double cold_iterations = 0;  // mean Newton steps per cold solve
  double warm_iterations = 0;  // mean Newton steps per warm solve
  double cold_ns = 0.0;        // wall time per solve (ns), this machine, one thread
  double warm_ns = 0.0;
  long failures = 0;  // solves that did not converge (ContactSolverStats::failures)
};

// `pairs` constructed contacts per path, at depth `depth_over_c` times the smaller c, their
// shapes taken in turn from every pair of the scene's shapes with an ellipsoid, their major
// semi-axes uniform over the scene's radius range, body 1 1.5-2 m from the origin. The warm start
// is the exact normal turned by `warm_angle` (rad). Deterministic (a fixed seed).
ContactSolverError contact_solver_error(const dem::SceneConfig& scene,
                                        const dem::ContactSolverSettings& settings, int pairs = 2000,
                                        double depth_over_c = 1e-3, double warm_angle = 1e-4);

}  // namespace upgrain::coupling
