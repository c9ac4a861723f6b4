#include "coupling/app/run_printout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "coupling/run/stress_summary.h"

namespace upgrain::coupling {

void print_progress(const Progress& p) {
  using Phase = Progress::Phase;
  static Phase shown = Phase::dynamics;
  if (p.phase != shown) std::printf("\n");
  shown = p.phase;
  const double pct = 100.0 * static_cast<double>(p.step) / static_cast<double>(std::max(p.total_steps, 1L));
  char line[200];
  if (p.phase == Phase::dynamics)
    std::snprintf(line, sizeof line, "  %5.1f %%  step %ld/%ld  %.0f steps/s  ETA %.0f s%s", pct, p.step,
                  p.total_steps, p.steps_per_second, p.eta_seconds, p.may_end_sooner ? " or at rest" : "");
  else
    std::snprintf(line, sizeof line,
                  "  relaxing (FIRE)  step %ld/%ld  residual %.1e, stops at %.0e  ETA <= %.0f s", p.step,
                  p.total_steps, p.residual, p.tolerance, p.eta_seconds);
  // Padded to the previous line's length only: a line longer than the terminal would wrap.
  static int previous = 0;
  const int length = static_cast<int>(std::strlen(line));
  std::printf("\r%-*s", std::max(length, previous), line);
  previous = length;
  std::fflush(stdout);
}

void print_deposition(const SceneInput& in, const RunResult& r) {
  std::printf("\n  done: %ld steps, %.3g s simulated in %.1f s (%.3g particle-steps/s)%s\n", r.steps,
              r.simulated_time, r.wall_seconds, r.particle_steps_per_second,
              r.stopped_at_rest ? ", stopped at rest" : "");
  if (!r.history.resumed_at.empty())
    std::printf("  over %zu segments (resumed at step %ld last), this one %.1f s\n",
                r.history.resumed_at.size() + 1, r.history.resumed_at.back(), r.segment_seconds);
  if (r.relaxation)
    std::printf("  relaxed to static equilibrium: %ld FIRE steps, residual force %.2e, torque %.2e%s\n",
                r.relaxation->steps, r.relaxation->max_force_residual, r.relaxation->max_torque_residual,
                r.relaxation->converged ? "" : " (not converged: step limit)");
  if (in.scene.insertion.enabled())
    std::printf("  poured: %ld of %ld grains (Insertion/count)\n", r.inserted, in.scene.insertion.count);
  const long grains = in.scene.particles.count + r.inserted;
  std::printf("  bed: surface %.4f m, solid fraction %.4f, %.2f contacts per particle, %ld outside\n",
              r.bed.surface_height, r.bed.solid_fraction,
              grains > 0
                  ? 2.0 * static_cast<double>(r.diagnostics.particle_contacts) / static_cast<double>(grains)
                  : 0.0,
              r.bed.particles_outside);
  if (std::isfinite(r.kinetic_to_released))
    std::printf("  energy: kinetic/released %.3e, balance error %.3e\n", r.kinetic_to_released,
                r.energy_balance_error);
  else
    std::printf("  energy: no potential energy released (kinetic/released undefined), balance error %.3e\n",
                r.energy_balance_error);
  if (r.load.ranks > 1)
    std::printf(
        "  load over %d ranks: owned particles max/mean %.3f, compute time max/mean %.3f, communication up "
        "to %.1f %% of a rank's step time, %ld rebalances\n",
        r.load.ranks, r.load.owned_imbalance, r.load.compute_imbalance, 100.0 * r.load.communication_share,
        r.load.rebalances);
  const dem::ContactSolverStats& cs = r.diagnostics.contact_solver;
  if (cs.calls > 0)
    std::printf(
        "  ellipsoid contacts: %lld solver calls (%lld warm, %.2f Newton steps per call), %lld proven "
        "apart before the solver, %lld still apart by an earlier proof, %lld fallbacks, %lld uncertified, "
        "%lld "
        "not converged\n",
        static_cast<long long>(cs.calls), static_cast<long long>(cs.warm_starts),
        static_cast<double>(cs.newton_iterations) / static_cast<double>(cs.calls),
        static_cast<long long>(cs.proven_apart), static_cast<long long>(cs.still_apart),
        static_cast<long long>(cs.fallbacks), static_cast<long long>(cs.uncertified),
        static_cast<long long>(cs.failures));
  if (r.final_stress) {
    const dem::GridStress& g = *r.final_stress;
    const dem::RegularGrid& grid = r.final_grid;
    std::printf("  grid stress (%d x %d x %d cells up to z = %.4f m), final state:\n", grid.n[0], grid.n[1],
                grid.n[2], grid.hi.z());
    for (dem::StressFormula f : in.output.grid_stress.formulas) {
      const StressSummary s = summarise_stress(g, grid, f);
      char rai[96];
      if (s.rated_cells == 0)
        std::snprintf(rai, sizeof rai, "no cell with measurable stress");
      else if (std::isinf(s.max_rai))
        std::snprintf(rai, sizeof rai, "max RAI unbounded (a cell with skew stress only)");
      else
        std::snprintf(rai, sizeof rai, "max RAI %.3g %%", 100.0 * s.max_rai);
      std::printf("    %-18s %s", std::string(dem::name_of(f)).c_str(), rai);
      if (s.negligible_cells > 0)
        std::printf(" (%d cell%s with grains but negligible stress left out)", s.negligible_cells,
                    s.negligible_cells > 1 ? "s" : "");
      std::printf(", mean sigma_zz of the bottom layer %.6g Pa\n", s.floor_szz);
    }
  }
  std::printf("  results: %s/{summary.json,time_series.csv,particles.xdmf,snapshots/%s%s}\n",
              in.output.folder.c_str(),
              r.final_stress ? ",grid_stress.csv,grid_stress.xdmf,grid_stress/" : "",
              r.final_strain ? ",grid_strain.csv,grid_strain.xdmf,grid_strain/" : "");
  std::fflush(stdout);
}

}  // namespace upgrain::coupling
