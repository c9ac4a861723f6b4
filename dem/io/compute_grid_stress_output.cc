#include "dem/io/compute_grid_stress_output.h"

#include <cstdio>

#include "dem/io/grid_stress_output.h"
#include "dem/stress/asymmetry.h"

namespace upgrain::dem::io {

namespace {
std::string compute_grid_header() {
  return "# Upgrain stress per compute grid (MPI block = rank; docs/stress.md, \"Stress in parallel\"). "
         "sigma_ij = (1/V) sum f_i l_j: first index the force, second the branch; compression negative; Pa. "
         "V = the block's volume (outer blocks clipped to the decomposition box); a grain belongs to the "
         "block of its owner. rai = relative asymmetry index (fraction, 2-norm).\n"
         "time,step,block,x0,y0,z0,x1,y1,z1,volume,formula,s_xx,s_xy,s_xz,s_yx,s_yy,s_yz,s_zx,s_zy,s_zz,rai,"
         "particles,internal_contacts,external_contacts,wall_contacts,solid_fraction\n";
}
}  // namespace

ComputeGridStressRecorder::ComputeGridStressRecorder(std::filesystem::path folder,
                                                     std::vector<StressFormula> formulas)
    : folder_(std::move(folder)),
      formulas_(std::move(formulas)),
      csv_(folder_ / "compute_grid_stress.csv", compute_grid_header()) {}

void ComputeGridStressRecorder::record(const ComputeGridStress& blocks, double time, long step) {
  const GridStress& g = blocks.stress;
  std::string rows;
  for (std::size_t b = 0; b < blocks.block.size(); ++b) {
    const Box& box = blocks.block[b];
    const double volume = g.volume.empty() ? g.cell_volume : g.volume[b];
    for (StressFormula f : formulas_) {
      const Mat3& s = g[f][b];
      char line[896];
      std::snprintf(
          line, sizeof line,
          "%.9g,%ld,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%."
          "17g,%.17g,%.17g,%.17g,%.17g,%ld,%ld,%ld,%ld,%.17g\n",
          time, step, b, box.lo.x(), box.lo.y(), box.lo.z(), box.hi.x(), box.hi.y(), box.hi.z(), volume,
          field_name(f).c_str(), s(0, 0), s(0, 1), s(0, 2), s(1, 0), s(1, 1), s(1, 2), s(2, 0), s(2, 1),
          s(2, 2), relative_asymmetry_index(s), g.particles[b], g.internal_contacts[b],
          g.external_contacts[b], g.wall_contacts[b], g.solid_fraction[b]);
      rows += line;
    }
  }
  csv_.append(rows);
}

}  // namespace upgrain::dem::io
