#include "dem/neighbor/verlet_list.h"

#include <algorithm>

namespace upgrain::dem {

namespace {

// A spring carried over a rebuild: the pair of global ids (lo < hi) and the spring
// oriented as the force on the particle with id lo. A sorted vector holds them: 48 bytes
// per active contact, less than half a hash map's, and its order does not depend on hashing.
struct CarriedSpring {
  GlobalId lo, hi;
  TangentialSpring spring;
  ShapedContactMemory memory;  // normal from lo to hi (ellipsoid scenes; else empty)
  RollingSpring rolling;       // torque on lo (rolling resistance; else empty)
  bool operator<(const CarriedSpring& o) const { return lo < o.lo || (lo == o.lo && hi < o.hi); }
};

}  // namespace

VerletList::VerletList(double max_radius, double skin, bool with_history)
    : cell_size_(2.0 * max_radius + skin), skin_(skin), with_history_(with_history) {}

bool VerletList::needs_rebuild(const ParticleStore& p) const {
  if (x_at_build_.size() != p.size()) return true;
  const double limit2 = rebuild_displacement2();
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if ((p.x[i] - x_at_build_[i]).squaredNorm() > limit2) return true;
  }
  return false;
}

void VerletList::rebuild(ParticleStore& p) {
  const int n = static_cast<int>(p.size());

  // 1. Springs of active contacts, keyed by the pair of global ids and oriented as the
  //    force on the particle with the smaller id.
  std::vector<CarriedSpring> history;
  const bool carry = (with_history_ || with_memory_ || with_rolling_) && !partners_.empty();
  if (carry) {
    auto spring_at = [&](int k) { return with_history_ ? springs_[k] : TangentialSpring{}; };
    auto memory_at = [&](int k) { return with_memory_ ? memory_[k] : ShapedContactMemory{}; };
    auto rolling_at = [&](int k) { return with_rolling_ ? rolling_[k] : RollingSpring{}; };
    std::size_t active = 0;
    for (std::size_t k = 0; k < partners_.size(); ++k)
      active += spring_at(static_cast<int>(k)).stiffness != 0.0 || !memory_at(static_cast<int>(k)).empty() ||
                rolling_at(static_cast<int>(k)).stiffness != 0.0;
    history.reserve(active);
    const int n_old = static_cast<int>(offsets_.size()) - 1;
    for (int i = 0; i < n_old; ++i) {
      for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
        const TangentialSpring s = spring_at(k);
        const ShapedContactMemory m = memory_at(k);
        const RollingSpring r = rolling_at(k);
        if (s.stiffness == 0.0 && m.empty() && r.stiffness == 0.0) continue;  // nothing to carry
        const GlobalId a = p.id[i];
        const GlobalId b = p.id[partners_[k]];
        if (a < b)
          history.push_back({a, b, s, m, r});
        else
          history.push_back({b, a, TangentialSpring{-s.force, s.stiffness}, m.reversed(),
                             RollingSpring{-r.torque, r.stiffness}});
      }
    }
  }

  // 2. Sort particles by cell for memory locality.
  Vec3 lo = Vec3::Constant(0.0), hi = Vec3::Constant(0.0);
  if (n > 0) {
    lo = hi = p.x[0];
    for (int i = 1; i < n; ++i) {
      lo = lo.cwiseMin(p.x[i]);
      hi = hi.cwiseMax(p.x[i]);
    }
  }
  grid_ = CellGrid(lo, hi, cell_size_, 4L * n + 64);
  grid_.bin(p.x);
  const std::vector<int>& perm = grid_.order();
  p.permute(perm);
  const std::vector<int>& start = grid_.cell_start();
  const auto& dims = grid_.dims();

  // 3. Half list from the 27-cell stencil.
  offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
  partners_.clear();
  for (int i = 0; i < n; ++i) {
    offsets_[i] = static_cast<int>(partners_.size());
    const Vec3 xi = p.x[i];
    const double ri = p.radius[i] + skin_;
    const auto c = grid_.cell_coords(xi);
    for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
        for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, dims[0] - 1); ++x) {
          const int cell = grid_.flat(x, y, z);
          for (int j = std::max(start[cell], i + 1); j < start[cell + 1]; ++j) {
            const double cut = ri + p.radius[j];
            if ((p.x[j] - xi).squaredNorm() < cut * cut) partners_.push_back(j);
          }
        }
  }
  offsets_[n] = static_cast<int>(partners_.size());
  // The list's size changes little between builds: drop the slack of the first build's
  // doubling growth once (measured: part of the peak memory per grain of the benchmark).
  if (partners_.capacity() > partners_.size() + partners_.size() / 8) partners_.shrink_to_fit();
  // Partners in increasing local index: a deterministic order of force accumulation.
  for (int i = 0; i < n; ++i) std::sort(partners_.begin() + offsets_[i], partners_.begin() + offsets_[i + 1]);

  // 4. Carry the springs over.
  std::sort(history.begin(), history.end());
  springs_.assign(with_history_ ? partners_.size() : 0, TangentialSpring{});
  memory_.assign(with_memory_ ? partners_.size() : 0, ShapedContactMemory{});
  rolling_.assign(with_rolling_ ? partners_.size() : 0, RollingSpring{});
  if (!history.empty()) {
    for (int i = 0; i < n; ++i) {
      for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
        const GlobalId a = p.id[i];
        const GlobalId b = p.id[partners_[k]];
        const CarriedSpring key{std::min(a, b), std::max(a, b), {}, {}, {}};
        const auto it = std::lower_bound(history.begin(), history.end(), key);
        if (it == history.end() || it->lo != key.lo || it->hi != key.hi) continue;
        if (with_history_)
          springs_[k] = a < b ? it->spring : TangentialSpring{-it->spring.force, it->spring.stiffness};
        if (with_memory_) memory_[k] = a < b ? it->memory : it->memory.reversed();
        if (with_rolling_)
          rolling_[k] = a < b ? it->rolling : RollingSpring{-it->rolling.torque, it->rolling.stiffness};
      }
    }
  }
  x_at_build_ = p.x;
  ++builds_;
}

}  // namespace upgrain::dem
