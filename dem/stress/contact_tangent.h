#pragma once
// The contact-stiffness tangent of a granular assembly (Kruyt and Rothenburg 1998, Int. J. Eng.
// Sci. 36, 1127; Guo and Zhao 2014, IJNME 99, 789, the DEM tangent of their FEM x DEM): every
// contact follows the affine field, the relative displacement of the pair's second grain
// Delta u = Delta H d over its branch d, and its force changes by the contact's stiffness
// K = k_n n (x) n + k_t (1 - n (x) n). Love-Weber's sigma = (1/V) sum f (x) d then changes by
//
//   D_ijkl = (1/V) sum_c K_ik d_j d_l,   Delta sigma_ij = D_ijkl Delta H_kl,
//
// an upper bound of the relaxed assembly's stiffness (the grains' own rearrangement can only
// soften it; Kruyt and Rothenburg 2002, Int. J. Solids Struct. 39, 311). Neither the change of
// the contact network nor the rotation of the present forces (the geometric terms) enters. Plain data and a
// plain function: the engine lists the contacts (dem/engine/contact_stiffnesses.h), tests write them by hand.
#include <Eigen/Core>
#include <span>

#include "dem/core/types.h"

namespace upgrain::dem {

// One touching pair: d = x_second - x_first (minimum image), n = d / |d|, the law's present
// normal and tangential stiffnesses (N/m).
struct ContactStiffness {
  Vec3 branch = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double normal_stiffness = 0.0;
  double tangential_stiffness = 0.0;
};

// D_ijkl as a 9 x 9 matrix, D(3 i + j, 3 k + l): the map of the displacement gradient Delta H to
// Delta sigma, both as 9-vectors of their rows. Major symmetric; the minor symmetries are the
// caller's to impose (a symmetric strain and stress).
using FullTangent = Eigen::Matrix<double, 9, 9>;

[[nodiscard]] FullTangent contact_stiffness_tangent(std::span<const ContactStiffness> contacts,
                                                    double volume);

}  // namespace upgrain::dem
