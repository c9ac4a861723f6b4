#include "coupling/parameter_schema.h"

#include <algorithm>

#include "dem/contact/contact_laws.h"

namespace upgrain::coupling {

namespace {

// Contact/law and every law's own parameters, from the law table, after the other Contact
// entries. A parameter two laws share is declared once.
std::vector<ParameterSpec> with_contact_laws(std::vector<ParameterSpec> schema) {
  std::string names;
  std::string doc = "Contact law (docs/contact-law.md).";
  std::vector<ParameterSpec> rows;
  for (const dem::LawInfo& law : dem::contact_law_table()) {
    if (!names.empty()) names += '|';
    names += law.name;
    doc += std::string(" ") + law.name + ": " + law.description;
    for (const dem::LawParameter& p : law.parameters) {
      const bool known =
          std::any_of(rows.begin(), rows.end(), [&](const ParameterSpec& r) { return r.name == p.name; });
      if (!known)
        rows.push_back({"Contact", p.name, p.default_value, Kind::real, p.min, p.max, "", p.unit, p.doc});
    }
  }
  rows.insert(rows.begin(), ParameterSpec{"Contact", "law", dem::contact_law_table().front().name,
                                          Kind::selection, 0, 0, names, "-", doc});
  auto last_contact = std::find_if(schema.rbegin(), schema.rend(),
                                   [](const ParameterSpec& p) { return p.section == "Contact"; });
  schema.insert(last_contact.base(), rows.begin(), rows.end());
  return schema;
}

}  // namespace

const std::vector<ParameterSpec>& parameter_schema() {
  using K = Kind;
  // The defaults are the built-in default scene: about 2,000 spheres of the paper's size
  // deposited into a 4.5 cm square box. Young's modulus is lowered from the paper's tens
  // of GPa to 5 GPa so that the default run takes about a minute (docs/parameters.md).
  static const std::vector<ParameterSpec> schema = with_contact_laws({
      {"Simulation", "time step", "1e-6", K::real, 1e-12, 1.0, "", "s",
       "Fixed time step of the velocity Verlet integrator. Refused when above the safe step "
       "(see Rayleigh fraction, Hertz fraction) unless 'allow unsafe time step' is true."},
      {"Simulation", "end time", "0.4", K::real, 0.0, 1e6, "", "s", "Simulated time at which the run ends."},
      {"Simulation", "maximum steps", "1e10", K::real, 1.0, 1e18, "", "steps",
       "The most time steps (end time / time step) a scene may ask for; more is refused as a likely "
       "mistake in a unit (1e10 steps take a day at the fastest step rates measured). Raise it for a "
       "longer run."},
      {"Simulation", "stop at rest ratio", "1e-6", K::real, 0.0, 1.0, "", "-",
       "End the run early once the kinetic energy is below this fraction of the potential energy "
       "released at every time-series row for the rest window (checked after the first tenth of "
       "the run). 0 disables."},
      {"Simulation", "stop at rest window", "2", K::real, 0.0, 1e6, "", "settling times",
       "How long the kinetic energy must stay below the rest ratio before the run stops, in "
       "settling times sqrt(d/g) (d the largest grain's diameter), so that a lull between bounces "
       "does not end a deposition. 0: the first row below the ratio."},
      {"Simulation", "Rayleigh fraction", "0.2", K::real, 1e-3, 1.0, "", "-",
       "Safe time step as a fraction of the Rayleigh time of the smallest grain."},
      {"Simulation", "Hertz fraction", "0.1", K::real, 1e-3, 1.0, "", "-",
       "Safe time step as a fraction of the shortest Hertz contact duration at the expected impact speed."},
      {"Simulation", "expected impact speed", "0", K::real, 0.0, 1e4, "", "m/s",
       "Highest relative impact speed for the Hertz time. 0 = estimate: initial speed plus free fall from "
       "the top of the fill."},
      {"Simulation", "allow unsafe time step", "false", K::boolean, 0, 0, "", "-",
       "Run even when the time step exceeds the safe step (results may be wrong or unstable)."},
      {"Simulation", "neighbor skin", "0.2", K::real, 0.01, 5.0, "", "largest diameters",
       "Verlet list skin; the list is rebuilt when a grain has moved more than half of it."},

      // Each effect: auto (derived from the scene's parameters, dem/scene/effect_choice.h),
      // true or false. Switching off an effect a parameter calls for is refused.
      {"Effects", "gravity", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Gravity along -z. auto: on when 'gravity acceleration' > 0."},
      {"Effects", "gravity acceleration", "9.81", K::real, 0.0, 1e3, "", "m/s^2", "Magnitude of gravity."},
      {"Effects", "tangential friction", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Mindlin tangential spring with Coulomb friction between particles. auto: on when Contact/friction "
       "coefficient > 0; off means frictionless contacts and no tangential history."},
      {"Effects", "damping", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Normal viscous damping c_n = 2 zeta sqrt(m* k_n). auto: on when Contact/damping ratio > 0."},
      {"Effects", "wall friction", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Mindlin tangential spring with Coulomb friction at walls. auto: on when a Container wall friction is "
       "> 0; off means frictionless walls and no wall history."},
      {"Effects", "rotation", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Integrate the angular velocity from contact torques. auto: on when a torque can act (friction, wall "
       "friction, rolling resistance or ellipsoids). false holds every grain from turning."},
      {"Effects", "energy tracking", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Accumulate elastic energy and dissipation per contact for the energy balance. auto: on when "
       "Output/energy balance is true."},
      {"Effects", "rolling resistance", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Rolling resistance at every contact: elastic-plastic spring-dashpot (Iwashita and Oda 1998; Ai et "
       "al. 2011, model C), |M_r| <= mu_r R* F_n. Not part of the paper's law: auto is off. Needs rotation."},
      {"Effects", "twisting resistance", "auto", K::selection, 0, 0, "auto|true|false", "-",
       "Twisting resistance at every contact: Hertz–Mindlin torsion of the contact circle (Lubkin 1951; "
       "Johnson 1985, 7.4), stiffness 16/3 G a^3, full slip at 3 pi/16 mu a F_n, with the rolling dashpot's "
       "damping ratio. Stops grains spinning about a contact normal (needles, discs). Not part of the "
       "paper's law: auto is off. Needs rolling resistance."},

      {"Particles", "count", "2000", K::integer, 0, 1e9, "", "-",
       "Number of grains of the initial fill (0: an empty container, for a pour: Insertion/count)."},
      {"Particles", "radius", "1.5e-3", K::real, 1e-9, 10.0, "", "m",
       "Radius of monodisperse spheres (used when 'gradation' is empty)."},
      {"Particles", "gradation", "", K::text, 0, 0, "", "m : -",
       "Gradation curve as comma-separated 'radius:fraction passing' points by mass, e.g. "
       "'1.0e-3:0, 1.5e-3:0.4, 2.5e-3:1'. Empty: monodisperse."},
      {"Particles", "shapes", "", K::text, 0, 0, "", "-",
       "Grain shapes as comma-separated aspect ratios 1:b/a:c/a, each with an optional number fraction "
       "after '@' (equal shares without), e.g. '1:1:1, 1:0.8:0.6, 1:0.8:0.4, 1:0.6:0.4' (the paper's four). "
       "Empty: spheres. The radius (or gradation) is each grain's major semi-axis a; orientations are "
       "uniformly random."},
      {"Particles", "initial packing", "", K::text, 0, 0, "", "-",
       "Start from the grains of this file instead of a fill: a text table (CSV or whitespace; columns id, "
       "x, "
       "y, z, r or d or a, b, c, optional qw, qx, qy, qz, vx, vy, vz, wx, wy, wz), a LAMMPS/LIGGGHTS data "
       "file "
       "(atom_style sphere or granular) or an Upgrain snapshot (HDF5). A relative path starts at the scene "
       "file's folder. count, radius, gradation, shapes and the Fill section are then not used; the grains "
       "take this section's material. Empty: fill the container (docs/input.md)."},
      {"Particles", "density", "2650", K::real, 1.0, 1e5, "", "kg/m^3",
       "Grain density (specific gravity 2.65 in the paper)."},
      {"Particles", "youngs modulus", "5e9", K::real, 1e3, 1e13, "", "Pa",
       "Young's modulus of the grains and walls."},
      {"Particles", "poisson ratio", "0.25", K::real, 0.0, 0.49, "", "-",
       "Poisson's ratio of the grains and walls."},

      {"Contact", "friction coefficient", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient between particles."},
      {"Contact", "damping ratio", "0.5", K::real, 0.0, 10.0, "", "-",
       "zeta in c_n = 2 zeta sqrt(m* k_n) (paper eq. 21)."},
      {"Contact", "rolling friction coefficient", "0.05", K::real, 0.0, 1.0, "", "-",
       "mu_r of the rolling resistance (Effects/rolling resistance): plastic limit mu_r R* F_n, rolling "
       "stiffness 2.25 k_n mu_r^2 R*^2. Particle-particle and particle-wall."},
      {"Contact", "rolling damping ratio", "0.3", K::real, 0.0, 10.0, "", "-",
       "eta_r of the rolling dashpot C_r = eta_r 2 sqrt(I_r k_r), active below the plastic limit."},
      {"Contact", "solver gradient tolerance", "16", K::real, 16.0, 1e12, "", "eps x size",
       "Ellipsoid contact solver: Newton stops when the gradient of the support-function gap is below "
       "this many machine epsilons times the pair's size (16: round-off; docs/ellipsoid-contact.md, "
       "\"Stopping rules\"). Scenes of spheres do not use it."},
      {"Contact", "solver iterations", "30", K::integer, 1, 1000, "", "-",
       "Ellipsoid contact solver: Newton steps per start before it gives up (a warm start takes 2-3; the "
       "force loop's straight-line path at most min(4, this))."},

      {"Container", "length x", "0.045", K::real, 1e-6, 1e4, "", "m",
       "Inner length of the box along x (walls at x = 0 and x = length x)."},
      {"Container", "length y", "0.045", K::real, 1e-6, 1e4, "", "m", "Inner length of the box along y."},
      {"Container", "height", "0.1", K::real, 1e-6, 1e4, "", "m",
       "Nominal wall height (for output; the walls are unbounded planes)."},
      {"Container", "floor friction", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient particle-floor."},
      {"Container", "wall x min friction", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient at the wall x = 0."},
      {"Container", "wall x max friction", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient at the wall x = length x."},
      {"Container", "wall y min friction", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient at the wall y = 0."},
      {"Container", "wall y max friction", "0.5", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient at the wall y = length y."},
      {"Container", "gate x", "0", K::real, 0.0, 1e4, "", "m",
       "Constrained collapse (paper): a gate wall at x = gate x holds the grains in [0, gate x] during "
       "deposition and is removed at 'gate open time', so the bed collapses into the rest of the box. "
       "0 = no gate."},
      {"Container", "gate open time", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time at which the gate is removed (with 'gate x' > 0)."},
      {"Container", "collapse", "none", K::selection, 0, 0, "none|constrained|unconstrained", "-",
       "Collapse scene (docs/scenes.md). constrained: the gate at 'gate x' is removed at 'gate open "
       "time'. unconstrained: all four side walls are removed at 'side walls open time' and the bed "
       "spreads on the (unbounded) floor; needs 'Study/compare with continuum = false'. none: a plain box "
       "(a 'gate x' > 0 still selects the constrained collapse)."},
      {"Container", "side walls open time", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time at which all side walls are removed (with 'collapse = unconstrained')."},

      {"Lid", "mode", "none", K::selection, 0, 0, "none|velocity|servo", "-",
       "A lid on the bed (docs/scenes.md, Lid): a horizontal wall placed at 'place time' just above the "
       "highest grain, then driven down at 'speed' (velocity) or servo-controlled to hold 'target stresses' "
       "(servo; docs/calibration.md). A run with a lid does not stop at rest. none: no lid."},
      {"Lid", "place time", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time at which the lid is placed; before Simulation/end time."},
      {"Lid", "gap", "0", K::real, 0.0, 1e4, "", "m",
       "Distance between the highest grain's top (its bounding sphere's) and the lid when it is placed."},
      {"Lid", "friction", "0", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient particle-lid (0 when Effects/wall friction is off)."},
      {"Lid", "speed", "0.01", K::real, -1e3, 1e3, "", "m/s",
       "Speed of the lid downwards, into the bed (mode velocity); negative lifts it."},
      {"Lid", "target stresses", "", K::text, 0, 0, "", "Pa",
       "Normal stresses on the lid (its force over the container's footprint) the servo holds in turn, "
       "comma-separated, each for 'step duration' after the placement, the last to the end (mode servo)."},
      {"Lid", "step duration", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time each target stress is held (mode servo); > 0 with more than one target."},
      {"Lid", "gain factor", "0.5", K::real, 1e-6, 1.0, "", "-",
       "alpha of the servo's gain G = alpha A / (K dt), K a bound of the lid's contact stiffness: the error "
       "shrinks by (1 - alpha) per update on a linear spring; <= 1 for a stable servo "
       "(docs/calibration.md)."},
      {"Lid", "max speed", "0.01", K::real, 1e-9, 1e3, "", "m/s",
       "Largest speed of the servo lid, also its speed of approach before it touches the bed."},
      {"Lid", "update interval", "10", K::integer, 1, 1000000, "", "steps",
       "Steps between servo updates; the lid keeps its velocity in between, and the gain takes the "
       "interval as its dt."},

      {"Fill", "method", "lattice", K::selection, 0, 0, "lattice|random", "-",
       "Initial placement: a jittered cubic lattice, or random sequential addition."},
      {"Fill", "bottom gap", "0.01", K::real, 0.0, 1e4, "", "m",
       "Gap between the floor and the lowest grain surface at the start."},
      {"Fill", "lattice spacing", "1.1", K::real, 1.0, 10.0, "", "largest diameters", "Lattice pitch."},
      {"Fill", "position jitter", "0.5", K::real, 0.0, 1.0, "", "-",
       "Random offset of lattice sites, as a fraction of the free gap between neighbours."},
      {"Fill", "solid fraction", "0.3", K::real, 0.01, 0.6, "", "-",
       "Solid fraction of the random fill region."},
      {"Fill", "initial velocity", "0, 0, 0", K::vector3, -1e4, 1e4, "", "m/s",
       "Initial velocity of every grain."},
      {"Fill", "velocity jitter", "0", K::real, 0.0, 1e4, "", "m/s",
       "Amplitude of a uniform random velocity added to each grain."},
      {"Fill", "seed", "12345", K::integer, 0, 2147483647, "", "-",
       "Seed of the random numbers (radii, jitter)."},

      {"Insertion", "count", "0", K::integer, 0, 1e9, "", "-",
       "Grains poured in during the run from the inlet box (docs/insertion.md), with the scene's "
       "gradation and shapes; 0: no insertion."},
      {"Insertion", "rate", "0", K::real, 0.0, 1e12, "", "grains/s",
       "Grains inserted per second (give this or 'mass rate')."},
      {"Insertion", "mass rate", "0", K::real, 0.0, 1e9, "", "kg/s",
       "Mass inserted per second (give this or 'rate')."},
      {"Insertion", "start time", "0", K::real, 0.0, 1e6, "", "s", "Time of the first batch."},
      {"Insertion", "interval", "0.01", K::real, 1e-12, 1e6, "", "s",
       "Time between two batches; each brings the grains due by the rate."},
      {"Insertion", "inlet min", "0, 0, 0", K::vector3, -1e4, 1e4, "", "m",
       "Lower corner of the inlet box, inside the container, where new grains are placed."},
      {"Insertion", "inlet max", "0, 0, 0", K::vector3, -1e4, 1e4, "", "m", "Upper corner of the inlet box."},
      {"Insertion", "velocity", "0, 0, 0", K::vector3, -1e4, 1e4, "", "m/s",
       "Initial velocity of every new grain."},

      {"Output", "folder", "upgrain-output", K::text, 0, 0, "", "-", "Folder for all results of the run."},
      {"Output", "overwrite", "false", K::boolean, 0, 0, "", "-",
       "Replace an earlier run in the folder: its files are removed before the new run writes any, so the "
       "two never mix (otherwise a folder with results is refused). Only a folder holding a run "
       "(time_series.csv, summary.json or checkpoints/) is replaced."},
      {"Output", "snapshot interval", "0.05", K::real, 0.0, 1e6, "", "s",
       "Simulated time between HDF5 snapshots; 0 = first and last only."},
      {"Output", "time series interval", "0.002", K::real, 0.0, 1e6, "", "s",
       "Simulated time between rows of time_series.csv."},
      {"Output", "force network", "false", K::boolean, 0, 0, "", "-",
       "Write every contact with each snapshot after the first: force_network/contacts_<step>.h5 (ids, "
       "point, "
       "normal and tangential force, overlap) and force_network.xdmf, the contacts as lines between the "
       "centres for ParaView (docs/output.md)."},
      {"Output", "energy balance", "true", K::boolean, 0, 0, "", "-",
       "Write the elastic energies, the dissipation and the balance error into time_series.csv and "
       "summary.json. false: with Effects/energy tracking = auto the contacts track no energy (faster), and "
       "those columns are nan (null in summary.json)."},

      {"Checkpoint", "interval", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time between checkpoints in <Output/folder>/checkpoints/ (docs/restart.md); 0 = none on a "
       "schedule. The same steps in every run of the scene, so an interrupted run resumed from one ends "
       "with the bytes of one that was not."},
      {"Checkpoint", "wall interval", "600", K::real, 0.0, 1e9, "", "s",
       "Wall-clock time between checkpoints (checked at the time-series rows); 0 = none. A run also writes "
       "one when it is asked to stop (SIGINT, SIGTERM, SIGHUP), then exits with 128 + the signal."},
      {"Checkpoint", "keep", "2", K::integer, 1, 1000, "", "-",
       "The newest checkpoints kept; older ones are removed."},

      {"Parallel", "summation", "deterministic", K::selection, 0, 0, "deterministic|fast", "-",
       "How the DEM sums forces and global quantities (docs/architecture.md). deterministic: each grain adds "
       "its contacts in the order of its partners' ids, and every result and output byte is the same on any "
       "rank count. fast: a scatter over a half list in local order, forces on ghosts returned to their "
       "owners; results then depend on the rank count to round-off."},
      {"Parallel", "DEM engine", "auto", K::selection, 0, 0, "auto|serial|mpi", "-",
       "No longer used: one engine runs the DEM on every rank count (docs/parallel.md). Kept so that older "
       "scene files still run; a value other than auto is ignored with a warning."},
      {"Parallel", "blocks", "0, 0, 0", K::integer3, 0, 4096, "", "-",
       "Blocks of the DEM's domain decomposition along x, y, z; their product must be the rank count. 0, 0, "
       "0 = chosen to "
       "minimise the cut area for the rank count and the box."},
      {"Parallel", "balance interval", "0.01", K::real, 0.0, 1e6, "", "s",
       "Simulated time between moves of the block planes to the quantiles of the cost (load balance, "
       "docs/parallel.md), applied at the next neighbour-list rebuild; also once at the start. 0 = fixed "
       "blocks. Results do not depend on it, only the speed."},
      {"Parallel", "balance cost", "particles", K::selection, 0, 0, "particles|pair slots", "-",
       "What the load balance equalises per block: owned particles, or particles plus their neighbour-list "
       "pairs (better for beds with loose and dense regions)."},

      {"Stress", "formulas", "weber, drescher, bagi, de saxce, nicot, modified nicot, modified de saxce",
       K::multiple_selection, 0, 0, "weber|drescher|bagi|de saxce|nicot|modified nicot|modified de saxce",
       "-",
       "Average-stress formulas written per grid cell (paper eqs. 1-7, docs/stress.md), comma-separated. "
       "Empty: no grid stress."},
      {"Stress", "grid cells", "3, 3, 4", K::integer3, 1, 1000, "", "-",
       "Cells of the stress grid along x, y, z."},
      {"Stress", "box", "auto", K::text, 0, 0, "", "m",
       "Box of the stress grid as 'x0, y0, z0, x1, y1, z1', or 'auto': the container footprint from the "
       "floor to the top of the highest grain at each evaluation."},
      {"Stress", "interval", "0", K::real, 0.0, 1e6, "", "s",
       "Simulated time between grid-stress evaluations; 0 = with each snapshot. The final state is always "
       "evaluated."},

      {"Strain", "enabled", "false", K::boolean, 0, 0, "", "-",
       "Write finite-strain measures per cell of the stress grid (F, L, J, ln J, E, e, Hencky strain, "
       "equivalent shear strain, D, W, R, increment from the previous evaluation; docs/strain.md), at the "
       "grid-stress evaluations and on their grid (Stress/grid cells and box). Needs Stress/formulas."},
      {"Strain", "reference time", "0", K::real, 0.0, 1e6, "", "s",
       "t0, where F = 1: 0 = the initial state; otherwise the first grid-stress evaluation at or after t0 "
       "(no strain is written before it). The end of deposition cannot be the reference of a deposition "
       "run."},
      {"Strain", "set", "lagrangian", K::selection, 0, 0, "lagrangian|eulerian", "-",
       "Particles of a cell: lagrangian = those in the cell at t0 (on the grid of t0), followed by global "
       "id; "
       "eulerian = those in the cell now, with their positions at t0."},
      {"Strain", "definitions", "best fit, tessellation", K::multiple_selection, 0, 0,
       "best fit|tessellation", "-",
       "How F and L are taken from a cell's particles: best fit = least-squares affine map; tessellation = "
       "volume average over the Delaunay tessellation of the centroids (Bagi 1996), comma-separated."},
      {"Strain", "rate formula", "bagi", K::selection, 0, 0,
       "weber|drescher|bagi|de saxce|nicot|modified nicot|modified de saxce", "-",
       "Grid-stress formula whose cell series gives the Jaumann, Green-Naghdi, Truesdell and Oldroyd "
       "rates written with the strain (backward differences over the last outputs; docs/strain.md). "
       "Must be in Stress/formulas."},

      {"Study", "compare with continuum", "true", K::boolean, 0, 0, "", "-",
       "After the DEM run, solve the continua of the same container (Continuum/variants) on a mesh matching "
       "the stress grid and write the comparison tables, plots and report.md (docs/study.md). False: the DEM "
       "run only."},
      {"Study", "comparison formulas", "bagi, modified nicot, weber", K::multiple_selection, 0, 0,
       "weber|drescher|bagi|de saxce|nicot|modified nicot|modified de saxce", "-",
       "DEM stress formulas set beside the continuum; each must also be in Stress/formulas."},
      {"Study", "relax at end", "true", K::boolean, 0, 0, "", "-",
       "Relax the deposited bed to static equilibrium by FIRE before its final stress (docs/stress.md)."},
      {"Study", "relaxation tolerance", "1e-9", K::real, 1e-15, 1.0, "", "-",
       "FIRE stops when every grain's |F + m g| < tolerance m g and |T| < tolerance m g r."},
      {"Study", "max relaxation steps", "200000", K::integer, 0, 2147483647, "", "-",
       "Upper bound on the FIRE steps; the residual reached is reported."},

      {"Accuracy", "knobs",
       "time step, youngs modulus, skin, summation, ranks, shape, rotation, solver tolerance, solver "
       "iterations, relaxation tolerance, grid, fem, outputs",
       K::multiple_selection, 0, 0,
       "time step|youngs modulus|skin|summation|ranks|shape|rotation|rolling resistance|solver "
       "tolerance|solver iterations|relaxation tolerance|grid|fem|outputs",
       "-",
       "What `upgrain --study accuracy` turns, one at a time, every other setting as the scene gives it "
       "(docs/accuracy.md). Knobs that do not apply to the scene are skipped with a note."},
      {"Accuracy", "time step fractions", "0.1, 0.25, 0.5, 1.0", K::text, 0, 0, "", "-",
       "Time steps to try, as fractions of the scene's safe step (the scene's own step is added)."},
      {"Accuracy", "modulus factors", "1, 0.1, 0.01", K::text, 0, 0, "", "-",
       "Young's modulus scaled by these factors, each with the safe step it allows (at the scene's own "
       "fraction of it)."},
      {"Accuracy", "skins", "0.1, 0.2, 0.5", K::text, 0, 0, "", "-",
       "Neighbour skins to try, in largest diameters: every result must be the same bits."},
      {"Accuracy", "solver tolerances", "16, 1e8, 1e10", K::text, 0, 0, "", "eps x size",
       "Ellipsoid contact solver gradient tolerances to try (Contact/solver gradient tolerance)."},
      {"Accuracy", "solver iteration caps", "30, 4, 2", K::text, 0, 0, "", "-",
       "Ellipsoid contact solver iteration caps to try (Contact/solver iterations)."},
      {"Accuracy", "relaxation tolerances", "1e-5, 1e-7, 1e-9", K::text, 0, 0, "", "-",
       "FIRE tolerances to try (Study/relaxation tolerance)."},
      {"Accuracy", "grids", "3 3 5; 5 5 9; 7 7 13", K::text, 0, 0, "", "-",
       "Stress grids to try, cells along x y z, separated by ';' (the paper's grid-size study)."},
      {"Accuracy", "fem degrees", "1, 2, 3", K::text, 0, 0, "", "-",
       "Polynomial degrees of the continuum to try against its analytic solution."},
      {"Accuracy", "fem refinements", "0, 1, 2", K::text, 0, 0, "", "-",
       "Global refinements to try with each degree."},
      {"Accuracy", "replicas", "3", K::integer, 1, 20, "", "-",
       "Runs of the scene as given that differ only in Fill/seed; their spread is the noise floor below "
       "which a change is reported as no measurable change."},
      {"Accuracy", "tolerance", "0.01", K::real, 0.0, 1.0, "", "-",
       "Relative change a setting may make in every measure of the bed (or the noise floor, if larger) "
       "for the report to call it within tolerance."},
      {"Calibration", "oedometer loading", "gravity", K::selection, 0, 0, "gravity|lid", "-",
       "How the oedometric test (docs/calibration.md) loads the bed: gravity raises its weight by each of "
       "'gravity factors' (no wall on the top: nothing to seat; the modulus at the bed's own stress, as a "
       "continuum loaded by gravity needs it); lid holds each of 'lid stresses' with a servo lid placed on "
       "the bed's highest grain."},
      {"Calibration", "gravity factors", "1.5, 2", K::text, 0, 0, "", "-",
       "The bed's weight times each of these in turn (oedometer loading = gravity), comma-separated, "
       "ascending, each > 1; the weight rises linearly over the first half of each hold."},
      {"Calibration", "lid stresses", "0.5, 1, 2, 4", K::text, 0, 0, "", "bed weight / footprint",
       "Targets of the oedometric test's servo lid (oedometer loading = lid), as multiples of the bed's "
       "weight over the box's footprint, comma-separated, ascending; at least two."},
      {"Calibration", "hold time", "0.03", K::real, 1e-9, 1e6, "", "s",
       "Simulated time each gravity factor or lid target is held before the bed's stress and strain are "
       "taken."},
      {"Calibration", "seating time", "0.2", K::real, 0.0, 1e6, "", "s",
       "Simulated time before the first hold in which the lid comes down onto the bed and seats at the "
       "first target (its first contacts with the uneven top are impacts); not recorded (oedometer "
       "loading = lid)."},
      {"Calibration", "gain factor", "0.5", K::real, 1e-6, 1.0, "", "-",
       "alpha of the lid's servo (as Lid/gain factor)."},
      {"Calibration", "max speed", "0.05", K::real, 1e-9, 1e3, "", "m/s", "Largest speed of the lid."},
      {"Calibration", "update interval", "10", K::integer, 1, 1000000, "", "steps",
       "Steps between the servo walls' updates (the lid's, the friction-angle test's walls); also the "
       "longest stair of the oedometric test's gravity ramp."},
      {"Calibration", "side wall friction", "0", K::real, 0.0, 10.0, "", "-",
       "Coulomb coefficient of the side walls in the bed of upgrain --study calibration (0: a lubricated "
       "oedometer ring, so that the test measures the grains, not the walls); the floor keeps "
       "Container/floor "
       "friction. A study's own bed keeps the scene's walls (docs/calibration.md)."},
      {"Calibration", "confining stress", "12.5", K::real, 1e-3, 1e6, "", "bed weight / footprint",
       "sigma_3 of the friction-angle test (docs/calibration.md), held by the four servo side walls, as a "
       "multiple of the bed's weight over the box's footprint; the bed is first consolidated to it "
       "isotropically (without gravity)."},
      {"Calibration", "axial strain rate", "0.375", K::real, 1e-6, 1e3, "", "1/s",
       "Axial strain rate of the friction-angle test: the lid comes down at this rate times the consolidated "
       "height. The driver prints the inertial number I = rate d sqrt(rho / sigma_3) (quasi-static below "
       "about 1e-3)."},
      {"Calibration", "final axial strain", "0.15", K::real, 0.01, 0.5, "", "-",
       "Axial strain at which the friction-angle test ends; its last 30 % is the critical state."},
      {"Calibration", "consolidation time", "0.05", K::real, 1e-9, 1e6, "", "s",
       "Simulated time in which the lid and the side walls consolidate the bed to the confining stress "
       "before the shearing."},
      {"Calibration", "continuum strength", "peak", K::selection, 0, 0, "peak|critical state", "-",
       "The strength the calibrated material file gives the Drucker–Prager continuum: the peak friction "
       "angle with the dilatancy angle at the peak, or the critical-state friction angle with no "
       "dilatancy."},
      {"CoarseGraining", "fields",
       "density, velocity, stress, wall force density, displacement, momentum balance", K::multiple_selection,
       0, 0, "density|velocity|stress|wall force density|displacement|momentum balance", "-",
       "Coarse-grained fields written on the study's mesh beside the continuum (docs/coarse-graining.md), "
       "comma-separated: density (and volume fraction), velocity (and momentum), stress (total and kinetic; "
       "the contact stress by the line integral along each branch), wall force density, displacement (and "
       "its "
       "gradient, against the state at 'reference time'), momentum balance (its residual and d(rho v)/dt). "
       "The stress is always compared with the continuum's. Empty: none. Needs 'Study/compare with "
       "continuum'."},
      {"CoarseGraining", "kernel", "gaussian", K::selection, 0, 0, "gaussian|lucy", "-",
       "Smoothing kernel: gaussian (cut at 3 w and renormalised, as MercuryCG) or lucy (Lucy's polynomial, "
       "cut-off 2 sqrt(3) w)."},
      {"CoarseGraining", "width", "1", K::real, 0.05, 20.0, "", "mean grain diameters",
       "Kernel width w, the standard deviation of the kernel along each axis, in mean grain diameters d "
       "(of the grains' volume-equivalent spheres)."},
      {"CoarseGraining", "evaluation points", "support points", K::selection, 0, 0,
       "support points|quadrature points", "-",
       "Where the fields are evaluated: the support points of the continuum's Q_k elements (written as "
       "continuous finite-element fields), or its quadrature points (written as cell means). The comparison "
       "with the continuum's stress is at its quadrature points either way."},
      {"CoarseGraining", "time derivative", "accelerations", K::selection, 0, 0, "accelerations|differences",
       "-",
       "d(rho v)/dt in the momentum balance: from the grains' accelerations of the final force evaluation "
       "(exact), or by differences of the final state and one 'sampling interval' later (trapezoidal)."},
      {"CoarseGraining", "sampling interval", "0", K::real, 0.0, 1e3, "", "s",
       "Time between the two states of 'time derivative = differences'; 0 = one time step. Rounded to whole "
       "time steps."},
      {"CoarseGraining", "reference time", "0", K::real, 0.0, 1e6, "", "s",
       "The reference state of the displacement field: the first step at or after this time (0 = the initial "
       "state)."},

      {"Continuum", "youngs modulus", "1e8", K::real, 1.0, 1e13, "", "Pa",
       "Young's modulus of every continuum (the stresses of the confined column do not depend on it, nor, "
       "without cohesion, those of the frictional continua; the displacements do)."},
      {"Continuum", "poisson ratio", "0.3", K::real, 0.0, 0.499, "", "-",
       "Poisson's ratio of every continuum; it sets K0 = nu / (1 - nu), and the lateral ratio of the Janssen "
       "line."},
      {"Continuum", "material from", "auto", K::selection, 0, 0, "auto|calibration|entries", "-",
       "Where the continua's youngs modulus, poisson ratio, friction angle and dilatancy angle come from. "
       "calibration: measured on the study's own bed after the DEM run, by the oedometric and friction-angle "
       "tests of docs/calibration.md (Calibration section; written to calibration/ in the output folder, "
       "their "
       "time in the report); entries: the Continuum entries as set; auto: calibration where those tests can "
       "load the bed (Hertz–Mindlin, a closed box, no Lid section), the entries otherwise. With a material "
       "file, leave it at auto: the file supplies the values it sets."},
      {"Continuum", "material file", "", K::text, 0, 0, "", "-",
       "A calibrated material file (calibration/material.prm of `upgrain --study calibration` or of an "
       "earlier study, docs/calibration.md) whose youngs modulus, poisson ratio, friction angle and "
       "dilatancy "
       "angle replace the entries of this section it sets; a relative path is taken from the scene file's "
       "folder. Empty: no file."},
      {"Continuum", "refinements", "1", K::integer, 0, 6, "", "-",
       "Global refinements of the mesh whose coarse cells are the stress grid's cells."},
      {"Continuum", "degree", "2", K::integer, 1, 4, "", "-",
       "Polynomial degree of the displacement element (Q2 reproduces the analytic column exactly)."},
      {"Continuum", "variants", "elastic friction, drucker prager", K::multiple_selection, 0, 0,
       "elastic friction|drucker prager", "-",
       "Continua solved beside the elastic column on frictionless rollers (which always runs), each in a "
       "rigid box whose walls carry Coulomb friction ('wall friction', 'floor friction'): elastic friction "
       "is linear elastic, drucker prager elastoplastic with the strength below (docs/fem.md). Empty: the "
       "rollers column only."},
      {"Continuum", "wall friction", "auto", K::text, 0, 0, "", "-",
       "Coulomb coefficient of the frictional continua's side walls: auto = each wall's Container "
       "coefficient "
       "as the DEM applies it (0 when Effects/wall friction is off), or one number in [0, 10] for all four."},
      {"Continuum", "floor friction", "auto", K::text, 0, 0, "", "-",
       "Coulomb coefficient of the frictional continua's floor: auto = Container/floor friction as the DEM "
       "applies it, or a number in [0, 10]; 0 makes the floor a roller, as for the elastic column."},
      {"Continuum", "friction angle", "30", K::real, 0.1, 89.0, "", "degrees",
       "Mohr–Coulomb friction angle phi of the Drucker–Prager continuum."},
      {"Continuum", "dilatancy angle", "0", K::real, 0.0, 89.0, "", "degrees",
       "Dilatancy angle psi of the Drucker–Prager continuum, at most the friction angle; psi = phi is "
       "associated flow."},
      {"Continuum", "cohesion", "0", K::real, 0.0, 1e9, "", "Pa",
       "Cohesion c of the Drucker–Prager continuum (the DEM's grains have none)."},
      {"Continuum", "cone matching", "outer cone", K::selection, 0, 0, "outer cone|inner cone|plane strain",
       "-",
       "How the Drucker–Prager cone is fitted to Mohr–Coulomb (phi, c): outer cone, through the "
       "triaxial-compression corners (exact for a column compressed axially, as at rest); inner cone, "
       "through "
       "the extension corners; plane strain, the same plane-strain collapse load (docs/fem.md)."},
      {"Continuum", "load steps", "1", K::integer, 1, 1000, "", "-",
       "Steps in which gravity is raised on the frictional continua, with Newton's method in each. Without "
       "cohesion the answer does not depend on them (the problem is homogeneous in g; docs/fem.md)."},
      {"Continuum", "staged construction", "false", K::boolean, 0, 0, "", "-",
       "Build the frictional continua layer by layer (one layer of fine cells per step, each placed "
       "stress-free on the deformed column below) instead of raising gravity on the whole column; it changes "
       "the lateral stresses near the walls (docs/fem.md)."},
  });
  return schema;
}

std::vector<std::string> entries_of(const std::string& section) {
  std::vector<std::string> out;
  for (const auto& p : parameter_schema())
    if (p.section == section) out.push_back(p.name);
  return out;
}

std::vector<std::string> sections() {
  std::vector<std::string> out;
  for (const auto& p : parameter_schema())
    if (std::find(out.begin(), out.end(), p.section) == out.end()) out.push_back(p.section);
  return out;
}

}  // namespace upgrain::coupling
