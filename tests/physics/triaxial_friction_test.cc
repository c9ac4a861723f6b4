// The friction-angle test (coupling/studies/calibration/triaxial_run.h, docs/calibration.md) on small
// random packings of polydisperse Hertz spheres without gravity, frictionless walls: the
// critical-state friction angle of frictionless spheres is small (about 5-6 degrees for large
// samples, Peyneau & Roux 2008, Phys. Rev. E 78 011307), and it grows with the interparticle
// friction (about 20-25 degrees at mu = 0.5, Thornton 2000, Geotechnique 50(1) 43-53). A sample of
// a few hundred grains between walls is noisy, so only the robust bounds are asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "../common/scenes.h"
#include "coupling/studies/calibration/triaxial_run.h"
#include "dem/boundary/container.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct Outcome {
  FrictionStrength strength;
  double mean_lateral = 0.0;  // the mean Bagi sigma_3 while shearing over the target
  double rms_walls = 0.0;     // the side walls' rms relative deviation from the target while shearing
};

// 8 x 8 x 8 spheres of radii uniform in [0.8, 1.2] mm on a jittered lattice of 2.6 mm,
// consolidated to 5 kPa in 0.08 s and sheared at 1/s to 25 % axial strain; the critical state is its second
// half.
Outcome shear(double mu) {
  constexpr double spacing = 2.6e-3, rho = 2650.0;
  constexpr int n = 8;
  SceneConfig s = test::bare_scene(5e-6);
  s.effects.damping = true;
  s.effects.friction = mu > 0.0;
  s.effects.rotation = true;
  s.damping_ratio = 0.5;
  s.friction = mu;
  s.container.lx = s.container.ly = n * spacing;
  for (double& f : s.container.friction) f = 0.0;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radius(0.8e-3, 1.2e-3), jitter(-0.1e-3, 0.1e-3);
  ParticleStore p;
  long id = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 x(spacing * (i + 0.5) + jitter(rng), spacing * (j + 0.5) + jitter(rng),
                     spacing * (k + 0.5) + jitter(rng));
        p.add_sphere(id++, radius(rng), rho, x, Vec3::Zero(), Vec3::Zero());
      }
  Simulation sim(s, p, make_open_box(s.container));
  coupling::TriaxialOptions o;
  o.confining_stress = 5e3;
  o.strain_rate = 1.0;
  o.final_strain = 0.25;
  o.consolidation_time = 0.08;
  o.max_speed = 0.1;
  o.records = 50;
  const std::vector<coupling::TriaxialRecord> rec = coupling::run_triaxial(sim, o);
  std::vector<TriaxialState> path;
  Outcome out;
  for (std::size_t k = 1; k < rec.size(); ++k) {
    out.mean_lateral +=
        rec[k].state.lateral_stress / o.confining_stress / static_cast<double>(rec.size() - 1);
    for (double w : rec[k].side_stress)
      out.rms_walls += std::pow(w / o.confining_stress - 1, 2) / static_cast<double>(4 * (rec.size() - 1));
  }
  out.rms_walls = std::sqrt(out.rms_walls);
  for (const coupling::TriaxialRecord& r : rec) path.push_back(r.state);
  out.strength = friction_strength(path, 0.02, 0.5);
  const coupling::TriaxialRecord& c = rec.front();
  std::printf("mu %.2f: consolidated lid %.0f Pa, sides %.0f %.0f %.0f %.0f Pa, Bagi %.0f / %.0f Pa\n", mu,
              c.lid_stress, c.side_stress[0], c.side_stress[1], c.side_stress[2], c.side_stress[3],
              c.state.axial_stress, c.state.lateral_stress);
  for (std::size_t k = 0; k < rec.size(); k += 5)
    std::printf("  eps_1 %.3f eps_v %+.4f sigma_1 %.0f sigma_3 %.0f phi %.1f\n", rec[k].state.axial_strain,
                rec[k].state.volumetric_strain, rec[k].state.axial_stress, rec[k].state.lateral_stress,
                mobilised_friction_angle(rec[k].state.axial_stress, rec[k].state.lateral_stress));
  const FrictionStrength& f = out.strength;
  std::printf(
      "  peak %.2f deg at %.3f (psi %.2f), critical %.2f +- %.2f deg (%d states), mean sigma_3 %.3f of the "
      "target, walls rms %.1f %%\n",
      f.peak_angle, f.peak_strain, f.peak_dilatancy_angle, f.critical_angle, f.critical_spread,
      f.critical_states, out.mean_lateral, 100 * out.rms_walls);
  return out;
}

}  // namespace

TEST(TriaxialFriction, FrictionlessSpheresAreWeakAndFrictionStrengthens) {
  const Outcome smooth = shear(0.0), rough = shear(0.5);
  // The servo side walls hold sigma_3 on average (the sample's Bagi stress, not the walls').
  for (const Outcome* o : {&smooth, &rough}) EXPECT_NEAR(o->mean_lateral, 1.0, 0.05);
  EXPECT_LT(smooth.strength.critical_angle, 12.0);
  EXPECT_GT(rough.strength.critical_angle, smooth.strength.critical_angle + 8.0);
  EXPECT_GT(rough.strength.critical_angle, 15.0);
  EXPECT_LT(rough.strength.critical_angle, 35.0);
}
