#include "dem/stress/contact_tangent.h"

namespace upgrain::dem {

FullTangent contact_stiffness_tangent(std::span<const ContactStiffness> contacts, double volume) {
  FullTangent d = FullTangent::Zero();
  for (const ContactStiffness& c : contacts) {
    const Mat3 nn = c.normal * c.normal.transpose();
    const Mat3 k = c.normal_stiffness * nn + c.tangential_stiffness * (Mat3::Identity() - nn);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int kk = 0; kk < 3; ++kk)
          for (int l = 0; l < 3; ++l) d(3 * i + j, 3 * kk + l) += k(i, kk) * c.branch[j] * c.branch[l];
  }
  return d / volume;
}

}  // namespace upgrain::dem
