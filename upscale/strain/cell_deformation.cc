#include "upscale/strain/cell_deformation.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace upgrain::upscale {

CellDeformation cell_deformation(const Mat3& h0, const Mat3& h, const std::array<bool, 3>& periodic,
                                 std::span<const GlobalId> reference_id, std::span<const Vec3> reference_x,
                                 std::span<const GlobalId> id, std::span<const Vec3> x) {
  CellDeformation d;
  d.cell = h * h0.inverse();
  std::vector<Vec3> a, b;
  a.reserve(id.size());
  b.reserve(id.size());
  std::size_t r = 0;
  for (std::size_t i = 0; i < id.size(); ++i) {
    while (r < reference_id.size() && reference_id[r] < id[i]) ++r;
    if (r < reference_id.size() && reference_id[r] == id[i]) {
      a.push_back(reference_x[r]);
      b.push_back(x[i]);
    }
  }
  d.grains = fit_deformation_gradient(a, b);
  if (!d.grains.valid) {
    d.difference = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (periodic[i] && periodic[j])
        d.difference = std::max(d.difference, std::abs(d.grains.gradient(i, j) - d.cell(i, j)));
  return d;
}

std::string cell_deformation_header() {
  std::string h =
      "# Upgrain: the deforming cell's F = h h0^-1 beside the best-fit F of all its grains followed across "
      "the faces (docs/periodic.md, \"Strain over a periodic cell\"); difference = max |F_grains - F_cell| "
      "over the components between periodic axes\ntime,step";
  for (const char* who : {"F_cell_", "F_grains_"})
    for (const char* c : {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"})
      h += std::string(",") + who + c;
  return h + ",difference,grains\n";
}

std::string cell_deformation_row(double time, long step, const CellDeformation& d) {
  char b[64];
  std::string row;
  auto put = [&](double v) {
    std::snprintf(b, sizeof b, std::isfinite(v) ? ",%.17g" : ",", v);
    row += b;
  };
  std::snprintf(b, sizeof b, "%.17g,%ld", time, step);
  row = b;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) put(d.cell(i, j));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) put(d.grains.valid ? d.grains.gradient(i, j) : std::nan(""));
  put(d.difference);
  std::snprintf(b, sizeof b, ",%d\n", d.grains.points);
  return row + b;
}

}  // namespace upgrain::upscale
