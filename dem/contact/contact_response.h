#pragma once
// Force of one Hertz-Mindlin contact with Coulomb friction and normal viscous damping,
// given the contact geometry (unit normal from i towards j, overlap, lever arms) and
// the kinematics of both bodies. Templated on the effect set: what a scene switches off
// is not computed. Equations and sign conventions: docs/contact-law.md.
#include <cmath>

#include "dem/contact/hertz_mindlin.h"
#include "dem/core/contact_history.h"
#include "dem/core/types.h"

namespace upgrain::dem {

struct ContactParameters {
  double e_star;    // effective Young's modulus (Pa)
  double g_star;    // effective shear modulus (Pa)
  double r_star;    // effective radius (m)
  double m_star;    // effective mass (kg)
  double friction;  // Coulomb coefficient
  double zeta;      // damping ratio
  double dt;        // time step (s)
};

struct ContactKinematics {
  Vec3 normal;     // unit normal, from body i towards body j
  double overlap;  // delta > 0
  Vec3 lever_i;    // from centroid i to the contact point (spheres: (r_i - delta/2) n)
  Vec3 lever_j;    // from centroid j to the contact point (spheres: -(r_j - delta/2) n)
  Vec3 v_i, v_j, omega_i, omega_j;
};

// The geometry of two touching spheres (the force loops' sphere pairs): d = x_j - x_i with
// |d|^2 = dist2 < (r_i + r_j)^2. Sets the normal (i to j), overlap and levers of `kin`, the lever
// lengths along the normal and the effective radius r_i r_j / (r_i + r_j).
[[gnu::always_inline]] inline void sphere_pair_kinematics(const Vec3& d, double dist2, double ri, double rj,
                                                          ContactKinematics& kin, double& arm_i,
                                                          double& arm_j, double& r_star) {
  const double rsum = ri + rj;
  const double dist = std::sqrt(dist2);
  const double delta = rsum - dist;
  kin.normal = d * (1.0 / dist);
  kin.overlap = delta;
  arm_i = ri - 0.5 * delta;
  arm_j = rj - 0.5 * delta;
  kin.lever_i = arm_i * kin.normal;
  kin.lever_j = -arm_j * kin.normal;
  r_star = ri * rj / rsum;
}

struct ContactEnergy {
  double elastic_normal = 0.0;
  double elastic_tangential = 0.0;
  double dissipated_damping = 0.0;
  double dissipated_friction = 0.0;
  // Change of the stored tangential energy |F_t|^2 / (2 k_t) caused by k_t following the
  // overlap while F_t is held: the incremental Mindlin spring is not a potential, and
  // this term is what it creates (> 0) or destroys (< 0). Accounted separately so the
  // balance error measures the integration (docs/contact-law.md, energy).
  double tangential_stiffness_change = 0.0;
  // Rolling resistance (contact/rolling_resistance.h): the spring's energy |M_r|^2 / (2 k_r),
  // its plastic and viscous dissipation (increment), and the energy its stiffness change
  // creates, as for the tangential spring.
  double elastic_rolling = 0.0;
  double dissipated_rolling = 0.0;
  double rolling_stiffness_change = 0.0;
};

struct ContactForce {
  Vec3 on_i;       // force on body i; body j receives -on_i
  double normal;   // magnitude of the (repulsive) normal force, >= 0
  double damping;  // its viscous part (normal minus elastic), along -normal on i
};

// spring: the tangential force of this contact on i, carried from the previous step
// (incremental Mindlin spring). Updated in place.
// Always inlined into the force loop: as a call, the kinematics are copied through memory
// per contact (measured with callgrind: about a fifth of the loop's instructions).
template <bool Tangential, bool Damping, bool Rotation, bool Energy>
[[gnu::always_inline]] inline ContactForce contact_response(const ContactParameters& p,
                                                            const ContactKinematics& k,
                                                            TangentialSpring& spring, ContactEnergy& energy) {
  const Vec3& n = k.normal;
  const double delta = k.overlap;
  const double sqrt_rd = std::sqrt(p.r_star * delta);
  const double f_elastic = 4.0 / 3.0 * p.e_star * sqrt_rd * delta;  // Hertz, = (4/3)E* sqrt(R*) d^1.5

  // Relative velocity of i with respect to j at the contact point.
  Vec3 v_rel = k.v_i - k.v_j;
  if constexpr (Rotation) {
    v_rel += k.omega_i.cross(k.lever_i) - k.omega_j.cross(k.lever_j);
  }
  const double v_n = v_rel.dot(n);  // > 0 while approaching

  double f_n = f_elastic;
  if constexpr (Damping) {
    const double k_n = 2.0 * p.e_star * sqrt_rd;
    f_n += 2.0 * p.zeta * std::sqrt(p.m_star * k_n) * v_n;
    f_n = f_n > 0.0 ? f_n : 0.0;  // the normal force is never attractive
    // A force evaluated at step k does work over the two half kicks around k, i.e. with
    // the mean of v(k-1/2) and v(k+1/2) (docs/integrator.md). This is the v(k-1/2) half;
    // the Simulation adds the other half after its next first kick.
    if constexpr (Energy) energy.dissipated_damping += 0.5 * (f_n - f_elastic) * v_n * p.dt;
  }
  if constexpr (Energy) energy.elastic_normal += 0.4 * f_elastic * delta;  // 8/15 E* sqrt(R*) d^2.5

  ContactForce out;
  out.normal = f_n;
  out.damping = f_n - f_elastic;
  out.on_i = -f_n * n;

  if constexpr (Tangential) {
    const double k_t = 8.0 * p.g_star * sqrt_rd;
    Vec3& f_t = spring.force;
    // Carry the stored spring into the current tangent plane, keeping its magnitude.
    const double old_norm2 = f_t.squaredNorm();
    if (old_norm2 > 0.0) {
      f_t -= f_t.dot(n) * n;
      const double new_norm2 = f_t.squaredNorm();
      if (new_norm2 > 0.0) f_t *= std::sqrt(old_norm2 / new_norm2);
      if constexpr (Energy) {
        if (spring.stiffness > 0.0)
          energy.tangential_stiffness_change += 0.5 * old_norm2 * (1.0 / k_t - 1.0 / spring.stiffness);
      }
    }
    const Vec3 v_t = v_rel - v_n * n;
    f_t -= k_t * p.dt * v_t;  // incremental Mindlin: dF_t = -k_t du_t
    spring.stiffness = k_t;
    const double limit = p.friction * f_n;
    const double trial2 = f_t.squaredNorm();
    if (trial2 > limit * limit) {
      const double trial = std::sqrt(trial2);
      if constexpr (Energy) energy.dissipated_friction += limit * (trial - limit) / k_t;
      f_t *= limit / trial;  // Coulomb: the stored spring is rescaled on slip
    }
    if constexpr (Energy) energy.elastic_tangential += 0.5 * f_t.squaredNorm() / k_t;
    out.on_i += f_t;
  }
  return out;
}

}  // namespace upgrain::dem
