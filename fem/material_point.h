#pragma once
// The state at one quadrature point of the frictional column (fem/frictional_column.cc), as
// in deal.II's step-18: plain structs, and the material law that turns a strain into the
// stress and tangent Newton's method needs. Plain C++ and Eigen (docs/fem.md).
#include <Eigen/Core>

#include "fem/frictional_column.h"
#include "fem/plasticity/drucker_prager.h"

namespace upgrain::fem {

// The stress and strain of the last converged step, and what the current Newton iterate
// makes of them. An incremental (stress-based) state serves both the elastic and the
// Drucker–Prager material and lets a layer placed during staged construction start
// stress-free on a deformed column.
struct MaterialPoint {
  Vec6 stress = Vec6::Zero();  // sigma_n
  Vec6 strain = Vec6::Zero();  // eps_n (at placement for a layer added later)
  ReturnRegion region = ReturnRegion::elastic;
  Vec6 new_stress = Vec6::Zero();
  Vec6 new_strain = Vec6::Zero();
  ReturnRegion new_region = ReturnRegion::elastic;

  void commit() {
    stress = new_stress;
    strain = new_strain;
    region = new_region;
  }
  void place(const Vec6& current_strain) {
    stress.setZero();
    strain = current_strain;
    region = ReturnRegion::elastic;
  }
};

// A quadrature point on a wall or the floor: the material there (its normal stress is the
// wall pressure) and the friction state, the traction t_n and displacement u_n of the last
// converged step (contact/coulomb_friction.h).
struct WallPoint {
  MaterialPoint material;
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  bool slipping = false;
  double pressure = 0.0;
  Eigen::Vector3d new_traction = Eigen::Vector3d::Zero();
  Eigen::Vector3d new_displacement = Eigen::Vector3d::Zero();
  bool new_slipping = false;
  double new_pressure = 0.0;

  void commit() {
    material.commit();
    traction = new_traction;
    displacement = new_displacement;
    slipping = new_slipping;
    pressure = new_pressure;
  }
  void place(const Vec6& current_strain, const Eigen::Vector3d& current_displacement) {
    material.place(current_strain);
    traction.setZero();
    displacement = current_displacement;
    slipping = false;
    pressure = 0.0;
  }
};

struct MaterialResponse {
  Vec6 stress;
  Mat6 tangent;  // what Newton's matrix uses (see MaterialLaw::respond)
  ReturnRegion region;
};

// The column's material: elastic, or Drucker–Prager by return mapping.
struct MaterialLaw {
  ColumnMaterial kind = ColumnMaterial::elastic;
  Elasticity elasticity;
  DruckerPrager cone;
  Mat6 stiffness = Mat6::Zero();  // C

  MaterialLaw(ColumnMaterial material, const Elasticity& e, const DruckerPrager& c)
      : kind(material), elasticity(e), cone(c), stiffness(e.stiffness()) {}

  // The elastic predictor sigma_n + C (eps - eps_n), returned to the cone if it lies outside.
  //
  // At the apex of a perfectly plastic cone the consistent tangent is zero (the stress is the
  // apex whatever the strain): a cell whose points all sit there has no stiffness, and the
  // Newton matrix is singular. Cohesionless material reaches the apex in tension, which
  // Newton iterates visit near the free top on their way to a compressed solution. The matrix
  // then takes the elastic stiffness at such points; the stress stays the returned one, so
  // the solution is unchanged and Newton converges quadratically once no point is at the apex
  // (docs/fem.md, "Return mapping and consistent tangent").
  [[nodiscard]] MaterialResponse respond(const MaterialPoint& point, const Vec6& strain) const {
    const Vec6 trial = point.stress + stiffness * (strain - point.strain);
    if (kind == ColumnMaterial::elastic) return {trial, stiffness, ReturnRegion::elastic};
    const ReturnMapping r = return_map(cone, elasticity, trial);
    return {r.stress, r.region == ReturnRegion::apex ? stiffness : r.tangent, r.region};
  }
};

}  // namespace upgrain::fem
