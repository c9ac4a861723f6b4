#include "dem/strain/equivalent_continuum.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "dem/strain/deformation_fit.h"

namespace upgrain::dem {

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

TessellationGradient gradient_over_tetrahedra(const DelaunayTetrahedra& tessellation,
                                              std::span<const Vec3> reference,
                                              std::span<const Vec3> current) {
  if (!tessellation.valid) return invalid(tessellation.reason);
  if (reference.size() != current.size()) return invalid("reference and current sets differ in length");
  for (const Vec3& y : current)
    if (!y.allFinite()) return invalid("a position is not finite");
  // Edge vectors about the first point of each set: they carry no digits of the distance to
  // the origin.
  const Vec3 x0 = reference[0], y0 = current[0];
  Mat3 weighted = Mat3::Zero();  // sum_t dx_t adj(dX_t)
  double det_sum = 0.0;          // sum_t det(dX_t) = 6 V
  for (const std::array<int, 4>& id : tessellation.tetrahedra) {
    Mat3 dx_ref, dx_cur;
    for (int e = 0; e < 3; ++e) {
      dx_ref.col(e) = (reference[id[e + 1]] - x0) - (reference[id[0]] - x0);
      dx_cur.col(e) = (current[id[e + 1]] - y0) - (current[id[0]] - y0);
    }
    weighted += dx_cur * adjugate(dx_ref);
    det_sum += dx_ref.determinant();  // CGAL's finite cells are positively oriented
  }
  if (!(det_sum > 0.0)) return invalid("the tessellation has no volume");
  TessellationGradient t;
  t.valid = true;
  t.gradient = weighted / det_sum;
  t.volume = det_sum / 6.0;
  t.tetrahedra = static_cast<long>(tessellation.tetrahedra.size());
  return t;
}

TessellationGradient equivalent_continuum_deformation(std::span<const Vec3> reference,
                                                      std::span<const Vec3> current) {
  if (reference.size() != current.size()) return invalid("reference and current sets differ in length");
  if (reference.size() < 4) return invalid("fewer than 4 particles: no tetrahedron");
  for (std::size_t k = 0; k < reference.size(); ++k)
    if (!reference[k].allFinite() || !current[k].allFinite()) return invalid("a position is not finite");
  return gradient_over_tetrahedra(delaunay_tetrahedra(reference), reference, current);
}

}  // namespace upgrain::dem
