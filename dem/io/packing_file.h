#pragma once
// Initial packings: grains a run starts from instead of a fill, read from a text table (CSV or
// whitespace), a LAMMPS/LIGGGHTS data file (atom_style sphere or granular) or an Upgrain
// snapshot (HDF5). docs/input.md, "Starting from a packing".
#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dem/boundary/container.h"
#include "dem/core/box.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem::io {

// A grain as a file gives it, before it is numbered.
struct PackedGrain {
  long file_id = 0;
  long line = 0;  // 1-based line of a text file; the row (from 1) of a snapshot
  Vec3 x = Vec3::Zero();
  Vec3 v = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  Vec3 semi_axes = Vec3::Ones();                                    // a >= b >= c; a sphere has a = b = c = r
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world
  ImageCount image{0, 0, 0};  // a LAMMPS data file's image flags (docs/periodic.md)
};

struct Packing {
  ParticleStore grains;            // ids 0..N-1, in the order of the file's ids
  std::vector<long> file_id;       // the file's id of each grain (by Upgrain id)
  std::vector<long> line;          // where each grain is given (by Upgrain id)
  std::string format;              // what the file was read as, for the log
  std::string where_word;          // "line" for text files, "row" for snapshots
  std::vector<std::string> notes;  // what the user should hear (a density the scene overrides)
  // A LAMMPS data file's box (its xlo xhi, ylo yhi, zlo zhi lines), and the line of each axis's.
  std::optional<Box> file_box;
  std::array<long, 3> box_line{0, 0, 0};

  // "grain 17 (line 19)": a grain by the file's id and where the file gives it.
  [[nodiscard]] std::string name(std::size_t k) const;
};

// Reads `path`: an HDF5 file as an Upgrain snapshot, a file with an "N atoms" header line as a
// LAMMPS data file, anything else as a text table. Every grain gets `density` (the scene's
// material). Throws upgrain::Error naming the file, and the line and column of a text file.
Packing read_packing(const std::filesystem::path& path, double density);

// The grains of a file numbered and stored: sorted by the file's ids (which must be unique),
// ids 0..N-1 in that order; the semi-axes and orientations checked. Used by every format.
Packing number_grains(std::vector<PackedGrain> grains, double density, const std::string& file,
                      const std::string& where_word);

// Text tables and LAMMPS data files (packing_text.cc).
std::vector<PackedGrain> read_text_table(const std::filesystem::path& path);
bool looks_like_lammps_data(const std::filesystem::path& path);
// `notes` receives what the file says that the run does not use (a density per atom); `box`
// its box, when the header gives all three axes' bounds (`box_line`: their lines). The image
// flags are kept: check_packing() refuses them on an axis that is not periodic.
std::vector<PackedGrain> read_lammps_data(const std::filesystem::path& path, double density,
                                          std::vector<std::string>& notes, std::string& style,
                                          std::optional<Box>* box = nullptr,
                                          std::array<long, 3>* box_line = nullptr);

// Refuses a packing a run cannot start from: a grain reaching through a wall of the container
// (the floor, the side walls, the gate of a constrained collapse), two grains overlapping by
// more than `overlap_limit` of the smaller one's smallest semi-axis, an image flag on an axis
// that is not periodic, or a file's box that is not the periodic cell along a periodic axis.
// Throws upgrain::Error naming the file and the grains.
void check_packing(const Packing& packing, const BoxContainer& box, const std::string& file,
                   double overlap_limit);

// The overlap a packing may hold: 5 % of the smaller grain's smallest semi-axis. A settled
// Hertz bed's contacts overlap by 1e-4 to 1e-2 of a radius; more than a twentieth is a packing
// made for other grains (docs/input.md).
inline constexpr double kPackingOverlapLimit = 0.05;

}  // namespace upgrain::dem::io
