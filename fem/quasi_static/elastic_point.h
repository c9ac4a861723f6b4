#pragma once
// Closed-form stand-ins for the DEM cell at a quadrature point (docs/femxdem.md, "Elastic
// stand-ins"): with them the quasi-static solver is checked against deal.II's linear
// elasticity and its Newton iteration against the quadratic convergence an exact tangent gives
// (Wriggers 2008, Nonlinear Finite Element Methods, sec. 5.1). Plain values, no deal.II.
#include <memory>
#include <optional>

#include "fem/quasi_static/point_state.h"

namespace upgrain::fem {

// The small-strain tensor eps = (H + H^T) / 2 of a displacement gradient, as a Mandel vector.
inline Vec6 small_strain(const Mat3x3& h) { return mandel::from_matrix(0.5 * (h + h.transpose())); }

// Isotropic linear elasticity about an initial stress: sigma = sigma_0 + C : eps, with a density
// of its own when given (else the problem's). Its history is the strain alone, so commit() and
// save() have nothing to keep.
class LinearElasticPoint final : public PointState {
 public:
  explicit LinearElasticPoint(const Elasticity& e, const Vec6& initial_stress = Vec6::Zero(),
                              std::optional<double> density = std::nullopt)
      : elasticity_(e), initial_stress_(initial_stress), density_(density) {}

  PointResponse respond(const Mat3x3& h) override {
    PointResponse r;
    r.stress = initial_stress_ + elasticity_.stress(small_strain(h));
    r.tangent = elasticity_.stiffness();
    return r;
  }
  void commit() override {}
  [[nodiscard]] std::unique_ptr<PointState> clone() const override {
    return std::make_unique<LinearElasticPoint>(*this);
  }
  [[nodiscard]] std::optional<double> density() const override { return density_; }
  [[nodiscard]] std::vector<char> save() const override { return {}; }
  void load(const std::vector<char>&) override {}

 private:
  Elasticity elasticity_;
  Vec6 initial_stress_;
  std::optional<double> density_;
};

// A nonlinear elastic law whose volume stiffens under compression as a granular assembly's
// does, with its exact tangent: sigma = K (eps_v + beta eps_v^3) 1 + 2 G dev(eps), the tangent
// K (1 + 3 beta eps_v^2) 1 (x) 1 + 2 G P_dev (eps_v = tr eps). The free energy
// K (eps_v^2 / 2 + beta eps_v^4 / 4) + G dev(eps) : dev(eps) makes it hyperelastic, so the
// tangent is symmetric.
class StiffeningElasticPoint final : public PointState {
 public:
  StiffeningElasticPoint(const Elasticity& e, double beta) : elasticity_(e), beta_(beta) {}

  PointResponse respond(const Mat3x3& h) override {
    const Vec6 eps = small_strain(h);
    const double ev = mandel::trace(eps);
    const double k = elasticity_.bulk_modulus, g = elasticity_.shear_modulus;
    PointResponse r;
    r.stress = k * (ev + beta_ * ev * ev * ev) * mandel::identity() + 2.0 * g * mandel::deviator(eps);
    r.tangent = k * (1.0 + 3.0 * beta_ * ev * ev) * mandel::identity() * mandel::identity().transpose() +
                2.0 * g * mandel::deviatoric_projector();
    return r;
  }
  void commit() override {}
  [[nodiscard]] std::unique_ptr<PointState> clone() const override {
    return std::make_unique<StiffeningElasticPoint>(*this);
  }
  [[nodiscard]] std::vector<char> save() const override { return {}; }
  void load(const std::vector<char>&) override {}

 private:
  Elasticity elasticity_;
  double beta_;
};

}  // namespace upgrain::fem
