#include "dem/simulation.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "dem/core/error.h"

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
      kernels_(select_force_kernels(scene.effects)),
      g_(scene.effects.gravity ? Vec3(0, 0, -scene.gravity) : Vec3::Zero()),
      dt_(scene.time_step),
      rotation_(scene.effects.rotation && (scene.effects.friction || scene.effects.wall_friction)) {
  if (!scene.effects.wall_friction) {
    for (auto& w : walls_) w.friction = 0.0;
  }
  ctx_.particles = &p_;
  ctx_.neighbors = &neighbors_;
  ctx_.walls = &walls_;
  ctx_.wall_neighbors = &wall_neighbors_;
  ctx_.material = ContactMaterial::from(scene.particles.material, scene.friction, scene.damping_ratio);
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
  if (rotation_) {
    for (std::size_t i = 0; i < n; ++i) p_.omega[i] += half * p_.inv_inertia[i] * p_.torque[i];
  }
  // Second half of the work of the previous step's damping forces, with v(k+1/2). Damping
  // acts along the normal through the centroids of spheres: no torque, no rotational work.
  if (!ctx_.damping_force.empty()) {
    double work = 0.0;
    for (std::size_t i = 0; i < n; ++i) work += ctx_.damping_force[i].dot(p_.v[i]);
    dissipated_damping_ -= half * work;
  }
  if (rebuild) rebuild_neighbors();
  evaluate_forces();
  // Second half kick with the new forces.
  for (std::size_t i = 0; i < n; ++i) p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
  if (rotation_) {
    for (std::size_t i = 0; i < n; ++i) p_.omega[i] += half * p_.inv_inertia[i] * p_.torque[i];
  }
  ++step_;
  time_ = step_ * dt_;
}

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
    if (rotation_) e.kinetic_rotational += 0.5 * p_.omega[i].squaredNorm() / p_.inv_inertia[i];
    e.potential -= p_.mass(i) * g_.dot(p_.x[i]);
  }
  e.elastic_normal = ctx_.energy.elastic_normal;
  e.elastic_tangential = ctx_.energy.elastic_tangential;
  e.dissipated_damping = dissipated_damping_;
  e.dissipated_friction = dissipated_friction_;
  e.tangential_stiffness_change = stiffness_change_;
  e.removed_by_relaxation = removed_by_relaxation_;
  return e;
}

double Simulation::energy_balance_error() const {
  const EnergyBalance e = energy();
  const double reference =
      e0_.kinetic() + std::abs(e0_.potential - e.potential) + e0_.elastic_normal + e0_.elastic_tangential;
  return reference > 0.0 ? (e.total() - e0_.total()) / reference : 0.0;
}

double Simulation::kinetic_to_released() const {
  const EnergyBalance e = energy();
  const double released = e0_.potential - e.potential;
  return released > 0.0 ? e.kinetic() / released : std::numeric_limits<double>::infinity();
}

StepDiagnostics Simulation::diagnostics() const {
  return {ctx_.particle_contacts, ctx_.wall_contacts, ctx_.max_overlap_ratio, neighbors_.builds()};
}

void Simulation::check_finite() const {
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.x[i].allFinite() || !p_.v[i].allFinite() || !p_.omega[i].allFinite()) {
      std::ostringstream m;
      m << "particle " << p_.id[i] << " has a non-finite position or velocity at step " << step_
        << " (t = " << time_ << " s)";
      throw Error(m.str());
    }
  }
}

}  // namespace upgrain::dem
