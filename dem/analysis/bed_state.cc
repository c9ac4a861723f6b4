#include "dem/analysis/bed_state.h"

#include <algorithm>
#include <vector>

#include "dem/neighbor/cell_grid.h"
#include "dem/shape/grain_shapes.h"

namespace upgrain::dem {

namespace {

// Height of grain i's top, and whether point q lies in it, by its shape (dem/shape).
double top_of(const ParticleStore& p, std::size_t i) {
  return shapes::visit_shape(p.kind(i), [&]<class S>() { return S::top(p, i); });
}
bool contains(const ParticleStore& p, std::size_t i, const Vec3& q) {
  return shapes::visit_shape(p.kind(i), [&]<class S>() { return S::contains(p, i, q); });
}

}  // namespace

BedState measure_bed(const ParticleStore& p, const BoxContainer& box, int samples) {
  BedState s;
  const std::size_t n = p.size();
  if (n == 0) return s;
  const double d = 2.0 * p.max_radius();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = p.x[i];
    if (x.x() < 0 || x.x() > box.lx || x.y() < 0 || x.y() > box.ly || x.z() < 0) ++s.particles_outside;
  }
  const int cx = std::max(1, static_cast<int>(box.lx / (2 * d)));
  const int cy = std::max(1, static_cast<int>(box.ly / (2 * d)));
  std::vector<double> top(static_cast<std::size_t>(cx * cy), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const int ix = std::clamp(static_cast<int>(p.x[i].x() / box.lx * cx), 0, cx - 1);
    const int iy = std::clamp(static_cast<int>(p.x[i].y() / box.ly * cy), 0, cy - 1);
    double& t = top[static_cast<std::size_t>(iy * cx + ix)];
    t = std::max(t, top_of(p, i));
  }
  double sum = 0.0;
  for (double t : top) sum += t;
  s.surface_height = sum / static_cast<double>(top.size());

  const double margin = 2.0 * d;
  const double lo[3] = {std::min(margin, 0.25 * box.lx), std::min(margin, 0.25 * box.ly),
                        std::min(margin, 0.25 * s.surface_height)};
  const double hi[3] = {box.lx - lo[0], box.ly - lo[1], s.surface_height - lo[2]};
  for (int k = 0; k < 3; ++k) {
    s.core_lo[k] = lo[k];
    s.core_hi[k] = hi[k];
  }
  if (!(hi[2] > lo[2])) return s;

  CellGrid grid(Vec3(0, 0, 0), Vec3(box.lx, box.ly, s.surface_height + d), d);
  grid.bin(p.x);
  const auto& start = grid.cell_start();
  const auto& order = grid.order();
  const auto& dims = grid.dims();
  long inside = 0, total = 0;
  for (int a = 0; a < samples; ++a)
    for (int b = 0; b < samples; ++b)
      for (int c = 0; c < samples; ++c) {
        const Vec3 q(lo[0] + (a + 0.5) / samples * (hi[0] - lo[0]),
                     lo[1] + (b + 0.5) / samples * (hi[1] - lo[1]),
                     lo[2] + (c + 0.5) / samples * (hi[2] - lo[2]));
        ++total;
        const auto cc = grid.cell_coords(q);
        bool hit = false;
        for (int z = std::max(cc[2] - 1, 0); !hit && z <= std::min(cc[2] + 1, dims[2] - 1); ++z)
          for (int y = std::max(cc[1] - 1, 0); !hit && y <= std::min(cc[1] + 1, dims[1] - 1); ++y)
            for (int x = std::max(cc[0] - 1, 0); !hit && x <= std::min(cc[0] + 1, dims[0] - 1); ++x) {
              const int cell = grid.flat(x, y, z);
              for (int k = start[cell]; k < start[cell + 1]; ++k) {
                const int i = order[k];
                if (contains(p, static_cast<std::size_t>(i), q)) {
                  hit = true;
                  break;
                }
              }
            }
        inside += hit ? 1 : 0;
      }
  s.solid_fraction = static_cast<double>(inside) / static_cast<double>(total);
  return s;
}

}  // namespace upgrain::dem
