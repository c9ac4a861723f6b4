#pragma once
// The rotational halves of Simulation::step over the grains [0, n) of a store: spheres
// w += (h/2) T / I; ellipsoids the symplectic splitting of rigid_rotation.h (first half: half kick and free
// rotation, also turning the orientation) and the body-frame half kick (second half). The angular momentum is
// rebuilt from w, L_b = J Q^T w (exact up to round-off), so that w stays the one angular state
// that contacts, relaxation and stress read (docs/ellipsoids.md, "Rotation").
#include <cstddef>

#include "dem/core/particle_store.h"

namespace upgrain::dem {

void rotation_first_half(ParticleStore& p, std::size_t n, double half, double dt);
void rotation_second_half(ParticleStore& p, std::size_t n, double half);

}  // namespace upgrain::dem
