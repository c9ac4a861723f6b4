#pragma once
// The grid strain of one evaluation as plain per-cell fields for the deal.II mesh
// (upscale/grid_mesh.h), so ParaView shows ln J, the equivalent shear strain and any
// component of F and of the Hencky strain ln V as cell data (docs/strain.md).
// No deal.II here.
#include <filesystem>

#include "upscale/grid_fields.h"
#include "upscale/strain/grid_strain.h"

namespace upgrain::upscale {

// On the strain's grid (the reference grid for Lagrangian sets, the current one for
// Eulerian), for each definition computed, with d = "best_fit" or "tessellation":
//   "<d>_ln_J", "<d>_J", "<d>_equivalent_shear_strain", "<d>_equivalent_shear_rate",
//   "<d>_increment_equivalent_shear_strain", "<d>_F_valid" (1 or 0), "<d>_F_reason" (the
//   StrainReason code), "<d>_F_xx" ... "<d>_F_zz", "<d>_hencky_xx" ... "<d>_hencky_zz"
//   (ln V, row-major);
// then "particles" (the size of each cell's set). Invalid cells hold zeros, as in the
// HDF5 files: threshold on <d>_F_valid in ParaView. The Q1 projection would blend those
// zeros into the neighbours, so the driver writes these as cell data only.
GridFields grid_fields_from_strain(const upscale::GridStrain& strain);

// The same fields, bit for bit, from a file written by upscale::write_grid_strain, for the
// definitions present in it. Errors name the file and the missing or misshapen dataset.
GridFields read_strain_fields(const std::filesystem::path& h5_file);

}  // namespace upgrain::upscale
