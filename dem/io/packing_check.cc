// Whether a run can start from a packing: every grain inside the container, no two grains
// overlapping by more than a settled bed's contacts do (docs/input.md, "Starting from a packing").
#include <algorithm>
#include <cmath>
#include <sstream>

#include "dem/contact/geometry/pair_geometries.h"
#include "dem/core/error.h"
#include "dem/io/packing_file.h"
#include "dem/neighbor/cell_grid.h"

namespace upgrain::dem::io {

void check_packing(const Packing& packing, const BoxContainer& box, const std::string& file,
                   double overlap_limit) {
  const ParticleStore& p = packing.grains;
  const std::size_t n = p.size();
  // Image flags belong to periodic axes; along one, the file's box must be the cell.
  const char* length_entry[3] = {"Container/length x", "Container/length y", "Container/height"};
  const double length[3] = {box.lx, box.ly, box.height};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      if (p.image[i][d] != 0 && !box.periodic[d]) {
        std::ostringstream m;
        m << "packing " << file << ", " << packing.name(i) << ": image flag "
          << "xyz"[d] << " = " << p.image[i][d] << ", but "
          << "xyz"[d]
          << " is walled (Container/periodic axes): the grain was wrapped through a periodic boundary; "
             "make the axis periodic or unwrap the positions first";
        throw Error(m.str());
      }
  if (packing.file_box)
    for (int d = 0; d < 3; ++d) {
      const double lo = packing.file_box->lo[d], hi = packing.file_box->hi[d];
      const double tol = 1e-9 * length[d];
      if (!box.periodic[d] || (std::abs(lo) <= tol && std::abs(hi - length[d]) <= tol)) continue;
      std::ostringstream m;
      m.precision(10);
      m << "packing " << file << ":" << packing.box_line[d] << ": the box along the periodic axis "
        << "xyz"[d] << " is [" << lo << ", " << hi << "] m, and the periodic cell is [0, " << length[d]
        << "] m (" << length_entry[d] << "); shift the positions so that the box starts at 0 and set "
        << length_entry[d] << " = " << hi - lo;
      throw Error(m.str());
    }
  std::vector<PlaneWall> walls = make_open_box(box);
  // The gate of a constrained collapse holds the grains in [0, gate x]; the x+ wall is beyond it.
  if (box.has_gate())
    walls.erase(std::remove_if(walls.begin(), walls.end(),
                               [](const PlaneWall& w) { return w.name == kSideWallNames[1]; }),
                walls.end());
  for (std::size_t i = 0; i < n; ++i) {
    for (const PlaneWall& w : walls) {
      const double depth = wall_depth(p, i, w);  // the grain's row of the wall-geometry table
      if (depth > overlap_limit * p.min_semi_axis(i)) {
        std::ostringstream m;
        m.precision(6);
        m << "packing " << file << ", " << packing.name(i) << " at (" << p.x[i].x() << ", " << p.x[i].y()
          << ", " << p.x[i].z() << ") m is outside the container: it reaches " << depth << " m through the "
          << w.name << " (Container: length x = " << box.lx << " m, length y = " << box.ly << " m"
          << (box.has_gate() ? ", gate x = " + std::to_string(box.gate_x) + " m" : std::string()) << ")";
        throw Error(m.str());
      }
    }
  }
  // Pairs by link cells: every pair whose bounding spheres meet lies in adjacent cells.
  Vec3 lo = p.x[0], hi = p.x[0];
  for (const Vec3& x : p.x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double range = 2.0 * p.max_radius();
  CellGrid grid(lo, hi + Vec3::Constant(range), range);
  grid.bin(p.x);
  const auto& dims = grid.dims();
  ContactSolverStats stats;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = grid.cell_coords(p.x[i]);
    for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
        for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, dims[0] - 1); ++x) {
          const int cell = grid.flat(x, y, z);
          for (int s = grid.cell_start()[cell]; s < grid.cell_start()[cell + 1]; ++s) {
            const auto j = static_cast<std::size_t>(grid.order()[s]);
            if (j <= i) continue;
            const double touch = p.radius[i] + p.radius[j];
            if ((p.x[i] - p.x[j]).squaredNorm() >= touch * touch) continue;
            const double depth = pair_contact(p, i, j, stats).depth;  // the pair's row of the geometry table
            const double allowed = overlap_limit * std::min(p.min_semi_axis(i), p.min_semi_axis(j));
            if (depth > allowed) {
              std::ostringstream m;
              m.precision(4);
              m << "packing " << file << ": " << packing.name(i) << " and " << packing.name(j)
                << " overlap by " << depth << " m, "
                << depth / std::min(p.min_semi_axis(i), p.min_semi_axis(j))
                << " of the smaller one's smallest semi-axis (at most " << overlap_limit
                << " is taken: the contacts of a settled bed)";
              throw Error(m.str());
            }
          }
        }
  }
}

}  // namespace upgrain::dem::io
