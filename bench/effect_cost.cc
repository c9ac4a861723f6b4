// Cost of each effect on one settled bed (docs/contact-law.md, "What each effect costs"):
//   bench_effect_cost bed.data [steps [rounds]]
// runs the bed of `bench_dense_bed settle` with every effect on, then with one effect off
// at a time through the scene's own parameters (the effect set derived by choose_effects,
// as the driver does), plus rolling resistance on. The variants alternate in `rounds` rounds
// of `steps` steps each (deterministic summation, one rank); the best round of each is
// reported as ns and particle-steps per second, as a ratio to all-on measured in the same
// run, and with the bytes per particle of the state the effects add (contact history and
// the loop's energy and damping arrays), which every step reads and writes.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bench/callgrind_marks.h"
#include "bench/dense_bed_scene.h"
#include "dem/engine/simulation.h"
#include "dem/parallel/mpi_start.h"
#include "dem/scene/effect_choice.h"

using namespace upgrain::dem;

namespace {

struct Variant {
  const char* name;
  std::function<void(SceneConfig&, EffectSwitches&)> change;
};

struct Measured {
  double best = std::numeric_limits<double>::infinity();  // s per particle-step
  double bytes = 0.0;                                     // per particle
  double contacts = 0.0;                                  // per particle
  EffectSet set;
};

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_effect_cost bed.data [steps [rounds]]\n");
    return 2;
  }
  const auto bed = upgrain::bench::read_bed(argv[1]);
  if (!bed) {
    std::fprintf(stderr, "bench_effect_cost: cannot read %s\n", argv[1]);
    return 1;
  }
  const long steps = argc > 2 ? std::atol(argv[2]) : 1000;
  // Under callgrind one round: each variant's timed steps are a profile file of their own
  // (`.1` ... in the order of the table), whose instructions per particle-step do not
  // depend on the machine's load.
  const int rounds = UPGRAIN_ON_VALGRIND() ? 1 : argc > 3 ? std::atoi(argv[3]) : 3;
  auto no_wall_friction = [](SceneConfig& s) {
    for (double& mu : s.container.friction) mu = 0.0;
  };
  std::vector<Variant> variants = {
      {"all effects (paper's law, energy tracked)", [](SceneConfig&, EffectSwitches&) {}},
      {"energy tracking off (Output/energy balance = false)", [](SceneConfig&, EffectSwitches&) {}},
      {"damping off (damping ratio 0)", [](SceneConfig& s, EffectSwitches&) { s.damping_ratio = 0.0; }},
      {"pair friction off (friction coefficient 0)",
       [](SceneConfig& s, EffectSwitches&) { s.friction = 0.0; }},
      {"wall friction off (wall coefficients 0)",
       [&](SceneConfig& s, EffectSwitches&) { no_wall_friction(s); }},
      {"frictionless (both 0: no rotation work)",
       [&](SceneConfig& s, EffectSwitches&) {
         s.friction = 0.0;
         no_wall_friction(s);
       }},
      {"coefficients 0 but friction forced on",
       [&](SceneConfig& s, EffectSwitches& sw) {
         s.friction = 0.0;
         no_wall_friction(s);
         sw.friction = sw.wall_friction = sw.rotation = EffectSwitch::on;
       }},
      {"rotation held (Effects/rotation = false)",
       [](SceneConfig&, EffectSwitches& sw) { sw.rotation = EffectSwitch::off; }},
      {"gravity off (acceleration 0)", [](SceneConfig& s, EffectSwitches&) { s.gravity = 0.0; }},
      {"rolling resistance on",
       [](SceneConfig&, EffectSwitches& sw) { sw.rolling_resistance = EffectSwitch::on; }},
  };
  const double n = static_cast<double>(bed->particles.size());
  std::vector<Measured> measured(variants.size());
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t k = 0; k < variants.size(); ++k) {
      Measured& v = measured[k];
      SceneConfig s = bed->scene;
      EffectSwitches sw;
      variants[k].change(s, sw);
      // A step so short that the grains do not move: every variant evaluates the same
      // contacts. At the bed's own step a bed without gravity or friction rearranges within
      // the run (its contacts fall from 4 to below 1 per particle in 1,000 steps), and the
      // work with it. The cost of a step does not depend on its length.
      s.time_step = 1e-10;
      s.effects = choose_effects(s, sw, {k != 1}).set;
      v.set = s.effects;
      Simulation sim(s, bed->particles);
      sim.run(50);  // lists built, history and caches warm
      UPGRAIN_ZERO_STATS();
      const auto t0 = std::chrono::steady_clock::now();
      sim.run(steps);
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      UPGRAIN_DUMP_STATS(variants[k].name);
      v.best = std::min(v.best, dt / (n * static_cast<double>(steps)));
      v.bytes = static_cast<double>(sim.effect_state_bytes()) / n;
      v.contacts = 2.0 * static_cast<double>(sim.diagnostics().particle_contacts) / n;
    }
  }
  std::printf("bench_effect_cost: %.0f particles, %ld steps x %d rounds, best round each\n\n", n, steps,
              rounds);
  std::printf(
      "| variant | F D W R E Rr | ns / particle-step | particle-steps/s | ratio to all on | bytes / particle "
      "| contacts / particle |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const double ref = measured[0].best;
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const Measured& v = measured[k];
    const EffectSet& e = v.set;
    std::printf("| %s | %d %d %d %d %d %d | %.1f | %.3e | %.3f | %.0f | %.2f |\n", variants[k].name,
                e.friction, e.damping, e.wall_friction, e.integrates_rotation(false), e.energy_tracking,
                e.rolling_resistance, 1e9 * v.best, 1.0 / v.best, v.best / ref, v.bytes, v.contacts);
  }
  return 0;
}
