#include "coupling/studies/continuum/study_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "coupling/studies/continuum/strain_report.h"
#include "coupling/studies/continuum/wall_shear_profile.h"
#include "coupling/studies/report_format.h"
#include "coupling/studies/run_account.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"
#include "dem/io/grid_stress_output.h"

namespace upgrain::coupling {

namespace {

std::string percent(double share) { return fmt(100.0 * share + 0.0, 3) + " %"; }

double largest(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

const char* matching_name(fem::ConeMatching m) {
  switch (m) {
    case fem::ConeMatching::inner:
      return "inner cone";
    case fem::ConeMatching::plane_strain:
      return "plane strain";
    case fem::ConeMatching::outer:
      break;
  }
  return "outer cone";
}

// The formulas the report ranks the continua for: Bagi and the modified Nicot, the ones
// that are right at rest (docs/stress.md), when compared; otherwise every compared formula.
std::vector<const FormulaComparison*> ranked_formulas(const DemFemComparison& c) {
  std::vector<const FormulaComparison*> out;
  for (const FormulaComparison& fc : c.formulas)
    if (fc.formula == dem::StressFormula::bagi || fc.formula == dem::StressFormula::modified_nicot)
      out.push_back(&fc);
  if (out.empty())
    for (const FormulaComparison& fc : c.formulas) out.push_back(&fc);
  return out;
}

void parameters_section(std::ostringstream& m, const StudyRecord& s) {
  const dem::SceneConfig& sc = s.in.scene;
  const DemOutcome& d = s.dem;
  const fem::ColumnProblem& p = s.rollers_problem;
  m << "## Parameters\n\n| quantity | value |\n|---|---|\n"
    << "| grains | " << sc.particles.count << grain_kind(sc.particles.shapes)
    << (sc.particles.gradation.empty() ? fmt(sc.particles.radius) + " m" : std::string("by gradation curve"))
    << ", density " << sc.particles.material.density << " kg/m^3, E " << sc.particles.material.youngs_modulus
    << " Pa, nu " << sc.particles.material.poisson_ratio << " |\n"
    << "| contact | friction " << sc.friction << ", damping ratio " << sc.damping_ratio << ", wall friction "
    << (sc.effects.wall_friction
            ? "floor " + fmt(sc.container.friction[0]) + ", sides " + fmt(sc.container.friction[1]) + " " +
                  fmt(sc.container.friction[2]) + " " + fmt(sc.container.friction[3]) + " " +
                  fmt(sc.container.friction[4])
            : std::string("off"))
    << " |\n"
    << "| container | " << sc.container.lx << " m x " << sc.container.ly << " m |\n"
    << "| time step, end time | " << sc.time_step << " s, " << sc.end_time << " s |\n"
    << "| stress grid | " << d.grid.n[0] << " x " << d.grid.n[1] << " x " << d.grid.n[2]
    << " cells up to z = " << fmt(d.grid.hi.z())
    << " m (top of the highest grain), V = " << fmt(d.stress.cell_volume) << " m^3 |\n"
    << "| continua | E " << p.youngs_modulus << " Pa, nu " << p.poisson_ratio
    << (s.in.study.continuum.material_file.empty()
            ? std::string(" (Continuum entries)")
            : " (E: " + s.in.study.continuum.source_of("youngs modulus") +
                  "; nu: " + s.in.study.continuum.source_of("poisson ratio") + ")")
    << " (K0 = " << fmt(s.comparison.k0) << "), Q" << p.degree << ", " << p.refinements << " refinement(s), "
    << s.rollers.n_dofs << " dofs |\n"
    << "| elastic on rollers | " << s.rollers.cg_iterations << " CG iterations |\n";
  for (const FrictionalRun& f : s.frictional) {
    const fem::FrictionalColumnProblem& q = f.problem;
    m << "| " << f.label << " | walls mu " << fmt(q.walls.side[0]) << " " << fmt(q.walls.side[1]) << " "
      << fmt(q.walls.side[2]) << " " << fmt(q.walls.side[3]) << ", floor mu " << fmt(q.walls.floor)
      << ", tangential penalty " << q.walls.penalty_factor << " G/h; "
      << (q.loading.staged_construction ? std::string("built layer by layer")
                                        : std::to_string(q.loading.load_steps) + " load step(s)");
    if (q.material == fem::ColumnMaterial::drucker_prager) {
      const fem::DruckerPrager cone = fem::drucker_prager_cone(q.strength);
      m << "; phi " << q.strength.friction_angle_deg << " deg ("
        << s.in.study.continuum.source_of("friction angle") << "), psi " << q.strength.dilatancy_angle_deg
        << " deg (" << s.in.study.continuum.source_of("dilatancy angle") << "), c " << q.strength.cohesion
        << " Pa, " << matching_name(q.strength.matching) << " (eta " << fmt(cone.eta) << ", eta_bar "
        << fmt(cone.eta_bar) << ", xi " << fmt(cone.xi) << ")";
    }
    m << " |\n";
  }
  m << "| Janssen line | K = nu/(1-nu) = " << fmt(s.janssen.lateral_ratio)
    << ", friction perimeter sum mu_i L_i = " << fmt(s.janssen.friction_perimeter) << " m |\n"
    << "| continuum load | bulk density " << fmt(p.density) << " kg/m^3 = grain mass " << fmt(d.total_mass)
    << " kg / (footprint x " << fmt(p.height) << " m) |\n\n";
}

// Where the continua's material came from, value by value; with the study's own calibration,
// what it measured (docs/calibration.md).
void material_section(std::ostringstream& m, const StudyRecord& s) {
  const ContinuumOptions& c = s.in.study.continuum;
  m << "## The continua's material\n\n";
  if (c.calibrated)
    m << "Measured on this bed after the DEM run (`Continuum/material from`), by the oedometric and "
         "friction-angle tests of docs/calibration.md; the paths and the material "
         "file are "
         "in `calibration/`. Another study of the same scene can reuse the file (`Continuum/material file`) "
         "instead of measuring again.\n\n";
  else if (!c.calibration_skipped.empty())
    m << "The Continuum entries: the study did not measure the material on its bed, because "
      << c.calibration_skipped << ".\n\n";
  m << "| quantity | value | from |\n|---|---|---|\n"
    << "| Young's modulus E | " << fmt(c.youngs_modulus) << " Pa | " << c.source_of("youngs modulus")
    << " |\n"
    << "| Poisson's ratio nu | " << fmt(c.poisson_ratio)
    << " (K0 = nu/(1-nu) = " << fmt(c.poisson_ratio / (1.0 - c.poisson_ratio)) << ") | "
    << c.source_of("poisson ratio") << " |\n"
    << "| friction angle phi | " << fmt(c.friction_angle_deg) << " deg | " << c.source_of("friction angle")
    << " |\n"
    << "| dilatancy angle psi | " << fmt(c.dilatancy_angle_deg) << " deg | " << c.source_of("dilatancy angle")
    << " |\n\n";
  if (!s.calibration) return;
  const BedCalibration& b = *s.calibration;
  const dem::ElasticEquivalent& eq = b.elastic;
  const dem::FrictionStrength& st = b.strength;
  m << "| calibration | result |\n|---|---|\n"
    << "| oedometric test | ";
  if (b.oedometer.loading == OedometerLoading::gravity) {
    m << "by gravity: the bed's weight times ";
    for (std::size_t k = 0; k < b.oedometer.gravity_factors.size(); ++k)
      m << (k > 0 ? ", " : "") << fmt(b.oedometer.gravity_factors[k]);
    m << "; " << b.held << " of " << b.fitted_states << " states (its own weight's included) at rest";
  } else {
    m << (b.oedometer.loading == OedometerLoading::lid ? "by a servo lid: "
                                                       : "in a periodic cell, without walls: ")
      << b.oedometer.lid_stresses.size() << " targets from " << fmt(b.oedometer.lid_stresses.front())
      << " Pa, " << b.held << " of " << b.fitted_states << " held";
  }
  m << " (the bed's weight over the footprint is " << fmt(b.weight_stress)
    << " Pa); at the bed's mean vertical stress " << fmt(b.sigma_mean) << " Pa: M = " << fmt(eq.modulus)
    << " Pa (taken at " << fmt(eq.modulus_stress) << " Pa), K0 = " << fmt(eq.k0)
    << " (the bed before loading: " << fmt(b.k0_deposited) << "); " << fmt(b.oedometer_seconds, 3) << " s |\n"
    << "| friction-angle test | sigma_3 = " << fmt(b.triaxial.confining_stress) << " Pa, axial strain rate "
    << fmt(b.triaxial.strain_rate) << "/s (inertial number " << fmt(b.inertial_number, 2) << "): peak phi "
    << fmt(st.peak_angle) << " deg at axial strain " << fmt(st.peak_strain) << " with psi "
    << fmt(st.peak_dilatancy_angle) << " deg; critical state " << fmt(st.critical_angle) << " +- "
    << fmt(st.critical_spread) << " deg; the continua take the "
    << (b.critical_state_strength ? "critical state's" : "peak's") << "; " << fmt(b.triaxial_seconds, 3)
    << " s |\n"
    << "| Jaky's K0 = 1 - sin phi_cs | " << fmt(b.jaky_k0) << " (oedometric K0 " << fmt(eq.k0) << ") |\n\n";
}

void headline_section(std::ostringstream& m, const StudyRecord& s) {
  const dem::SceneConfig& sc = s.in.scene;
  const RunResult& r = s.run;
  const double area = sc.container.lx * sc.container.ly;
  const double weight = s.dem.total_mass * sc.gravity;
  const DemFemComparison& c = s.comparison;
  m << "## Headline figures\n\n";
  m << "- DEM run: " << r.steps << " steps, " << fmt(r.simulated_time) << " s simulated";
  if (r.relaxation)
    m << "; relaxed by FIRE in " << r.relaxation->steps << " steps to residual force "
      << fmt(r.relaxation->max_force_residual, 3) << " and torque "
      << fmt(r.relaxation->max_torque_residual, 3) << " (of m g, m g r)"
      << (r.relaxation->converged
              ? std::string()
              : "; **not converged**: the step limit (`Study/max relaxation steps`) ended it "
                "above `Study/relaxation tolerance`");
  m << ".\n"
    << wall_clock_line(r) << "- Weight over the floor area: " << fmt(weight / area)
    << " Pa. Floor force over area: " << fmt(-s.dem.floor_force.z() / area) << " Pa.\n";
  m << "- Share of the weight the side walls carry: DEM " << percent(c.dem_wall_share);
  for (const ContinuumResult& cr : c.continua) m << "; " << cr.label << " " << percent(cr.wall_share);
  m << ".\n- Elastic column on rollers against its analytic solution: relative L2 error of the stress "
    << fmt(s.rollers.l2_error_stress / fem::analytic_solution(s.rollers_problem).stress_l2_norm(area), 3)
    << ".\n";
  for (const FrictionalRun& f : s.frictional) {
    const fem::FrictionalColumnSolution& q = f.solution;
    m << "- " << f.label << ": " << q.newton_iterations << " Newton iterations (" << q.linear_iterations
      << " GMRES) in " << q.load_steps.size() << " load step(s)"
      << (q.bisections ? ", " + std::to_string(q.bisections) + " bisected" : std::string()) << ", "
      << fmt(q.total_seconds, 3) << " s; ";
    const auto& side = f.problem.walls.side;
    if (std::all_of(side.begin(), side.end(), [](double mu) { return mu == 0.0; }))
      m << "side walls frictionless";
    else
      m << "the side walls slip on " << percent(q.slipping_wall_share) << " of their loaded area";
    if (f.problem.material == fem::ColumnMaterial::drucker_prager)
      m << ", " << percent(q.plastic_volume_share) << " of the volume yielded";
    m << "; floor and walls carry the weight to "
      << fmt((q.floor_vertical_force + q.side_wall_vertical_force) / q.weight - 1.0, 2) << ".\n";
  }
  for (const auto& [label, why] : s.failed) m << "- **" << label << " is left out**: " << why << ".\n";
  for (const FormulaComparison* fc : ranked_formulas(c)) {
    const std::size_t best = fc->closest;
    m << "- **Closest to the DEM (" << dem::name_of(fc->formula) << "): " << c.continua[best].label << "**, "
      << "||Δσ|| / ||σ_zz,hydrostatic|| = " << fmt(fc->against[best].tensor, 3) << " (σ_zz alone "
      << fmt(fc->against[best].component[8], 3) << ")";
    for (std::size_t k = 0; k < c.continua.size(); ++k)
      if (k != best) m << "; " << c.continua[k].label << " " << fmt(fc->against[k].tensor, 3);
    m << ".\n";
  }
  m << "\n";
}

void comparison_section(std::ostringstream& m, const StudyRecord& s) {
  const DemFemComparison& c = s.comparison;
  m << "## DEM against the continua\n\n"
       "||σ_DEM − σ_continuum|| over the cells with grains, divided by ||σ_zz|| of the hydrostatic column, "
       "for "
       "the whole tensor and (in brackets) σ_zz alone.\n\n| formula";
  for (const ContinuumResult& cr : c.continua) m << " | " << cr.label;
  m << " |\n|---";
  for (std::size_t k = 0; k < c.continua.size(); ++k) m << "|---";
  m << "|\n";
  for (const FormulaComparison& fc : c.formulas) {
    m << "| " << dem::name_of(fc.formula);
    for (const Difference& d : fc.against)
      m << " | " << fmt(d.tensor, 3) << " (" << fmt(d.component[8], 3) << ")";
    m << " |\n";
  }
  m << "\n| source | share of the weight on the side walls | mean (σ_xx+σ_yy)/(2σ_zz) | largest level spread "
       "of σ_zz |\n|---|---|---|---|\n";
  for (const FormulaComparison& fc : c.formulas)
    m << "| DEM " << dem::name_of(fc.formula) << " | " << percent(c.dem_wall_share) << " | "
      << fmt(fc.mean_lateral_ratio, 3) << " | " << fmt(largest(fc.level_spread), 3) << " |\n";
  for (const ContinuumResult& cr : c.continua)
    m << "| " << cr.label << " | " << percent(cr.wall_share) << " | " << fmt(cr.mean_lateral_ratio, 3)
      << " | " << fmt(largest(cr.level_spread), 3) << " |\n";
  if (s.cg.done)
    m << "| coarse-grained field (" << s.cg.kernel << ", w = " << fmt(s.cg.width_in_diameters, 3)
      << " d), over the mesh | - | " << fmt(s.cg.comparison.lateral_ratio, 3) << " | "
      << fmt(s.cg.largest_level_spread(), 3) << " |\n";
  m << "\nThe column on frictionless rollers has a uniform σ_zz across each level (spread 0) and the ratio "
       "K0; "
       "walls with friction carry part of the weight (Janssen's effect), most near the walls, which spreads "
       "each "
       "level; the DEM bed adds the packing's own unevenness (Yan and Regueiro's microstructural effect, "
       "docs/stress.md).\n\n";
}

// The coarse-grained fields against the column on rollers, on its mesh (docs/coarse-graining.md).
void coarse_graining_section(std::ostringstream& m, const StudyRecord& s) {
  const CoarseGrainingOutcome& cg = s.cg;
  if (!cg.done) return;
  const double norm = cg.comparison.l2_continuum_zz;
  m << "## Coarse-grained fields on the mesh\n\n"
    << "Each grain and contact smoothed by a " << cg.kernel
    << " kernel of width w = " << fmt(cg.width_in_diameters, 3) << " d = " << fmt(cg.width, 3)
    << " m (d = " << fmt(cg.diameter, 4) << " m the mean grain diameter, cut-off " << fmt(cg.cutoff, 3)
    << " m), " << cg.grains << " grains, " << cg.branches << " branches, " << cg.wall_contacts
    << " wall contacts, evaluated at " << cg.comparison.points << " " << cg.points
    << " of the continuum's mesh (docs/coarse-graining.md). Against the elastic column on rollers, in the L2 "
       "norm over the mesh (its Gauss points), divided by its ||σ_zz||: σ_zz "
    << fmt(cg.comparison.l2_difference[8] / norm, 3) << ", σ_xx "
    << fmt(cg.comparison.l2_difference[0] / norm, 3) << ", σ_xz "
    << fmt(cg.comparison.l2_difference[2] / norm, 3)
    << ". Its level spread is over the levels of Gauss points a cut-off below the bed's top ("
    << fmt(cg.bed_top, 4) << " m).\n\n"
    << "- Momentum balance: largest |d(ρv)/dt + ∇·(ρvv) − ∇·σ − ρg − b| over the points = "
    << fmt(cg.residual, 3) << " of the largest |ρg| (d(ρv)/dt from the grains' accelerations)";
  if (std::isfinite(cg.residual_by_differences))
    m << "; with d(ρv)/dt by differences over " << fmt(cg.sampling_interval, 3)
      << " s: " << fmt(cg.residual_by_differences, 3);
  m << ".\n- The bed's own d(ρv)/dt (its distance from rest): " << fmt(cg.momentum_rate, 3) << " of ρg.\n"
    << "- Cost: " << fmt(cg.seconds, 3) << " s (distribution, evaluation, comparison and output).\n"
    << "- File: `mesh/cg_fields.pvtu` (fields `cg_*`, the continuum's `fem_s_*` and `diff_s_*` as cell "
       "means).\n\n";
}

// One table of a quantity against height, centre and edge columns: the continua, then the
// DEM formulas. `value(tensor)` picks the quantity.
template <class Pick>
void profile_table(std::ostringstream& m, const StudyRecord& s, const std::string& title, bool with_analytic,
                   Pick value) {
  const DemFemComparison& c = s.comparison;
  const dem::RegularGrid& g = c.grid;
  m << "## " << title << ", centre and edge columns\n\n| column | z (m)";
  if (with_analytic) m << " | hydrostatic";
  for (const ContinuumResult& cr : c.continua) m << " | " << cr.label;
  for (const FormulaComparison& fc : c.formulas) m << " | " << dem::name_of(fc.formula);
  m << " |\n|---|---";
  const std::size_t columns = (with_analytic ? 1 : 0) + c.continua.size() + c.formulas.size();
  for (std::size_t k = 0; k < columns; ++k) m << "|---";
  m << "|\n";
  for (auto [name, i, j] : {std::tuple<const char*, int, int>{"centre", c.centre_i, c.centre_j},
                            std::tuple<const char*, int, int>{"edge", c.edge_i, c.edge_j}}) {
    for (int k = g.n[2] - 1; k >= 0; --k) {
      const int cell = (k * g.n[1] + j) * g.n[0] + i;
      m << "| " << name << " | " << fmt(g.cell_centre(cell).z());
      if (with_analytic) m << " | " << fmt(c.analytic_szz[cell]);
      for (const ContinuumResult& cr : c.continua) m << " | " << fmt(value(cr.cells[cell]), 4);
      for (const FormulaComparison& fc : c.formulas) {
        const dem::Mat3& t = s.dem.stress[fc.formula][cell];
        Tensor9 e;
        for (int q = 0; q < 9; ++q) e[q] = t(q / 3, q % 3);
        m << " | " << fmt(value(e), 4);
      }
      m << " |\n";
    }
  }
  m << "\n";
}

// The side walls' shear against height (wall_shear_profile.h): the DEM's from its wall
// contacts, each continuum's, and what they sum to.
void wall_shear_section(std::ostringstream& m, const StudyRecord& s) {
  const DemFemComparison& c = s.comparison;
  const dem::RegularGrid& g = c.grid;
  m << "## Wall shear stress (Pa) against height\n\n"
       "The side walls' mean upward shear on the fill over each level of the grid: their upward force within "
       "the level over the perimeter times the level's height (positive: the walls carry weight). The DEM's "
       "is "
       "from its side-wall contacts at the final state, binned by their points' height"
    << (c.dem_wall_shear.empty() ? " (not recorded: the final step did not record its contacts)" : "")
    << ". The last row is the share of the weight the walls carry.\n\n| z (m) | DEM";
  for (const ContinuumResult& cr : c.continua) m << " | " << cr.label;
  m << " |\n|---|---";
  for (std::size_t k = 0; k < c.continua.size(); ++k) m << "|---";
  m << "|\n";
  const double dz = grid_levels(g).dz;
  const auto at = [](const std::vector<double>& v, int k) {
    return static_cast<std::size_t>(k) < v.size() ? fmt(v[static_cast<std::size_t>(k)], 4) : std::string("-");
  };
  for (int k = g.n[2] - 1; k >= 0; --k) {
    m << "| " << fmt(g.lo.z() + (k + 0.5) * dz) << " | " << at(c.dem_wall_shear, k);
    for (const ContinuumResult& cr : c.continua) m << " | " << at(cr.wall_shear, k);
    m << " |\n";
  }
  m << "| share of the weight | " << percent(c.dem_wall_share);
  for (const ContinuumResult& cr : c.continua) m << " | " << percent(cr.wall_share);
  m << " |\n\n";
}

}  // namespace

void write_report(const std::filesystem::path& folder, const StudyRecord& s) {
  std::ostringstream m;
  m << "# Upgrain study: DEM bed against the continua\n\n"
    << "Scene: `" << scene_source(s.in, s.run) << "`. Written by `upgrain` on " << s.ranks << " MPI rank(s). "
    << "How to read it: docs/study.md.\n\n";
  parameters_section(m, s);
  material_section(m, s);
  headline_section(m, s);
  comparison_section(m, s);
  coarse_graining_section(m, s);
  profile_table(m, s, "σ_zz (Pa) against height", true, [](const Tensor9& t) { return t[8]; });
  profile_table(m, s, "Lateral ratio (σ_xx+σ_yy)/(2σ_zz) against height", false,
                [](const Tensor9& t) { return t[8] != 0.0 ? 0.5 * (t[0] + t[4]) / t[8] : 0.0; });
  wall_shear_section(m, s);
  m << "## Plots\n\n";
  if (s.plots.empty())
    m << "No plots: /usr/bin/python3 with matplotlib was not available (the CSV tables hold the same "
         "data).\n";
  for (const std::string& p : s.plots) m << "![" << p << "](" << p << ")\n\n";
  m << "\n## Files\n\n- `comparison_cells.csv`, `profiles.csv`, `relative_l2.csv`, `stress_summary.csv`, "
       "`wall_shear.csv`: the "
       "tables above, in full.\n"
    << "- `mesh/dem_fem.pvtu`: DEM (per formula), the continua and the DEM's difference from the column on "
       "rollers as cell data on one mesh, with Q1 projections (ParaView).\n"
    << "- `fem/column.pvtu`, `fem_<variant>/column.pvtu`: each continuum's solution.\n"
    << (s.cg.done ? "- `mesh/cg_fields.pvtu`: the coarse-grained fields on the continuum's mesh.\n" : "")
    << "- `grid_stress.xdmf`, `particles.xdmf`: the DEM grid stress and particles over time.\n\n";
  if (s.run.final_strain) m << strain_section(s.in, *s.run.final_strain, folder, s.strain_plots);
  m << "## Timings (wall clock, rank 0)\n\n| stage | s |\n|---|---|\n";
  for (const auto& [stage, secs] : s.timings) m << "| " << stage << " | " << fmt(secs, 3) << " |\n";
  dem::io::write_text_atomically(folder / "report.md", m.str());
}

// The headline numbers in machine-readable form (tests/end_to_end/check_study.py).
void write_study_json(const std::filesystem::path& folder, const StudyRecord& s) {
  const double area = s.in.scene.container.lx * s.in.scene.container.ly;
  const fem::ConfinedColumn exact = fem::analytic_solution(s.rollers_problem);
  const DemOutcome& d = s.dem;
  const DemFemComparison& c = s.comparison;
  // Every number through json_number: a value that is not finite is written null.
  const auto n = [](double v) { return dem::io::json_number(v); };
  std::ostringstream j;
  j << "{\n  \"ranks\": " << s.ranks << ",\n  \"grid_cells\": [" << d.grid.n[0] << ", " << d.grid.n[1] << ", "
    << d.grid.n[2] << "],\n  \"grid_top_m\": " << n(d.grid.hi.z())
    << ",\n  \"cell_volume_m3\": " << n(d.stress.cell_volume) << ",\n  \"grain_mass_kg\": " << n(d.total_mass)
    << ",\n  \"weight_N\": " << n(d.total_mass * s.in.scene.gravity)
    << ",\n  \"floor_force_z_N\": " << n(d.floor_force.z())
    << ",\n  \"side_wall_force_z_N\": " << n(d.side_wall_vertical)
    << ",\n  \"dem_wall_share\": " << n(c.dem_wall_share) << ",\n  \"footprint_m2\": " << n(area)
    << ",\n  \"bulk_density\": " << n(s.rollers_problem.density) << ",\n  \"k0\": " << n(c.k0)
    << ",\n  \"fem_dofs\": " << s.rollers.n_dofs
    << ",\n  \"fem_relative_l2_error_stress\": " << n(s.rollers.l2_error_stress / exact.stress_l2_norm(area))
    << ",\n  \"fem_relative_l2_error_displacement\": "
    << n(s.rollers.l2_error_displacement / exact.displacement_l2_norm(area))
    << ",\n  \"fem_mean_lateral_ratio\": " << n(c.continua.front().mean_lateral_ratio);
  const ContinuumOptions& mat = s.in.study.continuum;
  j << ",\n  \"continuum_material\": {\"youngs_modulus_Pa\": " << n(mat.youngs_modulus)
    << ", \"poisson_ratio\": " << n(mat.poisson_ratio)
    << ", \"friction_angle_deg\": " << n(mat.friction_angle_deg)
    << ", \"dilatancy_angle_deg\": " << n(mat.dilatancy_angle_deg) << ", \"source\": \""
    << (mat.calibrated              ? "calibration"
        : mat.material_file.empty() ? "entries"
                                    : "material file")
    << "\"";
  if (!mat.material_file.empty()) j << ", \"file\": " << dem::io::json_string(mat.material_file);
  if (!mat.calibration_skipped.empty())
    j << ", \"calibration_skipped\": " << dem::io::json_string(mat.calibration_skipped);
  if (s.calibration) {
    std::string cal = bed_calibration_json(*s.calibration);
    for (std::size_t p = cal.find('\n'); p != std::string::npos; p = cal.find('\n', p + 1))
      cal.insert(p + 1, "  ");
    j << ",\n    \"calibration\": {\n  " << cal << "\n    }";
  }
  j << "}";
  const auto array = [&](const std::vector<double>& v) {
    std::string a = "[";
    for (std::size_t k = 0; k < v.size(); ++k) a += (k ? ", " : "") + n(v[k]);
    return a + "]";
  };
  j << ",\n  \"wall_shear_level_height_m\": " << n(grid_levels(d.grid).dz)
    << ",\n  \"box_perimeter_m\": " << n(box_perimeter(s.in.scene));
  j << ",\n  \"wall_shear_Pa\": {\"dem\": " << array(c.dem_wall_shear);
  for (const ContinuumResult& cr : c.continua) j << ", \"" << cr.key << "\": " << array(cr.wall_shear);
  j << "}";
  j << ",\n  \"continua\": {";
  for (std::size_t k = 0; k < c.continua.size(); ++k) {
    const ContinuumResult& cr = c.continua[k];
    j << (k ? "," : "") << "\n    \"" << cr.key << "\": {\"label\": \"" << cr.label
      << "\", \"wall_share\": " << n(cr.wall_share)
      << ", \"mean_lateral_ratio\": " << n(cr.mean_lateral_ratio)
      << ", \"largest_level_spread\": " << n(largest(cr.level_spread));
    for (const FrictionalRun& f : s.frictional) {
      if (f.key != cr.key) continue;
      const fem::FrictionalColumnSolution& q = f.solution;
      j << ", \"newton_iterations\": " << q.newton_iterations
        << ", \"linear_iterations\": " << q.linear_iterations << ", \"bisections\": " << q.bisections
        << ", \"seconds\": " << n(q.total_seconds)
        << ", \"slipping_wall_share\": " << n(q.slipping_wall_share)
        << ", \"plastic_volume_share\": " << n(q.plastic_volume_share)
        << ", \"floor_force_z_N\": " << n(q.floor_vertical_force) << ", \"weight_N\": " << n(q.weight);
    }
    j << "}";
  }
  j << "\n  },\n  \"failed_continua\": [";
  for (std::size_t k = 0; k < s.failed.size(); ++k) j << (k ? ", " : "") << "\"" << s.failed[k].first << "\"";
  j << "],\n  \"formulas\": {";
  for (std::size_t k = 0; k < c.formulas.size(); ++k) {
    const FormulaComparison& fc = c.formulas[k];
    j << (k ? "," : "") << "\n    \"" << dem::io::field_name(fc.formula)
      << "\": {\"relative_l2_zz\": " << n(fc.against[0].component[8])
      << ", \"relative_l2_xx\": " << n(fc.against[0].component[0])
      << ", \"mean_lateral_ratio\": " << n(fc.mean_lateral_ratio) << ", \"closest_continuum\": \""
      << c.continua[fc.closest].key << "\", \"against\": {";
    for (std::size_t m = 0; m < c.continua.size(); ++m)
      j << (m ? ", " : "") << "\"" << c.continua[m].key << "\": {\"tensor\": " << n(fc.against[m].tensor)
        << ", \"zz\": " << n(fc.against[m].component[8]) << "}";
    j << "}}";
  }
  j << "\n  }";
  if (s.cg.done) {
    const CoarseGrainingOutcome& cg = s.cg;
    const double norm = cg.comparison.l2_continuum_zz;
    j << ",\n  \"coarse_graining\": {\"kernel\": \"" << cg.kernel << "\", \"width_m\": " << n(cg.width)
      << ", \"width_diameters\": " << n(cg.width_in_diameters) << ", \"mean_diameter_m\": " << n(cg.diameter)
      << ", \"points\": " << cg.comparison.points << ", \"evaluation_points\": \"" << cg.points
      << "\", \"relative_l2_zz\": " << n(cg.comparison.l2_difference[8] / norm)
      << ", \"relative_l2_xx\": " << n(cg.comparison.l2_difference[0] / norm)
      << ", \"lateral_ratio\": " << n(cg.comparison.lateral_ratio)
      << ", \"largest_level_spread\": " << n(cg.largest_level_spread())
      << ", \"momentum_residual\": " << n(cg.residual) << ", \"momentum_rate\": " << n(cg.momentum_rate)
      << ", \"momentum_residual_by_differences\": " << n(cg.residual_by_differences)
      << ", \"seconds\": " << n(cg.seconds) << "}";
  }
  j << "\n}\n";
  dem::io::write_text_atomically(folder / "study.json", j.str());
}

}  // namespace upgrain::coupling
