#pragma once
// Particle state as structure-of-arrays indexed by local index, with a persistent global
// id that survives reordering (and migration between ranks).
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "dem/core/periodic_cell.h"
#include "dem/core/shape_kind.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// A three-axis ellipsoid's body: semi-axes a >= b >= c along its body x, y, z axes (m), its
// uniform density (kg/m^3) and its orientation (body -> world).
struct EllipsoidBody {
  Vec3 semi_axes;
  double density;
  Eigen::Quaterniond orientation;
};

// Where a grain is and how it moves: centroid, velocity, angular velocity (world frame).
struct GrainMotion {
  Vec3 x;
  Vec3 v;
  Vec3 omega;
};

struct ParticleStore {
  std::vector<GlobalId> id;
  std::vector<double> radius;
  std::vector<double> inv_mass;     // 1 / m: the mass itself is not stored (8 B per grain less)
  std::vector<double> inv_inertia;  // sphere: 1 / (2/5 m r^2)
  std::vector<Vec3> x;              // centroid position (m)
  std::vector<Vec3> v;              // velocity (m/s)
  std::vector<Vec3> omega;          // angular velocity (rad/s)
  std::vector<Vec3> force;          // contact force of the current step (N)
  std::vector<Vec3> torque;         // contact torque about the centroid (N m)
  // Crossings of a periodic cell per axis (dem/core/periodic_cell.h): x + image L is the grain's
  // unwrapped position. Zero along bounded axes; a ghost's is its owner's plus the image shift.
  std::vector<ImageCount> image;

  // Shapes of three-axis ellipsoids (docs/ellipsoids.md). Empty while every grain is a
  // sphere, so sphere scenes carry and compute nothing for them; once an ellipsoid is
  // added they hold every grain, spheres as a = b = c. For an ellipsoid, radius[i] is its
  // bounding radius a (neighbour lists, broad phase) and inv_inertia[i] is not used.
  std::vector<ShapeKind> shape;                 // each grain's row of the shape table
  std::vector<Vec3> semi_axes;                  // a >= b >= c along the body x, y, z axes (m)
  std::vector<Eigen::Quaterniond> orientation;  // body -> world, unit
  std::vector<Vec3> inertia_body;               // principal moments of inertia (kg m^2)

  [[nodiscard]] std::size_t size() const { return id.size(); }
  [[nodiscard]] double mass(std::size_t i) const { return 1.0 / inv_mass[i]; }

  void reserve(std::size_t n);
  void add_sphere(GlobalId gid, double r, double density, const Vec3& pos, const Vec3& vel,
                  const Vec3& ang_vel);
  // A three-axis ellipsoid, semi-axes a >= b >= c (checked), uniform density.
  void add_ellipsoid(GlobalId gid, const EllipsoidBody& body, const GrainMotion& motion);
  // Gives every grain its shape arrays (spheres as a = b = c) if the store has none yet: what the
  // first ellipsoid does, for a store that is to receive ellipsoids (a pour, docs/insertion.md).
  void ensure_shapes();
  // Applies new[k] = old[perm[k]] to every array.
  void permute(const std::vector<int>& perm);

  [[nodiscard]] bool has_shapes() const { return !shape.empty(); }
  [[nodiscard]] ShapeKind kind(std::size_t i) const { return has_shapes() ? shape[i] : ShapeKind::sphere; }
  [[nodiscard]] bool is_ellipsoid(std::size_t i) const { return kind(i) == ShapeKind::ellipsoid; }
  // Every shape but the sphere has an orientation and a diagonal inertia in its body frame
  // (orientation, inertia_body); a sphere's rotation is a kick of omega by 1 / inv_inertia.
  [[nodiscard]] bool oriented(std::size_t i) const { return kind(i) != ShapeKind::sphere; }
  // Smallest semi-axis: the length overlaps are measured against.
  [[nodiscard]] double min_semi_axis(std::size_t i) const {
    return has_shapes() ? semi_axes[i].z() : radius[i];
  }
  [[nodiscard]] double volume(std::size_t i) const;
  // How far grain i reaches from its centre along the unit direction n: the support function
  // sqrt(n^T M n), M = Q diag(a^2, b^2, c^2) Q^T (docs/ellipsoid-contact.md); r for a sphere.
  [[nodiscard]] double reach(std::size_t i, const Vec3& n) const {
    if (!oriented(i)) return radius[i];
    return (orientation[i].conjugate() * n).cwiseProduct(semi_axes[i]).norm();
  }
  // Inertia tensor about the centroid in the world frame, Q J_body Q^T.
  [[nodiscard]] Mat3 inertia_world(std::size_t i) const;
  // (1/2) w^T I w for an angular velocity w of grain i (its own by default).
  [[nodiscard]] double rotational_energy(std::size_t i, const Vec3& w) const;
  [[nodiscard]] double rotational_energy(std::size_t i) const { return rotational_energy(i, omega[i]); }

  [[nodiscard]] double max_radius() const;
  [[nodiscard]] double min_radius() const;
};

}  // namespace upgrain::dem
