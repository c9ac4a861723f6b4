#pragma once
// A whole deposition run: fill, integrate to the end time (or until the bed is at rest),
// record, summarise. Used by the driver and by the regression tests.
#include <functional>
#include <optional>

#include <mpi.h>

#include "dem/analysis/bed_state.h"
#include "dem/engine/diagnostics.h"
#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"
#include "dem/io/grid_strain_output.h"
#include "dem/io/grid_stress_output.h"
#include "dem/io/run_recorder.h"

namespace upgrain::dem {

struct RunControl {
  // Stop early once kinetic energy < rest_ratio * (potential energy released), checked at
  // each time-series row after the first tenth of the run; 0 disables.
  double rest_ratio = 0.0;
  // After the run, relax the bed to static equilibrium by FIRE (dem/relaxation.h) and
  // write the final snapshot and grid stress of the relaxed state.
  bool relax_at_end = false;
  RelaxationOptions relaxation;
};

struct Progress {
  long step;
  long total_steps;
  double steps_per_second;
  double eta_seconds;
};

struct DepositionResult {
  long steps = 0;
  double simulated_time = 0.0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  EnergyBalance energy;
  double energy_balance_error = 0.0;
  double kinetic_to_released = 0.0;  // kinetic energy / potential energy released
  StepDiagnostics diagnostics;
  BedState bed;
  bool stopped_at_rest = false;
  std::optional<RelaxationResult> relaxation;  // when relax_at_end
  std::vector<Vec3> wall_forces;               // final force of the grains on each wall (N)
  std::vector<std::string> wall_names;
  double total_mass = 0.0;  // kg
  // The last grid-stress evaluation, when the output asked for one (for in-memory use).
  std::optional<GridStress> final_stress;
  RegularGrid final_grid;
  // The last grid-strain evaluation, when the output asked for one.
  std::optional<GridStrain> final_strain;
  EngineLoad load;  // how the ranks shared the work (one rank: the defaults)
};

// From the scene's fill (made on rank 0), collective over `comm`: every rank keeps the grains
// of its block. The output is written by rank 0 and holds the same bytes on any rank count
// with deterministic summation (docs/parallel.md, "Runs from the driver"); the result is
// complete on rank 0 only (bed, mass, strain and progress reports are rank 0's; the other
// fields are the same on every rank).
DepositionResult run_deposition(const SceneConfig& scene, const RunControl& control,
                                const std::optional<io::OutputOptions>& output,
                                const std::function<void(const Progress&)>& on_progress = {},
                                MPI_Comm comm = MPI_COMM_SELF, const EngineOptions& options = {});

// The same on an engine already made (collective over its ranks).
DepositionResult run_deposition(Simulation& engine, const SceneConfig& scene, const RunControl& control,
                                const std::optional<io::OutputOptions>& output,
                                const std::function<void(const Progress&)>& on_progress = {});

}  // namespace upgrain::dem
