#pragma once
// The step loop of a serial DEM run: velocity Verlet for translation and rotation
// (docs/integrator.md) around one force evaluation per step.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/force_kernel.h"
#include "dem/core/particle_store.h"
#include "dem/energy.h"
#include "dem/neighbor/verlet_list.h"
#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct StepDiagnostics {
  long particle_contacts = 0;
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;
  long neighbor_builds = 0;
  ContactSolverStats contact_solver;  // ellipsoid contact solver, cumulative (zero for spheres)
};

class Simulation {
 public:
  // Takes the scene and the initial particles; evaluates the initial forces.
  Simulation(const SceneConfig& scene, ParticleStore particles);
  // A container of any planar walls (tests: inclines, no walls).
  Simulation(const SceneConfig& scene, ParticleStore particles, std::vector<PlaneWall> walls);

  void step();

  // Asks the next force evaluation (the next step()) to record every contact, then
  // contacts() holds them: the exact forces of that evaluation, for stress output.
  void request_contacts() { record_next_ = true; }
  [[nodiscard]] const std::vector<ContactSample>& contacts() const { return ctx_.contacts; }
  void run(long steps);

  [[nodiscard]] const ParticleStore& particles() const { return p_; }
  [[nodiscard]] ParticleStore& particles() { return p_; }
  [[nodiscard]] const std::vector<PlaneWall>& walls() const { return walls_; }
  [[nodiscard]] const std::vector<Vec3>& wall_forces() const { return ctx_.wall_force; }
  [[nodiscard]] const SceneConfig& scene() const { return scene_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] long step_count() const { return step_; }
  [[nodiscard]] double time_step() const { return dt_; }
  [[nodiscard]] Vec3 gravity() const { return g_; }
  // Whether rotation is integrated (the rotation effect, and some friction to drive it).
  [[nodiscard]] bool integrates_rotation() const { return rotation_; }
  // Any direction of gravity (tests: an incline is a tilted gravity over a flat floor).
  // Resets the energy reference, since the potential energy is -m g.x.
  void set_gravity(const Vec3& g);

  // Books kinetic energy that a caller removed by changing velocities (relaxation), so the
  // energy balance stays closed.
  void account_removed_kinetic_energy(double joules) { removed_by_relaxation_ += joules; }

  [[nodiscard]] EnergyBalance energy() const;
  // (E_total(t) - E_total(0)) / (initial kinetic energy + |potential energy released|).
  [[nodiscard]] double energy_balance_error() const;
  [[nodiscard]] const EnergyBalance& initial_energy() const { return e0_; }
  // Kinetic energy over the potential energy released since the start: the measure of a
  // bed at rest. Infinity while no potential energy has been released.
  [[nodiscard]] double kinetic_to_released() const;
  [[nodiscard]] StepDiagnostics diagnostics() const;
  // Ellipsoid contact solver counters since the start (zero in sphere scenes).
  [[nodiscard]] const ContactSolverStats& contact_solver_stats() const { return ctx_.solver_stats; }

  // Takes a wall out of the scene (the constrained collapse's gate): it is moved out of
  // reach, so its contacts end at the next force evaluation and its list empties at the
  // next rebuild. Throws when no wall has that name.
  void remove_wall(const std::string& name);

  // Throws upgrain::Error naming the particle when a position or velocity is not finite.
  void check_finite() const;

 private:
  void evaluate_forces();
  void rebuild_neighbors();
  void first_rotation_half(double half);
  void second_rotation_half(double half);

  SceneConfig scene_;
  ParticleStore p_;
  std::vector<PlaneWall> walls_;
  VerletList neighbors_;
  WallNeighborList wall_neighbors_;
  ForceKernels kernels_;
  bool record_next_ = false;
  ForceContext ctx_;
  Vec3 g_;
  double dt_;
  bool rotation_;
  double time_ = 0.0;
  long step_ = 0;
  double dissipated_damping_ = 0.0;
  double dissipated_friction_ = 0.0;
  double stiffness_change_ = 0.0;
  double dissipated_rolling_ = 0.0;
  double rolling_stiffness_change_ = 0.0;
  double removed_by_relaxation_ = 0.0;
  EnergyBalance e0_;
};

// Largest overlap (as a fraction of the smaller radius) tolerated before the run stops:
// beyond it the contact law is far outside its validity and the step is too large.
inline constexpr double kRunawayOverlapRatio = 0.25;

}  // namespace upgrain::dem
