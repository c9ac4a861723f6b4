#include "coupling/studies/continuum/strain_report.h"

#include <algorithm>
#include <sstream>

#include "coupling/studies/figure_script.h"
#include "coupling/studies/report_format.h"
#include "coupling/studies/run_account.h"
#include "dem/files/atomic_file.h"
#include "dem/io/grid_stress_output.h"
#include "upscale/grid_mesh.h"
#include "upscale/strain_fields.h"

#ifndef UPGRAIN_SCRIPT_DIR
#define UPGRAIN_SCRIPT_DIR ""
#endif

namespace upgrain::coupling {

namespace {

// Median, smallest and largest of the values of the cells marked valid; "-" when none.
std::string spread(const std::vector<double>& v, const std::vector<upscale::StrainReason>& reason) {
  std::vector<double> x;
  for (std::size_t c = 0; c < v.size(); ++c)
    if (reason[c] == upscale::StrainReason::valid) x.push_back(v[c]);
  if (x.empty()) return "-";
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  const double median = n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  return fmt(median, 3) + " [" + fmt(x.front(), 3) + ", " + fmt(x.back(), 3) + "]";
}

std::string collapse_of(const SceneInput& in) {
  const dem::BoxContainer& c = in.scene.container;
  if (c.has_gate())
    return "constrained collapse: gate at x = " + fmt(c.gate_x) +
           " m removed at t = " + fmt(c.gate_open_time) + " s";
  if (c.opens_side_walls())
    return "unconstrained collapse: all side walls removed at t = " + fmt(c.side_walls_open_time) + " s";
  return "none (closed box)";
}

}  // namespace

std::vector<std::string> plot_strain(const std::filesystem::path& folder) {
  return run_figure_script("studies/continuum/plot_strain.py", folder, "strain_plots.log",
                           {"strain_ln_J.png", "strain_shear.png", "strain_final_map.png"})
      .made;
}

std::string write_strain_mesh(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(folder / "grid_strain"))
    if (e.path().extension() == ".h5") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // by step: the names carry it zero-padded
  upscale::UpscaleOptions options;
  options.project_q1 = false;  // invalid cells are zeros: a projection would blend them in
  std::ostringstream pvd;
  pvd.precision(17);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const std::filesystem::path& f : files) {
    const upscale::GridFields fields = upscale::read_strain_fields(f);
    const std::string base = f.stem().string();  // grid_strain_<step>
    const std::string name = "strain" + base.substr(base.find_last_of('_'));
    (void)upscale::upscale_to_mesh(fields, MPI_COMM_SELF, folder / "strain_mesh", name, options);
    pvd << "    <DataSet timestep=\"" << fields.time << "\" part=\"0\" file=\"" << name << ".pvtu\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  dem::io::write_text_atomically(folder / "strain_mesh" / "strain.pvd", pvd.str());
  return "strain_mesh/strain.pvd";
}

std::string strain_section(const SceneInput& in, const upscale::GridStrain& g,
                           const std::filesystem::path& folder, const std::vector<std::string>& plots) {
  const upscale::GridStrainOutputOptions& st = in.output.grid_strain;
  long outputs = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(folder / "grid_strain", ec))
    if (e.path().extension() == ".h5") ++outputs;
  std::ostringstream m;
  m << "## Strain\n\n"
    << "Finite strain per grid cell (docs/strain.md), relative to the state at t0 = " << fmt(g.reference_time)
    << " s (step " << g.reference_step << "), " << upscale::name_of(g.set) << " sets, on a " << g.grid.n[0]
    << " x " << g.grid.n[1] << " x " << g.grid.n[2] << " grid; " << outputs
    << " outputs in `grid_strain/`, the last at t = " << fmt(g.time)
    << " s. The Jaumann, Green-Naghdi, Truesdell and Oldroyd rates of the " << dem::name_of(st.rate_formula)
    << " grid stress are written beside them, by backward differences over the outputs that have a grid "
       "stress (none at the first, first order at the second, second order from the third on).\n\n"
    << "At the last output (median [smallest, largest] over the valid cells):\n\n"
    << "| definition | cells with a valid F | ln J | equivalent shear strain | cells with a valid L |\n"
    << "|---|---|---|---|---|\n";
  for (int d = 0; d < upscale::kStrainDefinitionCount; ++d) {
    if (!g.computed[d]) continue;
    const upscale::CellStrainFields& f = g.fields[d];
    const auto valid = [](const std::vector<upscale::StrainReason>& r) {
      return std::count(r.begin(), r.end(), upscale::StrainReason::valid);
    };
    m << "| " << upscale::name_of(static_cast<upscale::StrainDefinition>(d)) << " | " << valid(f.f_reason)
      << " of " << g.grid.num_cells() << " | " << spread(f.log_jacobian, f.f_reason) << " | "
      << spread(f.equivalent_shear_strain, f.f_reason) << " | " << valid(f.l_reason) << " |\n";
  }
  m << "\nln J < 0 is compaction and > 0 dilation since t0; cells with fewer than 4 grains or a degenerate "
       "set have no F (reason codes in the files).\n\n";
  if (plots.empty())
    m << "No strain plots: /usr/bin/python3 with matplotlib and h5py was not available (`grid_strain.csv` "
         "holds the same data).\n\n";
  for (const std::string& p : plots) m << "![" << p << "](" << p << ")\n\n";
  m << "Files: `grid_strain.xdmf` (ParaView: ln J, equivalent shear strain, F, L and the rates as cell "
       "data over time), `grid_strain.csv`, `grid_strain/*.h5` (every tensor at full precision), "
       "`strain_mesh/strain.pvd` (every output on the deal.II mesh, a time series for ParaView: ln J, "
       "equivalent shear strain, F and ln V components, F_valid as cell data).\n\n";
  return m.str();
}

void write_run_report(const std::filesystem::path& folder, const SceneInput& in, const RunResult& r,
                      const std::vector<std::string>& plots) {
  const dem::SceneConfig& s = in.scene;
  std::ostringstream m;
  m << "# Upgrain run\n\n"
    << "Scene: `" << scene_source(in, r)
    << "`. Written by `upgrain` (no continuum study: 'Study/compare with continuum' "
    << "is false).\n\n## Parameters\n\n| quantity | value |\n|---|---|\n"
    << "| grains | " << s.particles.count << grain_kind(s.particles.shapes)
    << (s.particles.gradation.empty() ? fmt(s.particles.radius) + " m" : std::string("by gradation curve"))
    << ", density " << s.particles.material.density << " kg/m^3, E " << s.particles.material.youngs_modulus
    << " Pa |\n"
    << "| contact | friction " << s.friction << ", damping ratio " << s.damping_ratio << " |\n"
    << "| container | " << s.container.lx << " m x " << s.container.ly << " m |\n"
    << "| collapse | " << collapse_of(in) << " |\n"
    << "| time step, end time | " << s.time_step << " s, " << s.end_time << " s |\n\n"
    << "## Run\n\n- " << r.steps << " steps, " << fmt(r.simulated_time) << " s simulated"
    << (r.stopped_at_rest ? ", stopped at rest" : "") << ".\n"
    << wall_clock_line(r) << "- Energy balance error " << fmt(r.energy_balance_error, 3)
    << ", kinetic / released " << fmt(r.kinetic_to_released, 3) << "; " << r.bed.particles_outside
    << " grains outside the box's footprint.\n\n";
  if (r.final_strain) m << strain_section(in, *r.final_strain, folder, plots);
  dem::io::write_text_atomically(folder / "report.md", m.str());
}

}  // namespace upgrain::coupling
