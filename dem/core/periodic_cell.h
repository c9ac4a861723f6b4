#pragma once
// The periodic cell of a scene (docs/periodic.md): an orthorhombic box [lo, hi) whose axes are
// each periodic or bounded. Along a periodic axis a grain that leaves the cell through one face
// comes back through the other, and every grain interacts with the nearest image of every other:
// the minimum-image convention (Allen and Tildesley 2017, Computer Simulation of Liquids, 2nd
// ed., sec. 1.6.2 and 5.2). A grain's image counter n (one integer per axis) counts its
// crossings, so that its unwrapped position x + n L is continuous across a wrap.
//
// Positions along a periodic axis are kept on a grid of spacing `quantum`, a power of two
// chosen so that every coordinate of the cell and of its ghosts' images (|x| < 2 M, M four
// times the cell's largest coordinate) is a whole multiple of it below 2^53 quanta: then x + L,
// x - L and x_j - x_i are exact. An image's branch vector is then the same bits as the
// unshifted one, whichever grain of the pair is the ghost and on whichever rank: the pair
// across a face gives the same force and history as inside the cell, and the two ranks that
// hold its two images evaluate it alike (docs/periodic.md, "Exact images"). The grid moves a
// grain by at most half a quantum (about 1e-17 of the cell's size) per step.
//
// A plain value with plain functions: the engine (dem/parallel/domain.h) makes the images of
// ghosts with them, and tests call them with numbers. The cell is orthorhombic, or sheared in the
// Lees-Edwards form (ShearImages): the functions take it whole.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "dem/core/box.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// A grain's image counter: how many times it crossed the cell along each axis (+1 through the
// upper face).
using ImageCount = std::array<std::int32_t, 3>;

// A sheared cell in the Lees-Edwards form (Lees and Edwards 1972, J. Phys. C 5, 1921): the cell
// matrix h has one off-diagonal component h(s, g), the tilt of the edge along the gradient axis g
// towards the shear axis s, so the images across g's faces are displaced by it along s. The
// grains stay in the orthorhombic box, a fundamental domain of the same lattice of images as the
// parallelepiped (the box's faces along g, its other faces sliding); only the images move. The
// tilt is kept as `offset` + `turns` L_s, the offset within half a length of zero and on the s
// grid: its remap by a whole L_s (remapped(), cell_motion.h) changes the lattice's basis, not the
// lattice, nor any grain's state, as LAMMPS's `fix deform remap ... flip` and Yade's
// `Cell.flipCell` do for their tilted cells.
struct ShearImages {
  int shear = -1;     // s, the axis the images slide along (-1: no shear)
  int gradient = -1;  // g, the axis across whose faces they slide
  double offset = 0.0;
  std::int64_t turns = 0;

  [[nodiscard]] bool any() const { return shear >= 0; }
};

struct PeriodicCell {
  Box box;  // [lo, hi) along every axis; its faces on the grid along the periodic axes
  std::array<bool, 3> periodic{false, false, false};
  Vec3 quantum = Vec3::Zero();  // the grid of positions along each periodic axis (0: bounded)
  ShearImages shear;            // a sheared cell's sliding images (none unless it is sheared)

  [[nodiscard]] bool any() const { return periodic[0] || periodic[1] || periodic[2]; }
  [[nodiscard]] double length(int d) const { return box.hi[d] - box.lo[d]; }
  // h(s, g): the whole tilt, remaps undone.
  [[nodiscard]] double tilt() const {
    return shear.any() ? shear.offset + static_cast<double>(shear.turns) * length(shear.shear) : 0.0;
  }
};

// The position x on the grid of `quantum` (round to nearest): x / q and its product by q are
// exact, q being a power of two.
inline double on_grid(double x, double quantum) { return quantum * std::nearbyint(x / quantum); }

// The cell of `box` with these periodic axes: the quantum of each periodic axis, and the box's
// faces along it moved onto its grid (by half a quantum at most).
// `growth`: the grid is sized for a cell up to that many times larger (a cell that deforms may
// grow up to it; a fixed cell passes 1, its grid then as fine as can be).
inline PeriodicCell make_periodic_cell(const Box& box, const std::array<bool, 3>& periodic,
                                       double growth = 1.0) {
  PeriodicCell c{box, periodic, Vec3::Zero(), ShearImages{}};
  for (int a = 0; a < 3; ++a) {
    if (!periodic[a]) continue;
    const double m =
        4.0 * growth * std::max({std::abs(box.lo[a]), std::abs(box.hi[a]), box.hi[a] - box.lo[a]});
    // 2^e >= m, and q = 2^(e - 52): every multiple of q below 2^53 q = 2^(e+1) >= 2 m is a
    // double, and so is the sum or difference of two coordinates below m.
    c.quantum[a] = std::ldexp(1.0, std::ilogb(m) + 1 - 52);
    c.box.lo[a] = on_grid(box.lo[a], c.quantum[a]);
    c.box.hi[a] = on_grid(box.hi[a], c.quantum[a]);
  }
  return c;
}

// Whether the cell's grid still holds the box (lo, hi): every coordinate within 2^50 quanta,
// the bound make_periodic_cell() sized it for (4 max(|lo|, |hi|, L) <= 2^52 q).
inline bool grid_holds(const PeriodicCell& cell, const Box& box) {
  for (int a = 0; a < 3; ++a) {
    if (!cell.periodic[a]) continue;
    const double limit = std::ldexp(cell.quantum[a], 50);
    if (std::max({std::abs(box.lo[a]), std::abs(box.hi[a]), box.hi[a] - box.lo[a]}) > limit) return false;
  }
  return true;
}

// x onto the grid along the periodic axes (after every drift).
inline void snap(const PeriodicCell& cell, Vec3& x) {
  for (int a = 0; a < 3; ++a)
    if (cell.periodic[a]) x[a] = on_grid(x[a], cell.quantum[a]);
}

// The branch vector d = x_j - x_i reduced to its nearest image along the periodic axes (the
// minimum-image convention): each periodic component within [-L/2, L/2]. A sheared cell's
// gradient axis first: an image across its faces is also displaced by the offset.
inline Vec3 minimum_image(const PeriodicCell& cell, Vec3 d) {
  if (const ShearImages& le = cell.shear; le.any()) {
    const double k = std::nearbyint(d[le.gradient] / cell.length(le.gradient));
    d[le.gradient] -= k * cell.length(le.gradient);
    d[le.shear] -= k * le.offset;
  }
  for (int a = 0; a < 3; ++a) {
    if (!cell.periodic[a]) continue;
    const double l = cell.length(a);
    d[a] -= l * std::nearbyint(d[a] / l);
  }
  return d;
}

// Puts x onto the grid and into [lo, hi) along the periodic axes and counts the crossings in
// `image`, so that the unwrapped position (unwrapped()) is the same point before and after
// (exactly, on the grid). A point several cells away is also brought back. In a sheared cell the
// gradient axis goes first: a crossing of its faces takes the offset off the shear axis (a sum on
// the grid, exact) and the turns off its image counter, and the shear axis is wrapped after.
inline void wrap(const PeriodicCell& cell, Vec3& x, ImageCount& image) {
  snap(cell, x);
  if (const ShearImages& le = cell.shear; le.any()) {
    const int g = le.gradient, s = le.shear;
    const double lo = cell.box.lo[g], hi = cell.box.hi[g], l = hi - lo;
    while (x[g] >= hi) {
      x[g] -= l;
      x[s] -= le.offset;
      ++image[g];
      image[s] -= static_cast<std::int32_t>(le.turns);
    }
    while (x[g] < lo) {
      const double y = x[g] + l;
      if (y >= hi) {  // within half an ulp of lo: onto the face (see below)
        x[g] = lo;
        break;
      }
      x[g] = y;
      x[s] += le.offset;
      --image[g];
      image[s] += static_cast<std::int32_t>(le.turns);
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!cell.periodic[a] || a == cell.shear.gradient) continue;
    const double lo = cell.box.lo[a], hi = cell.box.hi[a], l = hi - lo;
    while (x[a] >= hi) {
      x[a] -= l;
      ++image[a];
    }
    while (x[a] < lo) {
      // x + l rounds up to hi itself for an x within half an ulp of lo, below it: the point is
      // then taken onto the lower face (a move of less than an ulp of l), in this cell.
      const double y = x[a] + l;
      if (y >= hi) {
        x[a] = lo;
        break;
      }
      x[a] = y;
      --image[a];
    }
  }
}

// The unwrapped position x + h n (n the image counter): continuous across the wraps, and in a
// sheared cell across the remaps of its tilt (a remap moves the tilt's turns, which the counter
// of the shear axis took at each crossing of the gradient axis).
inline Vec3 unwrapped(const PeriodicCell& cell, const Vec3& x, const ImageCount& image) {
  Vec3 u = x;
  for (int a = 0; a < 3; ++a)
    if (cell.periodic[a]) u[a] += image[a] * cell.length(a);
  if (const ShearImages& le = cell.shear; le.any()) u[le.shear] += image[le.gradient] * cell.tilt();
  return u;
}

}  // namespace upgrain::dem
