#include "upscale/strain/equivalent_continuum.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "upscale/strain/deformation_fit.h"

namespace upgrain::upscale {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;

TessellationGradient invalid(std::string reason) {
  TessellationGradient t;
  t.reason = std::move(reason);
  return t;
}

// adj(A) = det(A) A^-1, by cofactors: defined for singular A too.
Mat3 adjugate(const Mat3& a) {
  Mat3 c;
  c.col(0) = a.col(1).cross(a.col(2));
  c.col(1) = a.col(2).cross(a.col(0));
  c.col(2) = a.col(0).cross(a.col(1));
  return c.transpose();
}

}  // namespace

DelaunayTetrahedra delaunay_tetrahedra(std::span<const Vec3> points) {
  DelaunayTetrahedra d;
  if (points.size() < 4) {
    d.reason = "fewer than 4 particles: no tetrahedron";
    return d;
  }
  for (const Vec3& x : points)
    if (!x.allFinite()) {
      d.reason = "a position is not finite";
      return d;
    }
  // The same degeneracy rule as the best fit (deformation_fit.h): CGAL tessellates a set
  // that is flat only to round-off, and its slivers then give a gradient of noise normal to
  // the set.
  {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& x : points) mean += x - points[0];
    mean /= static_cast<double>(points.size());
    Mat3 moment = Mat3::Zero();
    for (const Vec3& x : points) {
      const Vec3 e = x - points[0] - mean;
      moment += e * e.transpose();
    }
    const Vec3 m = Eigen::SelfAdjointEigenSolver<Mat3>(moment, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(m[0] >= kMinSecondMomentRatio * m[2])) {
      d.reason = "the particles span less than three dimensions (coplanar or nearly so)";
      return d;
    }
  }
  // Work about the first point: the tessellation carries no digits of the distance to the
  // origin.
  const Vec3 x0 = points[0];
  std::vector<std::pair<Kernel::Point_3, int>> cgal_points;
  cgal_points.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3 r = points[k] - x0;
    cgal_points.emplace_back(Kernel::Point_3(r.x(), r.y(), r.z()), static_cast<int>(k));
  }
  const Delaunay tessellation(cgal_points.begin(), cgal_points.end());
  if (tessellation.dimension() < 3) {
    d.reason = "the particles span less than three dimensions (coplanar)";
    return d;
  }
  d.tetrahedra.reserve(tessellation.number_of_finite_cells());
  for (auto cell = tessellation.finite_cells_begin(); cell != tessellation.finite_cells_end(); ++cell)
    d.tetrahedra.push_back(
        {cell->vertex(0)->info(), cell->vertex(1)->info(), cell->vertex(2)->info(), cell->vertex(3)->info()});
  d.valid = true;
  return d;
}

namespace {

// sum_t db_t adj(da_t) / sum_t det(da_t) over the tetrahedra; with `carried`, every det(da_t)
// must be positive (CGAL's own cells are positively oriented for the points they were made of).
TessellationGradient average_gradient(const DelaunayTetrahedra& tessellation, std::span<const Vec3> a,
                                      std::span<const Vec3> b, bool carried) {
  if (!tessellation.valid) return invalid(tessellation.reason);
  if (a.size() != b.size()) return invalid("reference and current sets differ in length");
  for (const Vec3& y : b)
    if (!y.allFinite()) return invalid("a position is not finite");
  if (carried)
    for (const Vec3& y : a)
      if (!y.allFinite()) return invalid("a position is not finite");
  // Edge vectors about the first point of each set: they carry no digits of the distance to
  // the origin.
  const Vec3 x0 = a[0], y0 = b[0];
  Mat3 weighted = Mat3::Zero();  // sum_t db_t adj(da_t)
  double det_sum = 0.0;          // sum_t det(da_t) = 6 V
  for (const std::array<int, 4>& id : tessellation.tetrahedra) {
    Mat3 da, db;
    for (int e = 0; e < 3; ++e) {
      da.col(e) = (a[id[e + 1]] - x0) - (a[id[0]] - x0);
      db.col(e) = (b[id[e + 1]] - y0) - (b[id[0]] - y0);
    }
    const double det = da.determinant();
    if (carried && !(det > 0.0)) return invalid("a tetrahedron has inverted");
    weighted += db * adjugate(da);
    det_sum += det;
  }
  if (!(det_sum > 0.0)) return invalid("the tessellation has no volume");
  TessellationGradient t;
  t.valid = true;
  t.gradient = weighted / det_sum;
  t.volume = det_sum / 6.0;
  t.tetrahedra = static_cast<long>(tessellation.tetrahedra.size());
  return t;
}

}  // namespace

TessellationGradient gradient_over_tetrahedra(const DelaunayTetrahedra& tessellation,
                                              std::span<const Vec3> reference,
                                              std::span<const Vec3> current) {
  return average_gradient(tessellation, reference, current, false);
}

TessellationGradient gradient_over_carried_tetrahedra(const DelaunayTetrahedra& tessellation,
                                                      std::span<const Vec3> positions,
                                                      std::span<const Vec3> values) {
  return average_gradient(tessellation, positions, values, true);
}

TessellationGradient equivalent_continuum_deformation(std::span<const Vec3> reference,
                                                      std::span<const Vec3> current) {
  if (reference.size() != current.size()) return invalid("reference and current sets differ in length");
  if (reference.size() < 4) return invalid("fewer than 4 particles: no tetrahedron");
  for (std::size_t k = 0; k < reference.size(); ++k)
    if (!reference[k].allFinite() || !current[k].allFinite()) return invalid("a position is not finite");
  return gradient_over_tetrahedra(delaunay_tetrahedra(reference), reference, current);
}

}  // namespace upgrain::upscale
