// The FEMxDEM section: the specimen, mesh, loading and DEM cells of `upgrain --study femxdem`
// (docs/femxdem.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class... Members>
auto femxdem(Members... m) {
  return at(&SceneInput::femxdem, m...);
}

}  // namespace

Section femxdem_section() {
  return {
      "FEMxDEM",
      {choice("loading", femxdem(&FemxdemOptions::loading),
              {{"biaxial", FemxdemLoading::biaxial}, {"gravity column", FemxdemLoading::gravity_column}},
              "biaxial: the bottom (y = 0) fixed, the top a platen that shortens the specimen by 'axial "
              "strain', the sides under the confining pressure. gravity column: the specimen under its own "
              "weight (gravity along -y, Effects/gravity acceleration, grown in 'load steps'), the sides on "
              "rollers, the bottom fixed, the top under the confining pressure (docs/femxdem.md)."),
       real("width", femxdem(&FemxdemOptions::width), 1e-6, 1e6, "m",
            "The specimen [0, width] x [0, height] in plane strain in x-y, per unit thickness along z."),
       real("height", femxdem(&FemxdemOptions::height), 1e-6, 1e6, "m", "The specimen's extent along y."),
       integer("cells x", femxdem(&FemxdemOptions::cells_x), 1, 1000, "-",
               "Elements across the width; each has (quadrature points)^2 DEM cells, one per Gauss point."),
       integer("cells y", femxdem(&FemxdemOptions::cells_y), 1, 1000, "-", "Elements along the height."),
       integer("degree", femxdem(&FemxdemOptions::degree), 1, 4, "-", "FE_Q degree of the displacement."),
       integer("quadrature points", femxdem(&FemxdemOptions::quadrature_points), 0, 5, "-",
               "Gauss points per direction in an element (0: degree + 1). One, with degree 1, is the reduced "
               "rule of a single-element test: a mesh of such elements has hourglass modes."),
       choice("platens", femxdem(&FemxdemOptions::rough_platens), {{"rough", true}, {"smooth", false}},
              "Rough platens hold the specimen's ends (no tangential motion), smooth ones let them slide."),
       real(
           "confining pressure", femxdem(&FemxdemOptions::rve, &RveOptions::mean_stress), 1.0, 1e9, "Pa",
           "The pressure on the specimen's sides (biaxial) or top (gravity column), and the isotropic stress "
           "every DEM cell is prepared at."),
       real("axial strain", femxdem(&FemxdemOptions::axial_strain), 1e-7, 0.5, "-",
            "The top platen's shortening of the specimen over the loading."),
       integer("load steps", femxdem(&FemxdemOptions::load_steps), 1, 100000, "-",
               "Equal steps of the axial strain; a step whose Newton iteration or DEM cell fails is cut in "
               "half, up to 'max step cuts' times."),
       real("residual tolerance", femxdem(&FemxdemOptions::residual_tolerance), 0.0, 1.0, "-",
            "Newton ends when the out-of-balance force is below this fraction of the internal force ..."),
       real("correction tolerance", femxdem(&FemxdemOptions::correction_tolerance), 0.0, 1.0, "-",
            "... or when the last correction is below this fraction of the step's displacement increment "
            "(Guo and Zhao 2014: 1e-2; 0: not used)."),
       integer("max newton iterations", femxdem(&FemxdemOptions::max_newton_iterations), 1, 1000, "-",
               "Newton iterations of a step before it is cut."),
       integer("line search halvings", femxdem(&FemxdemOptions::line_search_halvings), 0, 30, "-",
               "Halvings of a Newton correction that a DEM cell cannot take or that does not decrease the "
               "out-of-balance force (a backtracking line search, docs/femxdem.md); 0: plain Newton."),
       integer("max step cuts", femxdem(&FemxdemOptions::max_step_cuts), 0, 30, "-",
               "Halvings of a failing step in a row before the study stops with the step, cell and point."),
       real("rebalance threshold", femxdem(&FemxdemOptions::rebalance_threshold), 0.0, 1e6, "-",
            "After a load step in which the busiest rank's DEM cells took more than this times the ranks' "
            "mean grain-steps, the mesh is repartitioned with each element weighted by its cells' "
            "grain-steps, and the cells move with their elements (docs/femxdem.md); 0: never. Values "
            "between 0 and 1 are refused."),
       integer("grains per cell", femxdem(&FemxdemOptions::rve, &RveOptions::grains), 10, 100000, "-",
               "Grains in each DEM cell (a fully periodic cube of the scene's particles, prepared once and "
               "copied to every Gauss point)."),
       integer("cell seed", femxdem(&FemxdemOptions::rve, &RveOptions::seed), 0, 2147483647, "-",
               "Seed of the DEM cell's random placement (the first packing's)."),
       integer("cell packings", femxdem(&FemxdemOptions::cell_packings), 0, 100000, "-",
               "Distinct DEM cells, prepared with the seeds cell seed, cell seed + 1, ...: each Gauss point "
               "copies the one its place picks (the same on any rank count). 1: one cell copied to every "
               "point, a specimen that stays symmetric; more: point-to-point scatter, which triggers "
               "localisation; 0: every point its own packing (docs/femxdem.md)."),
       text("cell snapshots", femxdem(&FemxdemOptions::cell_snapshots), "-",
            "The DEM cells whose grains are written after every converged load step, as HDF5 snapshots "
            "with an XDMF series per cell for ParaView (femxdem/cells/E_P/): 'all', or a comma-separated "
            "list of element:point, as points.csv numbers them (the element is the first number of its "
            "cell column, the point its point column); empty: none."),
       real("preparation friction", femxdem(&FemxdemOptions::rve, &RveOptions::preparation_friction), -1.0,
            10.0, "-",
            "The grains' friction coefficient while the DEM cell is squeezed to the confining pressure: the "
            "lower, the denser the cell (0: the densest, a dilatant cell with a peak); -1: the scene's "
            "Contact/friction coefficient, a looser cell. The trials use the scene's coefficient."),
       real("steps per unit strain", femxdem(&FemxdemOptions::rve, &RveOptions::steps_per_unit_strain), 1.0,
            1e9, "-",
            "A DEM cell deforms by an increment Delta H in max(this max|Delta H_ij|, 2) steps (Guo and Zhao "
            "2014: 1e5)."),
       real("unbalanced force tolerance",
            femxdem(&FemxdemOptions::rve, &RveOptions::unbalanced_force_tolerance), 1e-12, 1.0, "-",
            "A deformed DEM cell is held still until its mean resultant force is below this fraction of its "
            "mean contact force (Yade's unbalancedForce) ..."),
       integer("relaxation step cap", femxdem(&FemxdemOptions::rve, &RveOptions::relaxation_step_cap), 1, 1e9,
               "-",
               "... or for at most this many steps: then the cell has not converged and the step is cut."),
       choice("relaxation", femxdem(&FemxdemOptions::rve, &RveOptions::relaxation),
              {{"damped", RveRelaxation::damped}, {"fire", RveRelaxation::fire}},
              "How the held cell reaches that ratio: its own dynamics damped by the contact dashpots, or "
              "steered by FIRE (velocities turned towards the forces, every grain stopped when the power "
              "turns negative; docs/femxdem.md)."),
       choice(
           "tangent", femxdem(&FemxdemOptions::rve, &RveOptions::tangent),
           {{"contact stiffness", RveTangent::contact_stiffness},
            {"perturbation", RveTangent::perturbation},
            {"elastic", RveTangent::elastic}},
           "The DEM cell's tangent: (1/V) sum over contacts of the contact stiffness (Kruyt and Rothenburg "
           "1998), forward differences of four extra trials (xx, yy, zz, xy), or the prepared cell's contact "
           "tangent kept "
           "fixed (docs/femxdem.md).")},
      nullptr};
}

}  // namespace upgrain::coupling::input
