#include "dem/simulation.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "dem/core/error.h"
#include "dem/motion/grain_rotation.h"

namespace upgrain::dem {

Simulation::Simulation(const SceneConfig& scene, ParticleStore particles)
    : Simulation(scene, std::move(particles), make_open_box(scene.container)) {}

Simulation::Simulation(const SceneConfig& scene, ParticleStore particles, std::vector<PlaneWall> walls)
    : scene_(scene),
      p_(std::move(particles)),
      walls_(std::move(walls)),
      neighbors_(std::max(p_.max_radius(), 1e-12), scene.neighbor_skin * 2.0 * p_.max_radius(),
                 scene.effects.friction),
      wall_neighbors_(scene.neighbor_skin * 2.0 * p_.max_radius(), scene.effects.wall_friction),
      kernels_(select_force_kernels(scene.effects, p_.has_shapes())),
      g_(scene.effects.gravity ? Vec3(0, 0, -scene.gravity) : Vec3::Zero()),
      dt_(scene.time_step),
      // Spheres turn only under friction or rolling resistance; ellipsoids under normal forces
      // as well.
      rotation_(scene.effects.rotation && (scene.effects.friction || scene.effects.wall_friction ||
                                           scene.effects.rolling_resistance || p_.has_shapes())) {
  if (scene.effects.rolling_resistance) {
    if (!scene.effects.rotation)
      throw Error(
          "rolling resistance needs rotation: set Effects/rotation = true or Effects/rolling resistance = "
          "false");
    neighbors_.keep_rolling_springs();
    wall_neighbors_.keep_rolling_springs();
  }
  if (p_.has_shapes()) {
    neighbors_.keep_contact_memory();
    wall_neighbors_.keep_contact_radii();
  }
  if (!scene.effects.wall_friction) {
    for (auto& w : walls_) w.friction = 0.0;
  }
  ctx_.particles = &p_;
  ctx_.neighbors = &neighbors_;
  ctx_.walls = &walls_;
  ctx_.wall_neighbors = &wall_neighbors_;
  ctx_.material = ContactMaterial::from(scene.particles.material, scene.friction, scene.damping_ratio);
  ctx_.rolling = {scene.rolling_friction, scene.rolling_damping_ratio};
  ctx_.dt = dt_;
  rebuild_neighbors();
  evaluate_forces();
  e0_ = energy();
}

void Simulation::rebuild_neighbors() {
  check_finite();
  neighbors_.rebuild(p_);
  wall_neighbors_.rebuild(p_, walls_);
}

void Simulation::evaluate_forces() {
  if (record_next_) {
    kernels_.recording(ctx_);
    record_next_ = false;
  } else {
    kernels_.plain(ctx_);
  }
  dissipated_damping_ += ctx_.energy.dissipated_damping;
  dissipated_friction_ += ctx_.energy.dissipated_friction;
  stiffness_change_ += ctx_.energy.tangential_stiffness_change;
  dissipated_rolling_ += ctx_.energy.dissipated_rolling;
  rolling_stiffness_change_ += ctx_.energy.rolling_stiffness_change;
  if (ctx_.max_overlap_ratio > kRunawayOverlapRatio) {
    std::ostringstream m;
    m << "runaway overlap at step " << step_ << " (t = " << time_ << " s): an overlap reached "
      << ctx_.max_overlap_ratio << " of a radius (limit " << kRunawayOverlapRatio << "); the time step "
      << dt_ << " s is too large for this scene or a particle was placed inside another";
    throw Error(m.str());
  }
}

void Simulation::step() {
  const std::size_t n = p_.size();
  const double half = 0.5 * dt_;
  // Velocity Verlet, first half kick and drift (Allen and Tildesley 2017, eq. 3.19), with
  // the Verlet list's displacement check in the same pass.
  const std::vector<Vec3>& x_built = neighbors_.positions_at_build();
  const double limit2 = neighbors_.rebuild_displacement2();
  bool rebuild = x_built.size() != n;
  for (std::size_t i = 0; i < n; ++i) {
    p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
    p_.x[i] += dt_ * p_.v[i];
    rebuild = rebuild || (p_.x[i] - x_built[i]).squaredNorm() > limit2;
  }
  if (rotation_) first_rotation_half(half);
  // Second half of the work of the previous step's damping forces, with v(k+1/2). Damping
  // acts along the normal through the centroids of spheres: no torque, no rotational work.
  if (!ctx_.damping_force.empty()) {
    double work = 0.0;
    for (std::size_t i = 0; i < n; ++i) work += ctx_.damping_force[i].dot(p_.v[i]);
    // Ellipsoids: the damping force misses the centroid and works on the rotation too.
    for (std::size_t i = 0; i < ctx_.damping_torque.size(); ++i)
      work += ctx_.damping_torque[i].dot(p_.omega[i]);
    dissipated_damping_ -= half * work;
  }
  // The same for the rolling dashpot (contact/rolling_resistance.h).
  if (!ctx_.rolling_damping_torque.empty()) {
    double work = 0.0;
    for (std::size_t i = 0; i < n; ++i) work += ctx_.rolling_damping_torque[i].dot(p_.omega[i]);
    dissipated_rolling_ -= half * work;
  }
  if (rebuild) rebuild_neighbors();
  evaluate_forces();
  // Second half kick with the new forces.
  for (std::size_t i = 0; i < n; ++i) p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
  if (rotation_) second_rotation_half(half);
  ++step_;
  time_ = step_ * dt_;
}

// Rotation in two halves around the force evaluation, as the translation. Spheres: the
// kick w += (h/2) T / I. Ellipsoids: the symplectic splitting of rigid_rotation.h, with
// the angular momentum L_b = J Q^T w rebuilt from w (exact up to round-off), so that w
// stays the one angular state that contacts, relaxation and stress read.
void Simulation::first_rotation_half(double half) { rotation_first_half(p_, p_.size(), half, dt_); }

void Simulation::second_rotation_half(double half) { rotation_second_half(p_, p_.size(), half); }

void Simulation::remove_wall(const std::string& name) {
  for (PlaneWall& w : walls_) {
    if (w.name != name) continue;
    // Far along its own normal's opposite side: every grain is then at a distance of order
    // 1e100 inside the domain, and no contact can form (distance() stays finite).
    w.point -= 1e100 * w.normal;
    rebuild_neighbors();
    return;
  }
  throw Error("no wall named '" + name + "' to remove");
}

void Simulation::set_gravity(const Vec3& g) {
  g_ = g;
  e0_ = energy();
}

void Simulation::run(long steps) {
  for (long s = 0; s < steps; ++s) step();
}

EnergyBalance Simulation::energy() const {
  EnergyBalance e;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    e.kinetic_translational += 0.5 * p_.mass(i) * p_.v[i].squaredNorm();
    if (rotation_) e.kinetic_rotational += p_.rotational_energy(i);
    e.potential -= p_.mass(i) * g_.dot(p_.x[i]);
  }
  e.elastic_normal = ctx_.energy.elastic_normal;
  e.elastic_tangential = ctx_.energy.elastic_tangential;
  e.dissipated_damping = dissipated_damping_;
  e.dissipated_friction = dissipated_friction_;
  e.tangential_stiffness_change = stiffness_change_;
  e.elastic_rolling = ctx_.energy.elastic_rolling;
  e.dissipated_rolling = dissipated_rolling_;
  e.rolling_stiffness_change = rolling_stiffness_change_;
  e.removed_by_relaxation = removed_by_relaxation_;
  return e;
}

double Simulation::energy_balance_error() const { return balance_error(e0_, energy()); }

double Simulation::kinetic_to_released() const { return dem::kinetic_to_released(e0_, energy()); }

StepDiagnostics Simulation::diagnostics() const {
  return {ctx_.particle_contacts, ctx_.wall_contacts, ctx_.max_overlap_ratio, neighbors_.builds(),
          ctx_.solver_stats};
}

void Simulation::check_finite() const {
  for (std::size_t i = 0; i < p_.size(); ++i) {
    const bool orientation_ok = !p_.has_shapes() || p_.orientation[i].coeffs().allFinite();
    if (!p_.x[i].allFinite() || !p_.v[i].allFinite() || !p_.omega[i].allFinite() || !orientation_ok) {
      std::ostringstream m;
      m << "particle " << p_.id[i] << " has a non-finite position, velocity or orientation at step " << step_
        << " (t = " << time_ << " s)";
      throw Error(m.str());
    }
  }
}

}  // namespace upgrain::dem
