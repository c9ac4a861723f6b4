#pragma once
// How the engine sums the forces on a particle and every global quantity (docs/architecture.md,
// "Two summations").
//  - deterministic: each particle adds its contributions in the order of its partners' global
//    ids (walls first), and global sums run in global-id order or by fixed-point limbs; the
//    particle states and the output are bitwise independent of the rank count.
//  - fast: a scatter over a half list in local order, forces on ghosts returned to their
//    owners (LAMMPS's `newton on`), and global sums in local order reduced over the ranks; the
//    results then depend on the decomposition, within round-off.
#include <string>

namespace upgrain::dem {

enum class Summation { deterministic, fast };

inline std::string to_string(Summation s) { return s == Summation::deterministic ? "deterministic" : "fast"; }

}  // namespace upgrain::dem
