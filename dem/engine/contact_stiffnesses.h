#pragma once
// The touching pairs of an engine's last recorded evaluation as the contact-stiffness tangent
// takes them (dem/stress/contact_tangent.h): branch, normal and the law's present normal and
// tangential stiffnesses. The geometry is the force loop's (sphere_pair_kinematics()), the
// stiffnesses the scene's law's own response at the pair's overlap (Hertz-Mindlin: k_n = 2 E* a,
// k_t = 8 G* a, a = sqrt(R* delta); Hooke: its constants), so the tangent sees the springs the
// engine used. Spheres only: an ellipsoid's curvature radii at the contact are the contact
// solver's, not recorded with the samples, and such a scene is refused.
#include <vector>

#include "dem/engine/simulation.h"
#include "dem/stress/contact_tangent.h"

namespace upgrain::dem {

// This rank's pairs whose first grain it owns (each pair once over the ranks), after a step that
// recorded contacts (a deforming cell records every step); wall contacts left out. Throws
// upgrain::Error when nothing was recorded or the grains have shapes. Not collective: a caller on
// more ranks sums the tangent over them.
[[nodiscard]] std::vector<ContactStiffness> contact_stiffnesses(const Simulation& sim);

}  // namespace upgrain::dem
