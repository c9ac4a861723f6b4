#pragma once
// The contact candidates of one rank, as plain data: the pair slots of a Verlet list in
// rows (CSR) and the particle-wall entries. Built by dem/neighbor/verlet_list.h; the force
// loop (dem/engine/force_loop.h) runs over them and the contact-history store
// (contact_history.h) keeps one history per slot and per entry.
#include <cstddef>
#include <vector>

namespace upgrain::dem {

// Slot k of row r is the pair (row_particle[r], partner[k]) for k in [row_start[r],
// row_start[r + 1]), both local indices (owned particles first, then ghosts). The first
// particle is the pair's body i: its forces, springs and normals are oriented from it.
struct PairList {
  std::vector<int> row_particle;
  std::vector<int> row_start{0};
  std::vector<int> partner;

  [[nodiscard]] std::size_t num_rows() const { return row_particle.size(); }
  [[nodiscard]] std::size_t num_pairs() const { return partner.size(); }
};

// Entry e is owned particle particle[e] near wall wall[e].
struct WallList {
  std::vector<int> particle;
  std::vector<int> wall;

  [[nodiscard]] std::size_t size() const { return particle.size(); }
};

}  // namespace upgrain::dem
