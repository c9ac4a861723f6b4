#pragma once
// What a run leaves besides its files: the figures of summary.json (docs/output.md), the
// measures of the bed, and the last grid evaluation, for the studies that go on from it.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "coupling/run/cg_capture.h"
#include "coupling/run/output_options.h"
#include "coupling/run/run_history.h"
#include "dem/analysis/bed_state.h"
#include "dem/engine/diagnostics.h"
#include "dem/engine/energy.h"
#include "dem/engine/engine_state.h"
#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"
#include "dem/stress/grid_stress.h"
#include "upscale/strain/grid_strain.h"

namespace upgrain::coupling {

// A grain's contact with a side wall (dem::kSideWallNames) at the end of a run: the wall's
// index, the contact point's height and the wall's force on the grain (N).
struct SideWallContact {
  int wall = 0;
  double z = 0.0;
  dem::Vec3 force_on_grain = dem::Vec3::Zero();
};

struct RunResult {
  long steps = 0;
  double simulated_time = 0.0;
  // Over every segment of a restarted run (history.wall_seconds at the checkpoint it resumed
  // from, and this segment's), and this segment's alone.
  double wall_seconds = 0.0;
  double segment_seconds = 0.0;
  double particle_steps_per_second = 0.0;  // the steps of every segment over wall_seconds
  // The scene the run was started with and where it was resumed (rank 0's).
  RunHistory history;
  dem::EnergyBalance energy;
  double energy_balance_error = 0.0;
  double kinetic_to_released = 0.0;  // kinetic energy / potential energy released
  double potential_released = 0.0;   // J, since the start
  dem::StepDiagnostics diagnostics;
  dem::BedState bed;
  bool stopped_at_rest = false;
  std::optional<dem::RelaxationResult> relaxation;  // when relax_at_end
  std::vector<dem::Vec3> wall_forces;               // final force of the grains on each wall (N)
  std::vector<std::string> wall_names;
  double total_mass = 0.0;  // kg
  long inserted = 0;        // grains poured in during the run (docs/insertion.md)
  // The last grid-stress evaluation, when the output asked for one (for in-memory use).
  std::optional<dem::GridStress> final_stress;
  dem::RegularGrid final_grid;
  // The last grid-strain evaluation, when the output asked for one (rank 0).
  std::optional<upscale::GridStrain> final_strain;
  dem::EngineLoad load;  // how the ranks shared the work (one rank: the defaults)
  // The states for the coarse-grained fields, when the output asked for them (rank 0).
  CapturedStates coarse_graining;
  // The engine's state at the end (RunControl::keep_final_state; rank 0's, empty elsewhere).
  std::optional<dem::EngineState> final_state;
  // The side-wall contacts of the last step (RunControl::keep_wall_contacts; rank 0's; none when
  // that step did not record its contacts).
  std::optional<std::vector<SideWallContact>> side_wall_contacts;
};

// The figures of the engine's final state into `r` (collective; the bed and the mass on rank
// 0): steps, time, energies, diagnostics, load, wall forces, bed. `wall_seconds` is the time the
// run took for its `steps_taken` steps (a resumed run's over every segment: run_history.h).
void measure_final_state(dem::Simulation& sim, double wall_seconds, long steps_taken, RunResult& r);

// The side-wall contacts of the engine's last step, which must have recorded its contacts
// (collective; rank 0's, sorted by grain id; empty elsewhere).
std::vector<SideWallContact> side_wall_contacts(const dem::Simulation& sim);

// summary.json's entries: the run's figures, the ranks and summation, and the effect set with
// the reason for each entry. JSON has no NaN: a figure not computed (the energy channels
// without energy tracking) is null.
std::map<std::string, std::string> summary_entries(const dem::Simulation& sim, const RunResult& r,
                                                   const std::vector<dem::EffectChoice>& effects);

}  // namespace upgrain::coupling
