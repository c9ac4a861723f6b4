#pragma once
// Sphere-sphere contact geometry in closed form: the normal along the line of centres, the
// overlap r_i + r_j - |x_j - x_i|, the contact point midway in the overlap, and the effective
// radius r_i r_j / (r_i + r_j) (Johnson 1985, sec. 4.2). The force loop evaluates it inline, as
// every scene's most frequent pair.
#include <cmath>
#include <cstddef>

#include "dem/contact/contact_kinematics.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem {

// What the force loop keeps of two touching spheres besides their kinematics: the lever
// lengths along the normal (the torques are n x F scaled by them) and the effective radius.
struct SpherePairArms {
  double arm_i;   // r_i - delta/2
  double arm_j;   // r_j - delta/2
  double r_star;  // r_i r_j / (r_i + r_j)
};

// The geometry of two touching spheres (the force loops' sphere pairs): d = x_j - x_i with
// |d|^2 = dist2 < (r_i + r_j)^2. Sets the normal (i to j), overlap and levers of `kin`.
[[gnu::always_inline]] inline SpherePairArms sphere_pair_kinematics(const Vec3& d, double dist2, double ri,
                                                                    double rj, ContactKinematics& kin) {
  const double rsum = ri + rj;
  const double dist = std::sqrt(dist2);
  const double delta = rsum - dist;
  kin.normal = d * (1.0 / dist);
  kin.overlap = delta;
  const SpherePairArms a{ri - 0.5 * delta, rj - 0.5 * delta, ri * rj / rsum};
  kin.lever_i = a.arm_i * kin.normal;
  kin.lever_j = -a.arm_j * kin.normal;
  return a;
}

// The sphere-sphere row of the pair-geometry table (pair_geometries.h): closed form, evaluated
// in the force pass itself.
struct SpherePair {
  static constexpr bool closed_form = true;
  static constexpr const char* name = "sphere-sphere, closed form";

  // Grains i and j of `p` outside the force loop (body 1 is i, j moved by shift_j;
  // pair_contact()).
  static ContactGeometry contact(const ParticleStore& p, std::size_t i, std::size_t j, const Vec3& shift_j,
                                 ContactSolverStats&) {
    return sphere_sphere_contact(p.x[i], p.radius[i], p.x[j] + shift_j, p.radius[j]);
  }
};

}  // namespace upgrain::dem
