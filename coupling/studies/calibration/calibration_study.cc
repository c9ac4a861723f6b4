#include "coupling/studies/calibration/calibration_study.h"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "coupling/run/scene_run.h"
#include "coupling/studies/calibration/bed_calibration.h"
#include "coupling/studies/dem_run.h"
#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

int run_calibration_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks) {
  // The scene was checked for the calibration's tests by its own checks (calibration_checks.h).
  const std::function<void(const Progress&)>& on_progress = hooks.progress;
  const CalibrationOptions& c = in.calibration;
  // The bed is deposited in the oedometer's ring: the side walls get the calibration's friction
  // (a lubricated ring by default), the floor keeps the scene's.
  dem::SceneConfig scene = in.scene;
  for (int w = 1; w < 5; ++w) scene.container.friction[w] = c.side_wall_friction;
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  dem::Simulation sim(scene, fill_on_root(scene, comm), comm, engine_options(in));
  // The deposition, as the scene runs it (to its end time or to rest), without output.
  RunControl deposition = in.control;
  deposition.relax_at_end = false;
  deposition.lid = {};
  const RunResult dep = run_scene(sim, deposition, std::nullopt, on_progress);
  const double deposition_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  // Both tests start from the deposited bed.
  const BedCalibration b =
      calibrate_bed(scene, sim.capture_state(), c, cell_servo_of(in), comm, sim.options(), on_progress);
  on_rank0(comm, [&] {
    const fs::path folder = fs::path(in.output.folder) / "calibration";
    write_bed_calibration(folder, in.source, b);
    // The headline figures (null without a fit); summary.json also marks the folder as a run's
    // (Output/overwrite), so a refused calibration can be run again over it.
    std::ostringstream j;
    j << "{\n  \"study\": \"calibration\",\n  \"particles\": " << b.particles
      << ",\n  \"deposition_steps\": " << dep.steps
      << ",\n  \"deposition_wall_time_s\": " << dem::io::json_number(deposition_seconds) << ",\n"
      << bed_calibration_json(b) << "\n}\n";
    dem::io::write_text_atomically(fs::path(in.output.folder) / "summary.json", j.str());
    if (const std::string why = b.material_error(folder); !why.empty()) throw Error("calibration: " + why);
    std::printf("\n  calibration: deposition %.1f s (%ld steps%s), ", deposition_seconds, dep.steps,
                dep.stopped_at_rest ? ", stopped at rest" : "");
    print_bed_calibration(b);
    std::printf("  results: %s/{oedometer.csv,triaxial.csv,material.prm}, %s/summary.json\n", folder.c_str(),
                in.output.folder.c_str());
  });
  return 0;
}

}  // namespace upgrain::coupling
