#pragma once
// Two touching grains across the faces of a periodic cell, and the same pair inside it: the
// cases the force network's and the coarse graining's periodic tests share (docs/periodic.md,
// docs/coarse-graining.md). Every position is on the cell's grid, so the pair inside is the
// pair across translated exactly, by a lattice vector and a translation T.
#include <string>
#include <vector>

#include "dem/core/periodic_cell.h"

namespace upgrain::test {

using dem::Vec3;

struct PeriodicPair {
  std::string name;
  dem::PeriodicCell cell;
  Vec3 xa, xb;       // the pair across: a inside near a face, b wrapped (on the other side)
  Vec3 inside_a;     // the same pair inside: a here, b at inside_a + d
  Vec3 d;            // the branch from a to b's image next to it
  Vec3 translation;  // xa - inside_a: a point r of the pair inside is r + T, wrapped, here
};

inline dem::PeriodicCell periodic_cube(double l) {
  dem::Box b;
  b.hi = Vec3(l, l, l);
  return dem::make_periodic_cell(b, {true, true, true});
}

// Across the face x = L, across the corner (L, L, L), and across the sliding face z = L of a
// cell sheared along x (offset 3.7 mm: b's image is slid), also across x = 0. Spheres of radius
// 1.5 mm in a 20 mm cube, 0.1 mm or so of overlap.
inline std::vector<PeriodicPair> periodic_pairs() {
  const double l = 0.02;
  dem::PeriodicCell sheared = periodic_cube(l);
  sheared.shear.shear = 0;
  sheared.shear.gradient = 2;
  sheared.shear.offset = dem::on_grid(0.0037, sheared.quantum.x());
  struct Case {
    const char* name;
    dem::PeriodicCell cell;
    Vec3 xa, d;
  };
  const std::vector<Case> cases = {
      {"face", periodic_cube(l), Vec3(l - 0.8e-3, 0.0101, 0.0093), Vec3(2.9e-3, 0.25e-3, -0.3e-3)},
      {"corner", periodic_cube(l), Vec3(l - 0.8e-3, l - 0.5e-3, l - 1.0e-3), Vec3(1.7e-3, 1.6e-3, 1.5e-3)},
      {"sliding face", sheared, Vec3(0.5e-3, 0.0101, l - 0.7e-3), Vec3(-1.2e-3, 0.4e-3, 2.6e-3)},
  };
  std::vector<PeriodicPair> out;
  for (const Case& c : cases) {
    PeriodicPair p{c.name, c.cell, c.xa, Vec3::Zero(), Vec3::Constant(0.01), Vec3::Zero(), Vec3::Zero()};
    dem::snap(p.cell, p.xa);
    dem::snap(p.cell, p.inside_a);
    Vec3 b = p.xa + c.d;
    dem::snap(p.cell, b);
    p.d = b - p.xa;  // exact on the grid
    dem::ImageCount image{0, 0, 0};
    dem::wrap(p.cell, b, image);
    p.xb = b;
    p.translation = p.xa - p.inside_a;
    out.push_back(p);
  }
  return out;
}

// The point r + t in the cell (the lattice's image of it there).
inline Vec3 in_cell(const dem::PeriodicCell& cell, const Vec3& r, const Vec3& t) {
  Vec3 x = r + t;
  dem::ImageCount image{0, 0, 0};
  dem::wrap(cell, x, image);
  return x;
}

}  // namespace upgrain::test
