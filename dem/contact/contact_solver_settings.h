#pragma once
// The stopping rules of the ellipsoid contact solver (docs/ellipsoid-contact.md, "Stopping
// rules"): Newton on the unit sphere of normals stops when the tangential gradient of the
// support-function gap f is at round-off, or after a number of steps. Both are scene settings
// (Contact/solver gradient tolerance, Contact/solver iterations) so that the accuracy study
// (docs/accuracy.md) can measure what a looser solver saves and what it costs in depth error.
namespace upgrain::dem {

struct ContactSolverSettings {
  // Newton stops when |grad f| <= gradient_tolerance * eps * size, where eps is the double
  // precision's machine epsilon and size = |c1 - c2|_1 + a1 + a2 bounds every term of f and its
  // gradient: 16 is the round-off level of the gradient itself. The depth error left grows with
  // the square of this bound (f is stationary at the minimum).
  double gradient_tolerance = 16.0;
  // Newton steps per start of the general solver (a warm start takes 2-3); the force loop's
  // straight-line path gives up to the general solver after min(4, max_iterations).
  int max_iterations = 30;
};

}  // namespace upgrain::dem
