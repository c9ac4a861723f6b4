#include "coupling/femxdem/rve_packings.h"

#include <chrono>

namespace upgrain::coupling {

std::uint64_t place_hash(const fem::PointPlace& place) {
  std::uint64_t h = 14695981039346656037ull;
  const auto mix = [&](unsigned char c) {
    h ^= c;
    h *= 1099511628211ull;
  };
  for (const char c : place.cell) mix(static_cast<unsigned char>(c));
  mix('/');
  for (int k = 0; k < 4; ++k) mix(static_cast<unsigned char>((place.index >> (8 * k)) & 0xffu));
  return h;
}

RvePackings::RvePackings(const dem::SceneConfig& scene, const RveOptions& o, int count)
    : scene_(scene), options_(o), count_(count) {}

std::uint64_t RvePackings::seed_of(const fem::PointPlace& place) const {
  const std::uint64_t h = place_hash(place);
  // A seed per point stays below 2^31 as the section's seeds do (the fill's generator takes any).
  if (count_ == 0) return (options_.seed + (h >> 33)) & 0x7fffffffull;
  return options_.seed + h % static_cast<std::uint64_t>(count_);
}

std::shared_ptr<const RveTemplate> RvePackings::with_seed(std::uint64_t seed) {
  auto& made = prepared_[seed];
  if (!made) {
    const auto t0 = std::chrono::steady_clock::now();
    RveOptions o = options_;
    o.seed = seed;
    made = std::make_shared<const RveTemplate>(prepare_rve(scene_, o));
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return made;
}

std::shared_ptr<const RveTemplate> RvePackings::for_point(const fem::PointPlace& place) {
  return with_seed(seed_of(place));
}

std::shared_ptr<const RveTemplate> RvePackings::frame_for_point(const fem::PointPlace& place) {
  const std::uint64_t seed = seed_of(place);
  if (const auto prepared = prepared_.find(seed); prepared != prepared_.end()) return prepared->second;
  auto& made = frames_[seed];
  if (!made) {
    RveOptions o = options_;
    o.seed = seed;
    made = std::make_shared<const RveTemplate>(rve_frame(scene_, o));
  }
  return made;
}

std::shared_ptr<const RveTemplate> RvePackings::first() { return with_seed(options_.seed); }

}  // namespace upgrain::coupling
