// The cost of a FEM x DEM Gauss point (docs/femxdem.md, "Cost"): the throughput of the DEM cell
// inside its trials (deform, hold, relax, tangent, state copies) against the plain engine
// stepping the same grains under the same strain rate, and the steps and stress of each
// relaxation of the held cell.
//
//   bench_femxdem_cell scene.prm [trials]
//
// The scene's FEMxDEM section gives the cell (grains, seed, steps per unit strain, tolerance,
// cap). Each trial shortens the cell along y by a further 1e-3 (the biaxial example's load step)
// from the last committed one, with the lateral axes held, and is committed: the path of a point
// on the specimen's axis. One rank.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "coupling/femxdem/rve_point.h"
#include "coupling/femxdem/rve_preparation.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/study_use.h"
#include "coupling/studies/element/element_cell.h"

namespace {

using namespace upgrain;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr double kStrainPerTrial = 1e-3;

// The plain engine: the prepared grains compressed along y at the trials' rate, without stops.
double plain_throughput(const coupling::RveTemplate& t, const coupling::RveOptions& o, long steps) {
  dem::SceneConfig scene = t.scene;
  dem::EngineState s = t.state;
  dem::CellMotion m = coupling::still_cell();
  m.axis[1] = coupling::cell_rate(-1.0 / (o.steps_per_unit_strain * scene.time_step));
  coupling::continue_under(scene, s, m);
  dem::Simulation sim(scene, s, MPI_COMM_SELF, t.engine);
  const auto t0 = Clock::now();
  sim.run(steps);
  return static_cast<double>(sim.particle_count() * steps) / seconds_since(t0);
}

struct TrialRun {
  double grain_steps = 0.0;
  double seconds = 0.0;
  long increment_steps = 0;
  long relaxation_steps = 0;
  int unconverged = 0;
  double final_stress_yy = 0.0;
};

TrialRun trials(std::shared_ptr<const coupling::RveTemplate> t, const coupling::RveOptions& o, int n) {
  coupling::RveCell cell(std::move(t), o);
  TrialRun r;
  const auto t0 = Clock::now();
  for (int k = 1; k <= n; ++k) {
    fem::Mat3x3 h = fem::Mat3x3::Zero();
    h(1, 1) = -kStrainPerTrial * k;
    const fem::PointResponse p = cell.respond(h);
    cell.commit();
    r.grain_steps += p.cost;
    r.increment_steps += cell.last_trial().increment_steps;
    r.relaxation_steps += cell.last_trial().relaxation_steps;
    r.unconverged += p.converged ? 0 : 1;
    r.final_stress_yy = p.stress(1);
  }
  r.seconds = seconds_since(t0);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_femxdem_cell scene.prm [trials]\n");
    MPI_Finalize();
    return 2;
  }
  const int n = argc > 2 ? std::atoi(argv[2]) : 20;
  const coupling::SceneInput in = coupling::read_scene_file(argv[1], {.name = "femxdem"});
  const coupling::RveOptions& base = in.femxdem.rve;
  const auto t0 = Clock::now();
  const auto prepared = std::make_shared<const coupling::RveTemplate>(coupling::prepare_rve(in.scene, base));
  std::printf("cell: %ld grains, %ld contacts, prepared in %ld steps, %.2f s\n", prepared->grains,
              prepared->contacts, prepared->steps, seconds_since(t0));

  const long plain_steps = static_cast<long>(n * kStrainPerTrial * base.steps_per_unit_strain) * 5;
  const double plain = plain_throughput(*prepared, base, plain_steps);
  std::printf("plain engine, the same grains compressed along y: %.3g grain-steps/s (%ld steps)\n", plain,
              plain_steps);
  std::printf("\n%-9s %-10s %6s %10s %10s %9s %12s %8s %10s %12s\n", "relax", "tolerance", "trials",
              "incr/trial", "relax/tr.", "unconv.", "grain-steps", "s", "gs/s", "plain/trial");
  for (const coupling::RveRelaxation method :
       {coupling::RveRelaxation::damped, coupling::RveRelaxation::fire}) {
    for (const double tolerance : {1e-2, 1e-3, 1e-4, 1e-5}) {
      coupling::RveOptions o = base;
      o.relaxation = method;
      o.unbalanced_force_tolerance = tolerance;
      o.tangent = coupling::RveTangent::contact_stiffness;
      const TrialRun r = trials(prepared, o, n);
      const double rate = r.grain_steps / r.seconds;
      std::printf("%-9s %-10.0e %6d %10.1f %10.1f %9d %12.4g %8.3f %10.3g %12.3f   sigma_yy %.6g Pa\n",
                  method == coupling::RveRelaxation::fire ? "fire" : "damped", tolerance, n,
                  static_cast<double>(r.increment_steps) / n, static_cast<double>(r.relaxation_steps) / n,
                  r.unconverged, r.grain_steps, r.seconds, rate, plain / rate, r.final_stress_yy);
    }
  }
  MPI_Finalize();
  return 0;
}
