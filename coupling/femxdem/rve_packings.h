#pragma once
// Which prepared DEM cell each Gauss point of FEM x DEM copies (docs/femxdem.md, "Point-to-point
// variability"). One packing copied to every point leaves a specimen under symmetric loading
// symmetric to round-off; distinct packings, each prepared to the same isotropic stress from its
// own random fill, give the points the scatter of a real specimen, which triggers localisation
// (Shahin et al. 2016, Int. J. Numer. Meth. Engng, doi:10.1002/nme.5202). A point's packing is a
// function of its place alone (its cell's id and its index in the cell), so it is the same on
// every rank count and after the point moves to another rank. The packings are prepared where
// and when a point starting a run first needs one (on MPI_COMM_SELF, deterministic) and then
// shared; a point that arrives with its bytes (a restart, a move) takes only its packing's frame.
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "coupling/femxdem/rve_preparation.h"
#include "fem/quasi_static/point_state.h"

namespace upgrain::coupling {

class RvePackings {
 public:
  // `count` packings with the seeds o.seed, o.seed + 1, ..., o.seed + count - 1, each point taking
  // the one its place's hash picks; count = 0: every point its own packing, seeded by o.seed and
  // its place's hash.
  RvePackings(const dem::SceneConfig& scene, const RveOptions& o, int count);

  // The packing of the point at `place`, prepared on first use.
  [[nodiscard]] std::shared_ptr<const RveTemplate> for_point(const fem::PointPlace& place);
  // The frame of that packing (rve_frame(): its scene, engine and grains, not prepared), for a
  // cell loaded from its bytes; the packing itself when it was prepared here already.
  [[nodiscard]] std::shared_ptr<const RveTemplate> frame_for_point(const fem::PointPlace& place);
  // The packing of seed o.seed: the first one (what the study reports).
  [[nodiscard]] std::shared_ptr<const RveTemplate> first();
  // The seed of the point at `place`.
  [[nodiscard]] std::uint64_t seed_of(const fem::PointPlace& place) const;

  [[nodiscard]] std::size_t prepared() const { return prepared_.size(); }
  [[nodiscard]] double preparation_seconds() const { return seconds_; }

 private:
  [[nodiscard]] std::shared_ptr<const RveTemplate> with_seed(std::uint64_t seed);

  dem::SceneConfig scene_;
  RveOptions options_;
  int count_;
  std::map<std::uint64_t, std::shared_ptr<const RveTemplate>> prepared_;
  std::map<std::uint64_t, std::shared_ptr<const RveTemplate>> frames_;
  double seconds_ = 0.0;
};

// FNV-1a (Fowler, Noll and Vo) of a point's place: its cell's id and its index, the same bits on
// every platform.
[[nodiscard]] std::uint64_t place_hash(const fem::PointPlace& place);

}  // namespace upgrain::coupling
