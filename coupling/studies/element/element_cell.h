#pragma once
// A fully periodic cell of grains whose control changes between the phases of an element test
// (docs/element-tests.md; docs/periodic.md, "A cell that deforms"): each change captures the
// engine's state and continues it, bitwise, under the new control (a restart, docs/restart.md),
// with the prescribed rates in the velocity gradient of the next step; the servo axes keep theirs
// (the servo's state) and move it towards their new targets. The element study and the
// calibration's periodic tests (docs/calibration.md, "In a periodic cell") drive their cells with
// it. Collective over the communicator.
#include <mpi.h>

#include <functional>
#include <memory>
#include <vector>

#include "dem/analysis/triaxial.h"
#include "dem/core/cell_motion.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// What a change of control does to a captured state and its scene: the prescribed rates of `m`
// into the velocity gradient of the next step (a shear rate too: a cell not yet sheared starts
// with its images unslid, the same lattice), and `m` as the scene's cell motion, its max_growth
// kept (the position grid was sized for it). ElementCell::resume() and the FEM x DEM cell
// (coupling/femxdem/rve_point.h) continue their engines so.
void continue_under(dem::SceneConfig& scene, dem::EngineState& s, const dem::CellMotion& m);

class ElementCell {
 public:
  // `grains` are rank 0's (the other ranks may pass an empty store); `after_step` is called after
  // every step (a progress report).
  ElementCell(dem::SceneConfig scene, dem::ParticleStore grains, MPI_Comm comm,
              const dem::EngineOptions& engine, std::function<void()> after_step);

  void control(const dem::CellMotion& m) { resume(sim_->capture_state(), m); }

  // Continues from `s` under `m`: the prescribed rates in the velocity gradient (a shear rate
  // too: a cell not yet sheared starts with its images unslid, the same lattice).
  void resume(dem::EngineState s, const dem::CellMotion& m);

  // Runs `steps` steps; returns sigma (tension positive) averaged over the last `window`.
  dem::Mat3 run_stress(long steps, long window);

  // Runs `steps` steps; returns -sigma_dd averaged over the last `window` of them.
  dem::Vec3 run(long steps, long window) { return -run_stress(steps, window).diagonal(); }

  dem::Simulation& sim() { return *sim_; }
  [[nodiscard]] double volume() const { return sim_->cell_matrix().determinant(); }
  [[nodiscard]] dem::Vec3 lengths() const { return sim_->cell_matrix().diagonal(); }

 private:
  dem::SceneConfig scene_;
  MPI_Comm comm_;
  std::function<void()> after_step_;
  std::unique_ptr<dem::Simulation> sim_;
};

// The axis controls the tests combine.
// A servo to `target` (Pa): L_dd = gain (p_dd - target) / target, bounded by max_rate
// (cell_motion.h).
inline dem::CellAxisControl cell_servo(double target, double gain, double max_rate) {
  return {dem::CellAxisMode::servo, 0.0, target, gain / target, max_rate};
}
inline dem::CellAxisControl cell_rate(double rate) { return {dem::CellAxisMode::rate, rate, 0.0, 0.0, 0.0}; }
inline dem::CellMotion every_axis(const dem::CellAxisControl& c) {
  dem::CellMotion m;
  m.axis = {c, c, c};
  return m;
}
inline dem::CellMotion still_cell() { return every_axis(cell_rate(0.0)); }

// The cell at one moment of a test: its lengths and volume, the stress (tension positive)
// averaged over the steps since the sample before, its touching pairs.
struct CellSample {
  double time = 0.0;  // since the start of the test (s)
  dem::Vec3 lengths = dem::Vec3::Zero();
  double volume = 0.0;
  dem::Mat3 stress = dem::Mat3::Zero();
  long contacts = 0;
};

// A sample of drained triaxial compression as a triaxial state (compression positive): eps_1 =
// 1 - h_z / h_z0 and eps_v = 1 - V / V0 from `start`, sigma_1 = -sigma_zz, sigma_3 =
// -(sigma_xx + sigma_yy) / 2.
dem::TriaxialState triaxial_state(const CellSample& c, const CellSample& start);

// Drained triaxial compression (docs/element-tests.md): x and y under `lateral` (a servo to
// sigma_3), z shortened at `axial_rate` (> 0) for `steps` steps. Sample 0 is the cell as it
// starts (the stress of its last step), then `records` samples evenly spaced (steps a multiple
// of records).
std::vector<CellSample> drained_triaxial(ElementCell& cell, const dem::CellAxisControl& lateral,
                                         double axial_rate, long steps, long records);

}  // namespace upgrain::coupling
