#pragma once
// What coarse-grained fields are made of, as plain arrays (docs/coarse-graining.md): the
// grains (in id order) with their masses, volumes, velocities, accelerations and, against a
// reference state, displacements; the branches of the contact stress; the wall contacts.
// Built from a gathered DEM state (state_from) or by hand in tests.
#include <cstdint>
#include <vector>

#include "dem/core/box.h"
#include "dem/core/particle_store.h"
#include "dem/parallel/records.h"
#include "upscale/cg/kernel.h"

namespace upgrain::upscale::cg {

struct GrainState {
  double time = 0.0;
  Vec3 gravity = Vec3::Zero();

  // Grains, in id order.
  std::vector<GlobalId> id;
  std::vector<Vec3> x, v;
  // Of the force evaluation the state belongs to: F / m + g (m/s^2).
  std::vector<Vec3> acceleration;
  // x - X against the reference state, when with_displacement.
  std::vector<Vec3> displacement;
  bool with_displacement = false;
  std::vector<double> mass, volume;

  // Branches of the contact stress, with the force on the grain they start from: a contact
  // between grains a and b at c gives (x_a -> c, f) and (x_b -> c, -f), a wall contact
  // (x_a -> c, f); in the order of the contacts' keys (lower id first). The path through the
  // contact point makes the stress Bagi's per-grain sum when smoothed by a box
  // (docs/stress.md). When c lies on the segment between the centres (spheres), the two
  // halves are one branch x_a -> x_b with f, which ends at a grain (ends_at_grain): the same
  // stress for half the line integrals.
  std::vector<Vec3> branch_from, branch_to, branch_force;
  std::vector<std::uint8_t> ends_at_grain;

  // Wall contacts: the point on the wall and the force of the wall on the grain.
  std::vector<Vec3> wall_point, wall_force;

  // The longest branch of the whole state (m): it sets the cells the branches are binned in,
  // which must not depend on the part of the state a rank holds (part_near keeps it).
  double longest_branch = 0.0;

  // The periodic cell the grains are wrapped in while its images are not in the state yet:
  // with_periodic_images() (periodic_images.h) adds them and leaves a bounded cell here, so
  // the sums of coarse_grain() never see a cell. Bounded (the default): nothing to add.
  dem::PeriodicCell cell;

  [[nodiscard]] std::size_t grains() const { return id.size(); }
  [[nodiscard]] std::size_t branches() const { return branch_from.size(); }
  [[nodiscard]] std::size_t wall_contacts() const { return wall_point.size(); }
  [[nodiscard]] bool has_displacement() const { return with_displacement; }
};

// Positions of a reference state by global id (sorted by id). In a periodic cell also the
// grains' image counters then (empty in a bounded box, and in a checkpoint written before
// they were kept), so that a displacement follows a grain across the faces.
struct ReferencePositions {
  double time = 0.0;
  std::vector<GlobalId> id;
  std::vector<Vec3> x;
  std::vector<dem::ImageCount> image;
};
ReferencePositions reference_from(const dem::ParticleStore& sorted_by_id, double time,
                                  const dem::PeriodicCell* cell = nullptr);

// The state of a store sorted by id (Simulation::whole_state) and its contacts
// (Simulation::gather_contacts_by_id: a < b, force on a; walls as b = -1 - w). With a
// reference, every grain must be in it (else upgrain::Error naming the grain).
// In a periodic `cell` (docs/coarse-graining.md, "Periodic cells"): each contact's branches go
// from x_a to its contact point and on to x_b by minimum image, so that a contact across a face
// is a short branch sticking out of the cell, not one across it; a displacement is
// x + h (n - n0) - X with the reference's counters n0 (x - X by minimum image without them);
// the state keeps the cell for with_periodic_images(). A bounded cell (or none): the bits as
// without one.
GrainState state_from(const dem::ParticleStore& sorted_by_id, const std::vector<dem::ContactRecord>& contacts,
                      const Vec3& gravity, double time, const ReferencePositions* reference = nullptr,
                      const dem::PeriodicCell* cell = nullptr);

// The part of `s` that the fields inside `box` need with a kernel of cut-off `range`: the
// grains within range of the box, the branches whose segment comes within range, the wall
// contacts within range; in their order in `s`, so that every point's sums are the same
// bits as over the whole state (docs/coarse-graining.md, "In parallel").
GrainState part_near(const GrainState& s, const dem::Box& box, double range);

// Appends grain i (branch k, wall contact k) of `from` to `to` as it is, or moved by `shift`
// (the periodic images: periodic_images.h); what part_near() and with_periodic_images() copy.
void append_grain(GrainState& to, const GrainState& from, std::size_t i, const Vec3* shift = nullptr);
void append_branch(GrainState& to, const GrainState& from, std::size_t k, const Vec3* shift = nullptr);
void append_wall_contact(GrainState& to, const GrainState& from, std::size_t k, const Vec3* shift = nullptr);

// The tests part_near() and with_periodic_images() take: a point within `range` of `box`
// (each axis), a segment whose bounding box comes within `range` of it.
bool point_near(const Vec3& x, const dem::Box& box, double range);
bool segment_near(const Vec3& a, const Vec3& c, const dem::Box& box, double range);

}  // namespace upgrain::upscale::cg
