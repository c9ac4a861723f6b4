#include "coupling/studies/element/element_study.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "coupling/run/scene_run.h"
#include "coupling/studies/dem_run.h"
#include "coupling/studies/element/element_run.h"
#include "coupling/studies/figure_script.h"
#include "coupling/studies/report_format.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

std::string isotropic_table(const ElementResult& r) {
  std::ostringstream t;
  t << "# Upgrain isotropic compression on a periodic cell (docs/element-tests.md). SI units, compression "
       "positive. p_x, p_y, p_z: -sigma_dd of the cell (Love-Weber and kinetic parts) averaged over the last "
       "quarter of the servo's hold; solid_fraction and coordination (2 contacts / grains) at its end; "
       "bulk_modulus = (p_after - p_before) / volumetric_strain of the isotropic strain step between two "
       "still cells\n"
       "target,p_x,p_y,p_z,p,relative_error,solid_fraction,contacts,coordination,p_before,p_after,"
       "volumetric_strain,bulk_modulus\n";
  for (const IsotropicRecord& k : r.isotropic)
    t << table_number(k.target) << ',' << table_number(k.pressure[0]) << ',' << table_number(k.pressure[1])
      << ',' << table_number(k.pressure[2]) << ',' << table_number(k.mean_pressure) << ','
      << table_number(k.mean_pressure / k.target - 1.0) << ',' << table_number(k.solid_fraction) << ','
      << k.contacts << ',' << table_number(k.coordination) << ',' << table_number(k.pressure_before) << ','
      << table_number(k.pressure_after) << ',' << table_number(k.volumetric_strain) << ','
      << table_number(k.bulk_modulus) << '\n';
  return t.str();
}

std::string triaxial_table(const ElementResult& r) {
  std::ostringstream t;
  t << "# Upgrain drained triaxial compression on a periodic cell (docs/element-tests.md). SI units, "
       "compression positive. Record 0: the last isotropic state; then z shortened at the prescribed rate, x "
       "and y servo to sigma_3. axial_strain = 1 - h_z/h_z0, volumetric_strain = 1 - V/V_0; sigma_1 = "
       "-sigma_zz, "
       "sigma_3 = -(sigma_xx + sigma_yy)/2 averaged over the steps since the record before; p = (sigma_1 + 2 "
       "sigma_3)/3, q = sigma_1 - sigma_3; phi_mobilised = asin(q / (sigma_1 + sigma_3)) in degrees\n"
       "record,time,axial_strain,volumetric_strain,sigma_1,sigma_3,p,q,q_over_p,phi_mobilised,solid_fraction,"
       "coordination\n";
  for (std::size_t k = 0; k < r.triaxial.size(); ++k) {
    const ElementTriaxialRecord& x = r.triaxial[k];
    const dem::TriaxialState& s = x.state;
    const double sum = s.axial_stress + s.lateral_stress;
    t << k << ',' << table_number(x.time) << ',' << table_number(s.axial_strain) << ','
      << table_number(s.volumetric_strain) << ',' << table_number(s.axial_stress) << ','
      << table_number(s.lateral_stress) << ',' << table_number(x.mean_stress) << ','
      << table_number(x.deviator) << ',' << table_number(x.deviator / x.mean_stress) << ','
      << (sum > 0.0 ? table_number(dem::mobilised_friction_angle(s.axial_stress, s.lateral_stress)) : "")
      << ',' << table_number(x.solid_fraction) << ',' << table_number(x.coordination) << '\n';
  }
  return t.str();
}

std::string shear_table(const ElementResult& r) {
  std::ostringstream t;
  t << "# Upgrain simple shear at a constant normal stress on a periodic cell (docs/element-tests.md). SI "
       "units, compression positive. One row per inertial number, the means over the last half of its shear "
       "strain: shear_rate = L_xz; inertial_number = shear_rate d sqrt(rho / P) with P = -sigma_zz; friction "
       "= "
       "mean tau / mean P, tau = (sigma_xz + sigma_zx) / 2; friction_spread the standard deviation of tau / "
       "P "
       "over the states; p = -tr sigma / 3; phi_mobilised = asin((s1 - s3) / (s1 + s3)) of the principal "
       "compressions in degrees, b = (s2 - s3) / (s1 - s3) and phi_matsuoka_nakai, the triaxial compression "
       "angle with the same I1 I2 / I3 (Matsuoka & Nakai 1974), each the mean of the states'\n"
       "target_inertial_number,shear_rate,steps,inertial_number,friction,friction_spread,normal_stress,p,"
       "phi_mobilised,b,phi_matsuoka_nakai,solid_fraction,coordination,fitted_friction,fitted_solid_"
       "fraction\n";
  const bool fitted = r.rheology_error.empty();
  for (const ShearSteadyState& x : r.shear)
    t << table_number(x.target_inertial_number) << ',' << table_number(x.shear_rate) << ',' << x.steps << ','
      << table_number(x.inertial_number) << ',' << table_number(x.friction) << ','
      << table_number(x.friction_spread) << ',' << table_number(x.normal_stress) << ','
      << table_number(x.mean_stress) << ',' << table_number(x.mobilised_angle) << ','
      << table_number(x.intermediate_ratio) << ',' << table_number(x.matsuoka_nakai_angle) << ','
      << table_number(x.solid_fraction) << ',' << table_number(x.coordination) << ','
      << (fitted ? table_number(r.mu_of_i(x.inertial_number)) : "") << ','
      << (fitted ? table_number(r.phi_of_i(x.inertial_number)) : "") << '\n';
  return t.str();
}

std::string shear_path_table(const ElementResult& r) {
  std::ostringstream t;
  t << "# Upgrain simple shear path (docs/element-tests.md): 20 states per inertial number, the stresses "
       "averaged over the steps since the state before, compression positive; shear_strain from the start of "
       "that inertial number's shear\n"
       "target_inertial_number,shear_strain,tau,normal_stress,p,friction,phi_mobilised,b,phi_matsuoka_nakai,"
       "solid_fraction,coordination\n";
  for (const ShearPathRecord& x : r.shear_path)
    t << table_number(x.target_inertial_number) << ',' << table_number(x.shear_strain) << ','
      << table_number(x.shear_stress) << ',' << table_number(x.normal_stress) << ','
      << table_number(x.mean_stress) << ',' << table_number(x.shear_stress / x.normal_stress) << ','
      << table_number(x.mobilised_angle) << ',' << table_number(x.intermediate_ratio) << ','
      << table_number(x.matsuoka_nakai_angle) << ',' << table_number(x.solid_fraction) << ','
      << table_number(x.coordination) << '\n';
  return t.str();
}

// Why the tests give no material the continuum takes (E > 0, 0 <= nu <= 0.499, phi in
// [0.1, 89]), or "".
std::string material_error(const ElementResult& r) {
  if (!r.strength_error.empty()) return "no friction angle: " + r.strength_error;
  std::ostringstream m;
  if (!(r.e50 > 0.0))
    m << "no E50 (the deviator did not rise from the isotropic state)";
  else if (!(r.poisson_ratio >= 0.0 && r.poisson_ratio <= 0.499))
    m << "Poisson's ratio (3 K - E50) / (6 K) = " << r.poisson_ratio
      << " is outside [0, 0.499] (K = " << r.isotropic.back().bulk_modulus << " Pa, E50 = " << r.e50
      << " Pa)";
  else if (!(r.strength.peak_angle >= 0.1 && r.strength.peak_angle <= 89.0))
    m << "the peak friction angle " << r.strength.peak_angle << " deg is outside [0.1, 89]";
  return m.str();
}

std::string material_file(const std::string& source, const ElementResult& r) {
  const IsotropicRecord& last = r.isotropic.back();
  const dem::FrictionStrength& s = r.strength;
  std::ostringstream m;
  m << "# Upgrain material from the element tests (docs/element-tests.md) of " << source << " on a periodic\n"
    << "# cell: the bulk modulus K = " << table_number(last.bulk_modulus)
    << " Pa at p = " << table_number(last.mean_pressure)
    << " Pa (isotropic.csv), the secant modulus E50 = " << table_number(r.e50) << " Pa of the drained\n"
    << "# triaxial compression at sigma_3 = " << table_number(r.confining_pressure)
    << " Pa (triaxial.csv); nu = (3 K - E50) / (6 K). Peak phi = " << table_number(s.peak_angle)
    << " deg at axial strain " << table_number(s.peak_strain)
    << "\n# with psi = " << table_number(s.peak_dilatancy_angle)
    << " deg; critical state phi = " << table_number(s.critical_angle) << " +- "
    << table_number(s.critical_spread) << " deg. The continuum takes the peak's (psi clamped to [0, phi]).\n"
    << "subsection Continuum\n"
    << "  set youngs modulus = " << table_number(r.e50) << "\n"
    << "  set poisson ratio = " << table_number(r.poisson_ratio) << "\n"
    << "  set friction angle = " << table_number(s.peak_angle) << "\n"
    << "  set dilatancy angle = " << table_number(std::clamp(s.peak_dilatancy_angle, 0.0, s.peak_angle))
    << "\n"
    << "end\n";
  return m.str();
}

std::string report_section(const ElementResult& r, const std::string& why_no_material, bool plots) {
  std::ostringstream m;
  const dem::FrictionStrength& s = r.strength;
  m << "## Element test\n\n"
    << r.particles
    << " grains in a fully periodic cell, without gravity or walls (docs/element-tests.md).\n\n"
    << "### Isotropic compression\n\n"
    << "| target p (Pa) | p reached (Pa) | error | solid fraction | coordination | K (Pa) "
       "|\n|---|---|---|---|---|---|\n";
  for (const IsotropicRecord& k : r.isotropic) {
    char row[256];
    std::snprintf(row, sizeof row, "| %.4g | %.6g | %+.2f %% | %.4f | %.3f | %.4g |\n", k.target,
                  k.mean_pressure, 100.0 * (k.mean_pressure / k.target - 1.0), k.solid_fraction,
                  k.coordination, k.bulk_modulus);
    m << row;
  }
  char text[1024];
  std::snprintf(
      text, sizeof text,
      "\n### Drained triaxial compression\n\nsigma_3 = %.4g Pa, axial strain rate with inertial number "
      "I = %.3g%s. Peak friction angle %.2f deg at eps_1 = %.4f with dilatancy angle %.2f deg; "
      "critical state %.2f +- %.2f deg (d eps_v / d eps_1 = %.3f there). E50 = %.4g Pa, "
      "nu = %.3f.\n\n",
      r.confining_pressure, r.inertial_number,
      r.inertial_number > 1e-3 ? " (above 1e-3: not quasi-static)" : "", s.peak_angle, s.peak_strain,
      s.peak_dilatancy_angle, s.critical_angle, s.critical_spread, s.critical_rate_ratio, r.e50,
      r.poisson_ratio);
  m << text;
  m << (why_no_material.empty() ? "Material: `material.prm`.\n"
                                : "No material file: " + why_no_material + ".\n");
  if (!r.shear.empty()) {
    m << "\n### Simple shear at a constant normal stress\n\nP = " << table_number(r.confining_pressure)
      << " Pa; each inertial number sheared from the one before (the first from the last isotropic state), "
         "the steady state over the last half of its strain.\n\n"
      << "| I | friction tau/P | spread | phi mobilised (deg) | b | phi Matsuoka-Nakai (deg) | solid "
         "fraction | "
         "coordination |\n|---|---|---|---|---|---|---|---|\n";
    for (const ShearSteadyState& x : r.shear) {
      char row[256];
      std::snprintf(row, sizeof row, "| %.4g | %.4f | %.4f | %.2f | %.3f | %.2f | %.4f | %.3f |\n",
                    x.inertial_number, x.friction, x.friction_spread, x.mobilised_angle, x.intermediate_ratio,
                    x.matsuoka_nakai_angle, x.solid_fraction, x.coordination);
      m << row;
    }
    if (r.rheology_error.empty()) {
      char fit[512];
      std::snprintf(fit, sizeof fit,
                    "\nmu(I) = mu_s + (mu_2 - mu_s) / (1 + I0 / I): mu_s = %.4f, mu_2 = %.4f, I0 = %.4g "
                    "(rms %.2g)%s; phi(I) = %.4f - %.4f I (rms %.2g).\n",
                    r.mu_of_i.mu_s, r.mu_of_i.mu_2, r.mu_of_i.i0, r.mu_of_i.rms,
                    r.mu_of_i.i0_at_bound ? ", I0 at the end of its search: the points do not bound it" : "",
                    r.phi_of_i.phi_max, r.phi_of_i.slope, r.phi_of_i.rms);
      m << fit;
    } else {
      m << "\nNo mu(I) fit: " << r.rheology_error << ".\n";
    }
  }
  m << "\nPaths: `isotropic.csv`, `triaxial.csv`"
    << (r.shear.empty() ? "" : ", `shear.csv`, `shear_path.csv`")
    << (plots ? std::string("; plots `isotropic.png`, `triaxial.png`") +
                    (r.shear.empty() ? "" : ", `shear.png`") + " (plot_element.py).\n"
              : std::string(".\n"));
  return m.str();
}

}  // namespace

int run_element_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks) {
  // The scene was checked by the study's own checks (element_checks.h): every axis periodic.
  const ElementResult r = run_element_tests(in.scene, fill_on_root(in.scene, comm), in.element, comm,
                                            engine_options(in), hooks.progress);
  on_rank0(comm, [&] {
    const fs::path folder = fs::path(in.output.folder) / "element";
    dem::io::create_folder(folder);
    dem::io::write_text_atomically(folder / "isotropic.csv", isotropic_table(r));
    dem::io::write_text_atomically(folder / "triaxial.csv", triaxial_table(r));
    if (!r.shear.empty()) {
      dem::io::write_text_atomically(folder / "shear.csv", shear_table(r));
      dem::io::write_text_atomically(folder / "shear_path.csv", shear_path_table(r));
    }
    const std::string why = material_error(r);
    if (why.empty()) dem::io::write_text_atomically(folder / "material.prm", material_file(in.source, r));
    // The summary first: the plots draw the fits from it.
    using dem::io::json_number;
    const dem::FrictionStrength& s = r.strength;
    std::ostringstream j;
    j << "{\n  \"study\": \"element\",\n  \"particles\": " << r.particles
      << ",\n  \"wall_time_s\": " << json_number(r.isotropic_seconds + r.triaxial_seconds + r.shear_seconds)
      << ",\n  \"pressures_Pa\": [";
    for (std::size_t k = 0; k < r.isotropic.size(); ++k)
      j << (k ? ", " : "") << json_number(r.isotropic[k].mean_pressure);
    j << "],\n  \"solid_fractions\": [";
    for (std::size_t k = 0; k < r.isotropic.size(); ++k)
      j << (k ? ", " : "") << json_number(r.isotropic[k].solid_fraction);
    j << "],\n  \"coordination_numbers\": [";
    for (std::size_t k = 0; k < r.isotropic.size(); ++k)
      j << (k ? ", " : "") << json_number(r.isotropic[k].coordination);
    j << "],\n  \"bulk_moduli_Pa\": [";
    for (std::size_t k = 0; k < r.isotropic.size(); ++k)
      j << (k ? ", " : "") << json_number(r.isotropic[k].bulk_modulus);
    j << "],\n  \"confining_pressure_Pa\": " << json_number(r.confining_pressure)
      << ",\n  \"inertial_number\": " << json_number(r.inertial_number)
      << ",\n  \"peak_friction_angle_deg\": " << json_number(s.peak_angle)
      << ",\n  \"peak_axial_strain\": " << json_number(s.peak_strain)
      << ",\n  \"peak_dilatancy_angle_deg\": " << json_number(s.peak_dilatancy_angle)
      << ",\n  \"critical_friction_angle_deg\": " << json_number(s.critical_angle)
      << ",\n  \"critical_friction_angle_spread_deg\": " << json_number(s.critical_spread)
      << ",\n  \"critical_volumetric_rate_ratio\": " << json_number(s.critical_rate_ratio)
      << ",\n  \"e50_Pa\": " << json_number(r.e50)
      << ",\n  \"poisson_ratio\": " << json_number(r.poisson_ratio)
      << ",\n  \"material_file\": " << (why.empty() ? "true" : "false")
      << ",\n  \"shear_inertial_numbers\": [";
    for (std::size_t k = 0; k < r.shear.size(); ++k)
      j << (k ? ", " : "") << json_number(r.shear[k].inertial_number);
    j << "],\n  \"shear_friction\": [";
    for (std::size_t k = 0; k < r.shear.size(); ++k) j << (k ? ", " : "") << json_number(r.shear[k].friction);
    j << "],\n  \"shear_solid_fractions\": [";
    for (std::size_t k = 0; k < r.shear.size(); ++k)
      j << (k ? ", " : "") << json_number(r.shear[k].solid_fraction);
    const bool fit = r.rheology_error.empty();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    j << "],\n  \"mu_s\": " << json_number(fit ? r.mu_of_i.mu_s : nan)
      << ",\n  \"mu_2\": " << json_number(fit ? r.mu_of_i.mu_2 : nan)
      << ",\n  \"I0\": " << json_number(fit ? r.mu_of_i.i0 : nan)
      << ",\n  \"I0_at_bound\": " << (fit && r.mu_of_i.i0_at_bound ? "true" : "false")
      << ",\n  \"phi_max\": " << json_number(fit ? r.phi_of_i.phi_max : nan)
      << ",\n  \"phi_slope\": " << json_number(fit ? r.phi_of_i.slope : nan) << "\n}\n";
    dem::io::write_text_atomically(fs::path(in.output.folder) / "summary.json", j.str());
    std::vector<std::string> figures = {"isotropic.png", "triaxial.png"};
    if (!r.shear.empty()) figures.emplace_back("shear.png");
    const FigureRun plots =
        run_figure_script("studies/element/plot_element.py", folder, "plots.log", figures);
    dem::io::write_text_atomically(folder / "report.md", report_section(r, why, plots.succeeded));
    std::printf(
        "\n  element tests: %ld grains, isotropic %.1f s, triaxial %.1f s, shear %.1f s of wall clock\n",
        r.particles, r.isotropic_seconds, r.triaxial_seconds, r.shear_seconds);
    for (const IsotropicRecord& k : r.isotropic)
      std::printf("    p* %.4g Pa: p %.6g Pa (%+.2f %%), phi %.4f, Z %.3f, K %.4g Pa\n", k.target,
                  k.mean_pressure, 100.0 * (k.mean_pressure / k.target - 1.0), k.solid_fraction,
                  k.coordination, k.bulk_modulus);
    std::printf(
        "    triaxial at sigma_3 %.4g Pa, I %.3g: peak phi %.2f deg at eps_1 %.4f, psi %.2f deg; "
        "critical phi %.2f +- %.2f deg; E50 %.4g Pa, nu %.3f\n",
        r.confining_pressure, r.inertial_number, s.peak_angle, s.peak_strain, s.peak_dilatancy_angle,
        s.critical_angle, s.critical_spread, r.e50, r.poisson_ratio);
    for (const ShearSteadyState& x : r.shear)
      std::printf(
          "    shear at P %.4g Pa, I %.4g: mu %.4f +- %.4f, phi_m %.2f deg, b %.3f, phi_MN %.2f deg, solid "
          "fraction "
          "%.4f, Z %.3f\n",
          x.normal_stress, x.inertial_number, x.friction, x.friction_spread, x.mobilised_angle,
          x.intermediate_ratio, x.matsuoka_nakai_angle, x.solid_fraction, x.coordination);
    if (!r.shear.empty() && r.rheology_error.empty())
      std::printf("    mu(I): mu_s %.4f, mu_2 %.4f, I0 %.4g%s; phi(I) = %.4f - %.4f I\n", r.mu_of_i.mu_s,
                  r.mu_of_i.mu_2, r.mu_of_i.i0, r.mu_of_i.i0_at_bound ? " (at its bound)" : "",
                  r.phi_of_i.phi_max, r.phi_of_i.slope);
    else if (!r.shear.empty())
      std::printf("    no mu(I) fit: %s\n", r.rheology_error.c_str());
    if (!why.empty()) std::printf("    no material file: %s\n", why.c_str());
    std::printf("  results: %s/{isotropic.csv,triaxial.csv%s%s,report.md}, %s/summary.json\n", folder.c_str(),
                r.shear.empty() ? "" : ",shear.csv,shear_path.csv", why.empty() ? ",material.prm" : "",
                in.output.folder.c_str());
  });
  return 0;
}

}  // namespace upgrain::coupling
