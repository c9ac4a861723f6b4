#include "upscale/strain/grid_strain.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "dem/core/error.h"
#include "upscale/strain/deformation_fit.h"
#include "upscale/strain/equivalent_continuum.h"
#include "upscale/strain/strain_measures.h"

namespace upgrain::upscale {

std::string_view name_of(StrainSet s) { return s == StrainSet::lagrangian ? "lagrangian" : "eulerian"; }

std::string_view name_of(StrainDefinition d) {
  return d == StrainDefinition::best_fit ? "best fit" : "tessellation";
}

std::string_view name_of(StrainReason r) {
  static constexpr std::string_view names[kStrainReasonCount] = {
      "valid",         "too few particles", "degenerate set",   "J <= 0",
      "near-singular", "non-finite",        "previous invalid", "no earlier output"};
  const auto i = static_cast<int>(r);
  return i >= 0 && i < kStrainReasonCount ? names[i] : "unknown";
}

void CellStrainFields::resize(int cells) {
  const auto n = static_cast<std::size_t>(cells);
  for (auto* m : {&deformation_gradient, &velocity_gradient, &increment, &green_lagrange, &euler_almansi,
                  &hencky, &rotation, &rate_of_deformation, &spin})
    m->assign(n, Mat3::Zero());
  for (auto* s : {&jacobian, &log_jacobian, &equivalent_shear_strain, &equivalent_shear_rate,
                  &increment_log_jacobian, &increment_equivalent_shear_strain, &residual_rms})
    s->assign(n, 0.0);
  for (auto* r : {&f_reason, &l_reason, &increment_reason}) r->assign(n, StrainReason::valid);
}

StrainReference make_strain_reference(std::span<const GlobalId> id, std::span<const Vec3> x,
                                      std::span<const int> cell, int cells, double time, long step) {
  if (id.size() != x.size() || id.size() != cell.size())
    throw Error("strain reference: " + std::to_string(id.size()) + " ids but " + std::to_string(x.size()) +
                " positions and " + std::to_string(cell.size()) + " cells");
  std::vector<std::size_t> order(id.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  StrainReference r;
  r.time = time;
  r.step = step;
  r.cells = cells;
  r.id.reserve(id.size());
  r.x.reserve(id.size());
  r.cell.reserve(id.size());
  for (std::size_t k : order) {
    if (!r.id.empty() && r.id.back() == id[k])
      throw Error("strain reference: global id " + std::to_string(id[k]) + " appears twice");
    if (cell[k] >= cells) throw Error("strain reference: cell " + std::to_string(cell[k]) + " out of range");
    r.id.push_back(id[k]);
    r.x.push_back(x[k]);
    r.cell.push_back(cell[k] < 0 ? -1 : cell[k]);
  }
  return r;
}

StrainReference make_strain_reference(std::span<const GlobalId> id, std::span<const Vec3> x,
                                      const RegularGrid& grid, double time, long step) {
  std::vector<int> cell(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) cell[k] = grid.cell_of(x[k]);
  StrainReference r = make_strain_reference(id, x, cell, grid.num_cells(), time, step);
  r.grid = grid;
  return r;
}

namespace {

bool all_finite(std::span<const Vec3> p) {
  return std::all_of(p.begin(), p.end(), [](const Vec3& v) { return v.allFinite(); });
}

// The reason a gradient of a set of n points could not be had, given that its kernel refused.
StrainReason refused(std::size_t n, std::span<const Vec3> a, std::span<const Vec3> b) {
  if (n < static_cast<std::size_t>(kMinFitPoints)) return StrainReason::too_few_particles;
  if (!all_finite(a) || !all_finite(b)) return StrainReason::non_finite;
  return StrainReason::degenerate_set;
}

// The reason strain_measures() refused F.
StrainReason refused_measures(const Mat3& f) {
  if (!f.allFinite()) return StrainReason::non_finite;
  if (!(f.determinant() > 0.0)) return StrainReason::non_positive_jacobian;
  return StrainReason::near_singular;
}

struct Gradient {
  StrainReason reason = StrainReason::valid;
  Mat3 value = Mat3::Zero();
  double residual_rms = 0.0;
};

// `tetrahedra`: the tessellation of `a` when it is known (the tessellation's F).
Gradient gradient(StrainDefinition d, std::span<const Vec3> a, std::span<const Vec3> b,
                  const DelaunayTetrahedra* tetrahedra = nullptr) {
  Gradient g;
  if (a.size() < static_cast<std::size_t>(kMinFitPoints)) {
    g.reason = StrainReason::too_few_particles;
    return g;
  }
  if (d == StrainDefinition::best_fit) {
    const AffineFit f = fit_affine_map(a, b);
    if (!f.valid) {
      g.reason = refused(a.size(), a, b);
      return g;
    }
    g.value = f.gradient;
    g.residual_rms = f.residual_rms;
  } else {
    // The same degeneracy test as the best fit (kMinSecondMomentRatio) first: CGAL's exact
    // predicates see a set that is flat to round-off as three-dimensional and tessellate it
    // into slivers, whose adjugate-weighted average is then noise.
    if (!fit_affine_map(a, b).valid) {
      g.reason = refused(a.size(), a, b);
      return g;
    }
    const TessellationGradient t =
        tetrahedra ? gradient_over_tetrahedra(*tetrahedra, a, b) : equivalent_continuum_deformation(a, b);
    if (!t.valid) {
      g.reason = refused(a.size(), a, b);
      return g;
    }
    g.value = t.gradient;
  }
  if (!g.value.allFinite()) g = {StrainReason::non_finite, Mat3::Zero(), 0.0};
  return g;
}

// One cell's set: X the reference positions, x and v the current state, matched by id;
// `tetrahedra` the tessellation of X when known.
struct CellSet {
  std::span<const Vec3> X, x, v;
  const DelaunayTetrahedra* tetrahedra = nullptr;
};

// One cell c, one definition.
void evaluate_cell(CellStrainFields& out, int c, StrainDefinition d, const CellSet& set,
                   const CellStrainFields* previous) {
  const std::span<const Vec3> X = set.X, x = set.x, v = set.v;
  const DelaunayTetrahedra* tetrahedra = set.tetrahedra;
  const Gradient f = gradient(d, X, x, tetrahedra);
  out.f_reason[c] = f.reason;
  if (f.reason == StrainReason::valid) {
    const StrainMeasures m = strain_measures(f.value);
    if (m.valid) {
      out.deformation_gradient[c] = f.value;
      out.residual_rms[c] = f.residual_rms;
      out.jacobian[c] = m.jacobian;
      out.log_jacobian[c] = m.volumetric_strain;
      out.green_lagrange[c] = m.green_lagrange;
      out.euler_almansi[c] = m.euler_almansi;
      out.hencky[c] = m.hencky_left;
      out.rotation[c] = m.polar.rotation;
      out.equivalent_shear_strain[c] = m.equivalent_shear_strain;
    } else {
      out.f_reason[c] = refused_measures(f.value);
    }
  }

  // L over the reference tetrahedra carried to the current positions while none has inverted
  // (the same cells as F), else over a new tessellation of the current positions.
  Gradient l;
  bool carried = false;
  if (d == StrainDefinition::tessellation && tetrahedra &&
      x.size() >= static_cast<std::size_t>(kMinFitPoints) && fit_affine_map(x, v).valid) {
    const TessellationGradient t = gradient_over_carried_tetrahedra(*tetrahedra, x, v);
    if (t.valid && t.gradient.allFinite()) {
      l.value = t.gradient;
      carried = true;
    }
  }
  if (!carried) l = gradient(d, x, v);
  out.l_reason[c] = l.reason;
  if (l.reason == StrainReason::valid) {
    out.velocity_gradient[c] = l.value;
    out.rate_of_deformation[c] = rate_of_deformation(l.value);
    out.spin[c] = spin(l.value);
    out.equivalent_shear_rate[c] = equivalent_shear_rate(l.value);
  }

  // F_inc = F F_prev^-1; without a previous evaluation F_prev = 1.
  if (out.f_reason[c] != StrainReason::valid) {
    out.increment_reason[c] = out.f_reason[c];
    return;
  }
  Mat3 inc = out.deformation_gradient[c];
  if (previous) {
    if (previous->f_reason[c] != StrainReason::valid) {
      out.increment_reason[c] = StrainReason::previous_invalid;
      return;
    }
    const IncrementalDeformation i = incremental_deformation_gradient(inc, previous->deformation_gradient[c]);
    if (!i.valid) {
      out.increment_reason[c] = StrainReason::previous_invalid;
      return;
    }
    inc = i.gradient;
  }
  const StrainMeasures mi = strain_measures(inc);
  if (!mi.valid) {
    out.increment_reason[c] = refused_measures(inc);
    return;
  }
  out.increment_reason[c] = StrainReason::valid;
  out.increment[c] = inc;
  out.increment_log_jacobian[c] = mi.volumetric_strain;
  out.increment_equivalent_shear_strain[c] = mi.equivalent_shear_strain;
}

}  // namespace

GridStrain grid_strain(const StrainReference& reference, const RegularGrid& current_grid,
                       const ParticleKinematics& now, const StateInstant& when,
                       const GridStrainOptions& options, const GridStrain* previous,
                       std::span<const Vec3> placed) {
  if (now.id.size() != now.x.size() || now.id.size() != now.v.size() ||
      (!placed.empty() && placed.size() != now.id.size()))
    throw Error("grid strain: the current state's ids, positions and velocities differ in length");
  const bool lagrangian = options.set == StrainSet::lagrangian;
  if (!lagrangian && current_grid.num_cells() != reference.cells)
    throw Error("grid strain: the current grid has " + std::to_string(current_grid.num_cells()) +
                " cells, the reference " + std::to_string(reference.cells));
  std::vector<int> current_cell(lagrangian ? 0 : now.x.size());
  const std::span<const Vec3> at = placed.empty() ? now.x : placed;
  for (std::size_t k = 0; k < current_cell.size(); ++k) current_cell[k] = current_grid.cell_of(at[k]);
  GridStrain g = partition_strain(reference, current_cell, now, when, options, previous);
  g.grid = lagrangian ? reference.grid : current_grid;
  return g;
}

GridStrain partition_strain(const StrainReference& reference, std::span<const int> current_cell,
                            const ParticleKinematics& now, const StateInstant& when,
                            const GridStrainOptions& options, const GridStrain* previous) {
  if (now.id.size() != now.x.size() || now.id.size() != now.v.size())
    throw Error("strain: the current state's ids, positions and velocities differ in length");
  const bool lagrangian = options.set == StrainSet::lagrangian;
  if (!lagrangian && current_cell.size() != now.id.size())
    throw Error("strain: " + std::to_string(current_cell.size()) + " current cells for " +
                std::to_string(now.id.size()) + " particles");
  GridStrain g;
  g.set = options.set;
  g.reference_time = reference.time;
  g.reference_step = reference.step;
  g.time = when.time;
  g.step = when.step;
  const int cells = reference.cells;
  if (previous && static_cast<int>(previous->particles.size()) != cells) previous = nullptr;

  // The sorted id -> index map of the current state, built once, merged with the reference
  // (also sorted by id): matched pairs come out in id order, so each cell's set is ordered
  // by id whatever the order of the particle store.
  std::vector<std::pair<GlobalId, std::size_t>> current(now.id.size());
  for (std::size_t i = 0; i < now.id.size(); ++i) current[i] = {now.id[i], i};
  std::sort(current.begin(), current.end());
  for (std::size_t i = 1; i < current.size(); ++i)
    if (current[i].first == current[i - 1].first)
      throw Error("grid strain: global id " + std::to_string(current[i].first) + " appears twice");

  struct Match {
    std::size_t ref, cur;
    int cell;
  };
  std::vector<Match> matches;
  matches.reserve(std::min(current.size(), reference.id.size()));
  std::size_t k = 0, i = 0;
  while (k < reference.id.size() || i < current.size()) {
    if (i == current.size() || (k < reference.id.size() && reference.id[k] < current[i].first)) {
      if (lagrangian && reference.cell[k] >= 0) ++g.untracked;  // gone since t0
      ++k;
    } else if (k == reference.id.size() || current[i].first < reference.id[k]) {
      if (!lagrangian && current_cell[current[i].second] >= 0) ++g.untracked;  // new since t0
      ++i;
    } else {
      const int c = lagrangian ? reference.cell[k] : current_cell[current[i].second];
      if (c >= cells)
        throw Error("strain: particle " + std::to_string(reference.id[k]) + " is in cell " +
                    std::to_string(c) + " of a partition into " + std::to_string(cells) + " sets");
      if (c >= 0) matches.push_back({k, current[i].second, c});
      ++k;
      ++i;
    }
  }

  // Bucket the matches by cell (counting sort, stable: id order within a cell).
  std::vector<std::size_t> start(static_cast<std::size_t>(cells) + 1, 0);
  for (const Match& m : matches) ++start[m.cell + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Vec3> X(matches.size()), x(matches.size()), v(matches.size());
  std::vector<GlobalId> ids(matches.size());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (const Match& m : matches) {
      const std::size_t at = fill[m.cell]++;
      ids[at] = reference.id[m.ref];
      X[at] = reference.x[m.ref];
      x[at] = now.x[m.cur];
      v[at] = now.v[m.cur];
    }
  }

  g.particles.assign(cells, 0);
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    if (!options.definitions[d]) continue;
    g.computed[d] = true;
    g.fields[d].resize(cells);
  }
  const std::span<const Vec3> all_X(X), all_x(x), all_v(v);
  const std::span<const GlobalId> all_ids(ids);
  const int tessellation = static_cast<int>(StrainDefinition::tessellation);
  if (g.computed[tessellation]) g.reference_tessellations.resize(cells);
  const bool reuse = previous && previous->reference_step == reference.step &&
                     previous->reference_tessellations.size() == static_cast<std::size_t>(cells);
  for (int c = 0; c < cells; ++c) {
    const std::size_t b = start[c], n = start[c + 1] - start[c];
    g.particles[c] = static_cast<long>(n);
    // The reference tessellation of the cell's set: the previous one while the set is the
    // same, else a new one.
    const DelaunayTetrahedra* tetrahedra = nullptr;
    if (g.computed[tessellation] && n >= static_cast<std::size_t>(kMinFitPoints)) {
      std::shared_ptr<const CellTessellation>& t = g.reference_tessellations[c];
      const auto set = all_ids.subspan(b, n);
      if (reuse && previous->reference_tessellations[c] &&
          std::ranges::equal(previous->reference_tessellations[c]->ids, set))
        t = previous->reference_tessellations[c];
      else
        t = std::make_shared<const CellTessellation>(CellTessellation{
            std::vector<GlobalId>(set.begin(), set.end()), delaunay_tetrahedra(all_X.subspan(b, n))});
      tetrahedra = &t->tetrahedra;
    }
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      if (!g.computed[d]) continue;
      const CellStrainFields* prev = previous && previous->computed[d] ? &previous->fields[d] : nullptr;
      const CellSet cell_set{all_X.subspan(b, n), all_x.subspan(b, n), all_v.subspan(b, n),
                             d == tessellation ? tetrahedra : nullptr};
      evaluate_cell(g.fields[d], c, static_cast<StrainDefinition>(d), cell_set, prev);
    }
  }
  return g;
}

}  // namespace upgrain::upscale
