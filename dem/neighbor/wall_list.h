#pragma once
// Wall neighbour lists: for each wall, the particles within r + skin of it, rebuilt with
// the Verlet list, so the force loop visits only grains near a wall instead of all grains
// for every wall. Each entry carries its tangential spring; at a rebuild the springs of
// active contacts are carried over by particle id.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/contact_response.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem {

class WallNeighborList {
 public:
  struct Entries {
    std::vector<int> particle;             // local index
    std::vector<GlobalId> id;              // global id, for carrying springs over rebuilds
    std::vector<TangentialSpring> spring;  // empty when the scene has no wall friction
    std::vector<double> r_star;            // Hertz radius frozen at first touch (ellipsoid scenes)
    std::vector<RollingSpring> rolling;    // rolling spring, torque on the grain (rolling resistance)
  };

  WallNeighborList(double skin, bool with_history) : skin_(skin), with_history_(with_history) {}

  // Call after every change of the particles' local order (i.e. after VerletList::rebuild).
  void rebuild(const ParticleStore& p, const std::vector<PlaneWall>& walls);

  // Ellipsoid scenes: keep each entry's frozen Hertz radius (contact_response.h).
  void keep_contact_radii() { with_radii_ = true; }
  // Scenes with rolling resistance: keep each entry's rolling spring.
  void keep_rolling_springs() { with_rolling_ = true; }
  [[nodiscard]] std::vector<Entries>& walls() { return lists_; }
  [[nodiscard]] const std::vector<Entries>& walls() const { return lists_; }

 private:
  double skin_;
  bool with_history_;
  bool with_radii_ = false;
  bool with_rolling_ = false;
  std::vector<Entries> lists_;
};

}  // namespace upgrain::dem
