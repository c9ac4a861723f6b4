// The Parallel section: the summation, the blocks and the load balance (docs/parallel.md).
#include <sstream>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto parallel(Member m) {
  return at(&SceneInput::parallel, m);
}

}  // namespace

Section parallel_section() {
  Section section{
      "Parallel",
      {choice("summation", parallel(&ParallelInput::summation),
              {{"deterministic", dem::Summation::deterministic}, {"fast", dem::Summation::fast}},
              "How the DEM sums forces and global quantities (docs/architecture.md). deterministic: each "
              "grain adds its contacts in the order of its partners' ids, and every result and output "
              "byte is the same on any rank count. fast: a scatter over a half list in local order, "
              "forces on ghosts returned to their owners; results then depend on the rank count to "
              "round-off."),
       choice("DEM engine", parallel(&ParallelInput::legacy_engine),
              {{"auto", std::string("auto")}, {"serial", std::string("serial")}, {"mpi", std::string("mpi")}},
              "No longer used: one engine runs the DEM on every rank count (docs/parallel.md). Kept so "
              "that older scene files still run; a value other than auto is ignored with a warning."),
       integer3("blocks", parallel(&ParallelInput::blocks), 0, 4096, "-",
                "Blocks of the DEM's domain decomposition along x, y, z; their product must be the rank "
                "count. 0, 0, 0 = chosen to minimise the cut area for the rank count and the box."),
       real("balance interval", parallel(&ParallelInput::balance_interval), 0.0, 1e6, "s",
            "Simulated time between moves of the block planes to the quantiles of the cost (load "
            "balance, docs/parallel.md), applied at the next neighbour-list rebuild; also once at the "
            "start. 0 = fixed blocks. Results do not depend on it, only the speed."),
       choice("balance cost", parallel(&ParallelInput::balance_by_pairs),
              {{"particles", false}, {"pair slots", true}},
              "What the load balance equalises per block: owned particles, or particles plus their "
              "neighbour-list pairs (better for beds with loose and dense regions).")},
      nullptr};
  section.check = [](SceneInput& in, const std::string& where) {
    const auto& b = in.parallel.blocks;
    const bool chosen = b[0] == 0 && b[1] == 0 && b[2] == 0;
    if (!chosen && (b[0] == 0 || b[1] == 0 || b[2] == 0)) {
      std::ostringstream m;
      m << where << "Parallel/blocks = " << b[0] << ", " << b[1] << ", " << b[2]
        << ": give every count (their product is the rank count), or 0, 0, 0 to have them chosen";
      throw Error(m.str());
    }
  };
  return section;
}

}  // namespace upgrain::coupling::input
