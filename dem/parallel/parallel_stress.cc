#include "dem/parallel/parallel_stress.h"

#include <algorithm>
#include <array>

#include "dem/parallel/exchange.h"

namespace upgrain::dem {

namespace {

// StressSums as 50 doubles (the counts are exact as doubles), for messages.
constexpr int kFlat = 5 * 9 + 5;
using FlatSums = std::array<double, kFlat>;

FlatSums flatten(const StressSums& s) {
  FlatSums f{};
  const Mat3* m[5] = {&s.weber, &s.drescher, &s.bagi, &s.de_saxce, &s.inertial};
  for (int k = 0; k < 5; ++k) std::copy(m[k]->data(), m[k]->data() + 9, f.begin() + 9 * k);
  f[45] = static_cast<double>(s.particles);
  f[46] = static_cast<double>(s.internal_contacts);
  f[47] = static_cast<double>(s.external_contacts);
  f[48] = static_cast<double>(s.wall_contacts);
  f[49] = s.solid_volume;
  return f;
}

StressSums unflatten(const double* f) {
  StressSums s;
  Mat3* m[5] = {&s.weber, &s.drescher, &s.bagi, &s.de_saxce, &s.inertial};
  for (int k = 0; k < 5; ++k) std::copy(f + 9 * k, f + 9 * k + 9, m[k]->data());
  s.particles = static_cast<long>(f[45]);
  s.internal_contacts = static_cast<long>(f[46]);
  s.external_contacts = static_cast<long>(f[47]);
  s.wall_contacts = static_cast<long>(f[48]);
  s.solid_volume = f[49];
  return s;
}

struct ShareRecord {
  GlobalId gid;
  long cell;
  FlatSums sums;
};

// The shares summed per cell in global-id order (an index is sorted, not the 400-byte
// shares).
void sum_in_id_order(const std::vector<ParticleStressShare>& shares, std::vector<StressSums>& cells) {
  std::vector<std::pair<GlobalId, int>> order(shares.size());
  for (std::size_t k = 0; k < shares.size(); ++k) order[k] = {shares[k].gid, static_cast<int>(k)};
  std::sort(order.begin(), order.end());
  for (const auto& [gid, k] : order) {
    const ParticleStressShare& s = shares[static_cast<std::size_t>(k)];
    if (s.cell >= 0) cells[static_cast<std::size_t>(s.cell)] += s.sums;
  }
}

Box clip(const Box& block, const Box& box) { return {block.lo.cwiseMax(box.lo), block.hi.cwiseMin(box.hi)}; }

// The stress of every block from its sums, over the block's clipped volume.
void finish_blocks(ComputeGridStress& out, const std::vector<StressSums>& sums) {
  const int size = static_cast<int>(out.block.size());
  out.stress = empty_grid_stress(size, 0.0);
  out.stress.volume.resize(size);
  for (int r = 0; r < size; ++r) {
    const double v = (out.block[r].hi - out.block[r].lo).prod();
    out.stress.volume[r] = v;
    finish_cell(out.stress, r, sums[r], v);
  }
}

// Cell sums of every rank added elementwise over the ranks.
std::vector<StressSums> summed_over_ranks(const std::vector<StressSums>& mine, MPI_Comm comm) {
  std::vector<double> flat(mine.size() * kFlat);
  for (std::size_t c = 0; c < mine.size(); ++c) {
    const FlatSums f = flatten(mine[c]);
    std::copy(f.begin(), f.end(), flat.begin() + static_cast<std::ptrdiff_t>(c) * kFlat);
  }
  MPI_Allreduce(MPI_IN_PLACE, flat.data(), static_cast<int>(flat.size()), MPI_DOUBLE, MPI_SUM, comm);
  std::vector<StressSums> out(mine.size());
  for (std::size_t c = 0; c < mine.size(); ++c) out[c] = unflatten(flat.data() + c * kFlat);
  return out;
}

}  // namespace

std::vector<ParticleStressShare> particle_stress_shares(const ParticleStore& p, int n_owned,
                                                        const std::vector<ContactSample>& contacts,
                                                        const std::vector<int>& cell,
                                                        const std::vector<Vec3>& centre,
                                                        const GrainDynamics& dynamics) {
  // Each contact once per owned particle it touches, ordered by (particle, walls by
  // index, then partners by global id): the order of the sum does not depend on the rank
  // or on local indices.
  struct Entry {
    int owned;
    GlobalId key;  // wall w: w - 2^62, so walls come first; partner: its global id
    int sample;
  };
  constexpr GlobalId kWallBase = -(GlobalId{1} << 62);
  std::vector<Entry> entries;
  entries.reserve(2 * contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactSample& s = contacts[k];
    const int ks = static_cast<int>(k);
    if (s.with_wall()) {
      if (s.a < n_owned) entries.push_back({s.a, kWallBase + s.wall(), ks});
      continue;
    }
    if (s.a < n_owned) entries.push_back({s.a, p.id[s.b], ks});
    if (s.b < n_owned) entries.push_back({s.b, p.id[s.a], ks});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.owned < b.owned || (a.owned == b.owned && a.key < b.key);
  });

  std::vector<ParticleStressShare> out(static_cast<std::size_t>(n_owned));
  for (int i = 0; i < n_owned; ++i) {
    out[i].gid = p.id[i];
    out[i].cell = cell[i];
  }
  for (const Entry& e : entries) {
    const int i = e.owned;
    const int c = cell[i];
    if (c < 0) continue;
    StressSums& s = out[i].sums;
    const ContactSample& cs = contacts[e.sample];
    if (cs.with_wall()) {
      add_external_contact(s, cs.point, p.x[i], cs.force_on_a, centre[c]);
      ++s.wall_contacts;
      continue;
    }
    const bool is_a = cs.a == i;
    const int q = is_a ? cs.b : cs.a;
    const Vec3 f = is_a ? cs.force_on_a : Vec3(-cs.force_on_a);
    if (cell[q] == c) {
      // Internal: Bagi's per-grain branch to the contact point; Weber's centroid-to-centroid
      // term once, from the lower id.
      s.bagi += f * (cs.point - p.x[i]).transpose();
      if (p.id[i] < p.id[q]) {
        s.weber += f * (p.x[q] - p.x[i]).transpose();
        ++s.internal_contacts;
      }
    } else {
      add_external_contact(s, cs.point, p.x[i], f, centre[c]);
      ++s.external_contacts;
    }
  }
  for (int i = 0; i < n_owned; ++i) {
    const int c = cell[i];
    if (c < 0) continue;
    add_grain_count(out[i].sums, p.volume(static_cast<std::size_t>(i)));
    add_grain_terms(out[i].sums, p, static_cast<std::size_t>(i), centre[c], dynamics);
  }
  return out;
}

// The positions by which grains are put into grid cells: in a periodic cell, wrapped
// (periodic_cell.h), so that a ghost image and a grain not yet wrapped since it crossed a face
// belong to the cell their grain is in; their branch vectors keep the image positions (the
// minimum image). Otherwise the positions themselves.
namespace {
std::vector<Vec3> positions_in_cell(const std::vector<Vec3>& x, const PeriodicCell& cell) {
  if (!cell.any()) return x;
  std::vector<Vec3> w = x;
  ImageCount image{0, 0, 0};
  for (Vec3& y : w) wrap(cell, y, image);
  return w;
}
}  // namespace

GridStress parallel_grid_stress(const ParticleStore& local, int n_owned,
                                const std::vector<ContactSample>& contacts, const RegularGrid& grid,
                                const GrainDynamics& dynamics, MPI_Comm comm, const PeriodicCell& cell) {
  const int cells = grid.num_cells();
  const CellAssignment a = assign_cells(grid, positions_in_cell(local.x, cell));
  const std::vector<ParticleStressShare> shares =
      particle_stress_shares(local, n_owned, contacts, a.cell, a.centre, dynamics);

  std::vector<ShareRecord> mine;
  for (const ParticleStressShare& s : shares)
    if (s.cell >= 0) mine.push_back({s.gid, s.cell, flatten(s.sums)});
  std::vector<ShareRecord> all = gather_to_root(mine, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<double> flat(static_cast<std::size_t>(cells) * kFlat, 0.0);
  if (rank == 0) {
    std::vector<std::pair<GlobalId, int>> order(all.size());
    for (std::size_t k = 0; k < all.size(); ++k) order[k] = {all[k].gid, static_cast<int>(k)};
    std::sort(order.begin(), order.end());
    std::vector<StressSums> sums(cells);
    for (const auto& [gid, k] : order) sums[all[k].cell] += unflatten(all[k].sums.data());
    for (int c = 0; c < cells; ++c) {
      const FlatSums f = flatten(sums[c]);
      std::copy(f.begin(), f.end(), flat.begin() + static_cast<std::ptrdiff_t>(c) * kFlat);
    }
  }
  MPI_Bcast(flat.data(), static_cast<int>(flat.size()), MPI_DOUBLE, 0, comm);
  GridStress g = empty_grid_stress(cells, grid.cell_volume());
  for (int c = 0; c < cells; ++c) finish_cell(g, c, unflatten(flat.data() + c * kFlat), g.cell_volume);
  return g;
}

std::vector<Box> compute_grid_blocks(const Decomposition& d) {
  std::vector<Box> block(static_cast<std::size_t>(d.size()));
  const auto& dims = d.blocks();
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const std::array<int, 3> c{i, j, k};
        Box b;
        for (int a = 0; a < 3; ++a) {
          b.lo[a] = d.plane(a, c[a]);
          b.hi[a] = d.plane(a, c[a] + 1);
        }
        block[d.rank_of_block(c)] = clip(b, d.box());
      }
  return block;
}

ComputeGridStress parallel_compute_grid_stress(const ParticleStore& local, int n_owned,
                                               const std::vector<ContactSample>& contacts,
                                               const Decomposition& d, const GrainDynamics& dynamics) {
  const int size = d.size();
  ComputeGridStress out;
  out.block = compute_grid_blocks(d);
  // One cell: this rank's owned particles. Ghosts are outside it.
  std::vector<int> cell(local.size(), -1);
  std::fill(cell.begin(), cell.begin() + n_owned, 0);
  const Box& mine = out.block[d.rank()];
  const std::vector<Vec3> centre{0.5 * (mine.lo + mine.hi)};
  const std::vector<ParticleStressShare> shares =
      particle_stress_shares(local, n_owned, contacts, cell, centre, dynamics);
  std::vector<StressSums> sums(1);
  sum_in_id_order(shares, sums);
  const FlatSums f = flatten(sums[0]);
  std::vector<double> flat(static_cast<std::size_t>(size) * kFlat);
  MPI_Allgather(f.data(), kFlat, MPI_DOUBLE, flat.data(), kFlat, MPI_DOUBLE, d.comm());
  std::vector<StressSums> sums_of(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) sums_of[static_cast<std::size_t>(r)] = unflatten(flat.data() + r * kFlat);
  finish_blocks(out, sums_of);
  return out;
}

GridStress summed_grid_stress(const ParticleStore& local, int n_owned,
                              const std::vector<ContactSample>& contacts, const RegularGrid& grid,
                              const GrainDynamics& dynamics, MPI_Comm comm, const PeriodicCell& cell) {
  const int cells = grid.num_cells();
  const CellAssignment a = assign_cells(grid, positions_in_cell(local.x, cell));
  std::vector<StressSums> sums =
      cell_stress_sums(local, static_cast<std::size_t>(n_owned), contacts, a.cell, a.centre, dynamics);
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size > 1) sums = summed_over_ranks(sums, comm);
  GridStress g = empty_grid_stress(cells, grid.cell_volume());
  for (int c = 0; c < cells; ++c) finish_cell(g, c, sums[c], g.cell_volume);
  return g;
}

ComputeGridStress summed_compute_grid_stress(const ParticleStore& local, int n_owned,
                                             const std::vector<ContactSample>& contacts,
                                             const Decomposition& d, const std::vector<int>& owner,
                                             const GrainDynamics& dynamics) {
  const int size = d.size();
  ComputeGridStress out;
  out.block = compute_grid_blocks(d);
  std::vector<Vec3> centre(size);
  for (int r = 0; r < size; ++r) centre[r] = 0.5 * (out.block[r].lo + out.block[r].hi);
  std::vector<StressSums> sums =
      cell_stress_sums(local, static_cast<std::size_t>(n_owned), contacts, owner, centre, dynamics);
  if (size > 1) sums = summed_over_ranks(sums, d.comm());
  finish_blocks(out, sums);
  return out;
}

}  // namespace upgrain::dem
