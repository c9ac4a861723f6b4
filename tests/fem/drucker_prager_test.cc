// The Drucker–Prager kernel (fem/plasticity/drucker_prager.h) against independent answers:
// the Mohr–Coulomb criterion at the states each cone matching is built for, the defining
// equations of the backward Euler return (yield condition and flow rule), and central
// finite differences of the return map for the consistent tangent. No MPI, no deal.II.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/LU>

#include "fem/plasticity/drucker_prager.h"

namespace upgrain::fem {
namespace {

constexpr double degree = std::numbers::pi / 180.0;

Vec6 diagonal(double a, double b, double c) { return (Vec6() << a, b, c, 0, 0, 0).finished(); }

// Mohr–Coulomb with principal stresses s1 >= s3 (tension positive): the radius t and centre
// m of the largest Mohr circle satisfy t + m sin(phi) = c cos(phi) on the yield surface.
double mohr_coulomb(double s1, double s3, double phi, double c) {
  return 0.5 * (s1 - s3) + 0.5 * (s1 + s3) * std::sin(phi) - c * std::cos(phi);
}

// sqrt(J2) of a diagonal stress.
double sqrt_j2_of(double a, double b, double c) {
  return std::sqrt(((a - b) * (a - b) + (b - c) * (b - c) + (c - a) * (c - a)) / 6.0);
}

struct Material {
  double phi_deg, psi_deg, cohesion;
};
const Material materials[] = {{30.0, 30.0, 0.0}, {30.0, 0.0, 0.0}, {35.0, 10.0, 2e3}, {20.0, 20.0, 5e3}};

// Outer cone: through the triaxial-compression corners, sigma = diag(a, a, b) with b < a (the
// axial stress the most compressive). Inner cone: through the triaxial-extension corners,
// diag(a, b, b) with a > b.
TEST(DruckerPragerMatching, OuterAndInnerConesPassThroughTheirMohrCoulombCorners) {
  for (const Material& m : materials) {
    const double phi = m.phi_deg * degree, c = m.cohesion;
    const double scale = 1e4;
    // Compressive states, and one in tension where the cohesion allows it.
    for (const double a : {-0.2 * scale, -scale, c > 0.0 ? 0.3 * c : -0.5 * scale}) {
      // On Mohr–Coulomb with s1 = a: (a - b)/2 + (a + b)/2 sin(phi) = c cos(phi) for b.
      const double b = (a * (1.0 + std::sin(phi)) - 2.0 * c * std::cos(phi)) / (1.0 - std::sin(phi));
      ASSERT_LT(b, a);
      ASSERT_NEAR(mohr_coulomb(a, b, phi, c), 0.0, 1e-9 * scale);
      const DruckerPrager outer = match_mohr_coulomb(phi, m.psi_deg * degree, c, ConeMatching::outer);
      EXPECT_NEAR(outer.yield_function(diagonal(a, a, b)), 0.0, 1e-12 * scale) << m.phi_deg;
      const DruckerPrager inner = match_mohr_coulomb(phi, m.psi_deg * degree, c, ConeMatching::inner);
      EXPECT_NEAR(inner.yield_function(diagonal(a, b, b)), 0.0, 1e-12 * scale) << m.phi_deg;
      // The other corner type lies inside the outer cone and outside the inner one.
      EXPECT_LT(outer.yield_function(diagonal(a, b, b)), 0.0);
      EXPECT_GT(inner.yield_function(diagonal(a, a, b)), 0.0);
    }
  }
}

// Plane strain in the 1-3 plane: under plastic flow with d eps^p_22 = 0, the cone must give
// Mohr–Coulomb's strength and dilatancy. The state is built from Mohr–Coulomb alone: in-plane
// principal stresses on its criterion, and the out-of-plane stress found by bisection so that
// the plastic potential's flow has no 22 component.
TEST(DruckerPragerMatching, PlaneStrainConeGivesMohrCoulombStrengthAndDilatancy) {
  for (const Material& m : materials) {
    const double phi = m.phi_deg * degree, psi = m.psi_deg * degree, c = m.cohesion;
    const DruckerPrager dp = match_mohr_coulomb(phi, psi, c, ConeMatching::plane_strain);
    for (const double s1 : {-1e3, -5e4}) {
      const double s3 = (s1 * (1.0 + std::sin(phi)) - 2.0 * c * std::cos(phi)) / (1.0 - std::sin(phi));
      ASSERT_LT(s3, s1);
      // dPsi/dsigma_22 = s_22 / (2 sqrt J2) + eta_bar / 3 changes sign between s2 = s3 and
      // s2 = s1; bisect for its zero.
      const auto flow_22 = [&](double s2) {
        const double p = (s1 + s2 + s3) / 3.0;
        return (s2 - p) / (2.0 * sqrt_j2_of(s1, s2, s3)) + dp.eta_bar / 3.0;
      };
      double lo = s3, hi = s1;
      ASSERT_LT(flow_22(lo) * flow_22(hi), 0.0);
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (flow_22(mid) * flow_22(lo) > 0.0 ? lo : hi) = mid;
      }
      const double s2 = 0.5 * (lo + hi);
      EXPECT_NEAR(dp.yield_function(diagonal(s1, s2, s3)), 0.0, 1e-10 * std::abs(s3)) << m.phi_deg;
      // Dilatancy: d eps_v / (d eps_1 - d eps_3) of Psi's flow equals sin(psi).
      const double q = sqrt_j2_of(s1, s2, s3), p = (s1 + s2 + s3) / 3.0;
      const double n1 = (s1 - p) / (2.0 * q) + dp.eta_bar / 3.0, n3 = (s3 - p) / (2.0 * q) + dp.eta_bar / 3.0;
      EXPECT_NEAR(dp.eta_bar / (n1 - n3), std::sin(psi), 1e-10) << m.phi_deg << " " << m.psi_deg;
    }
    // Associated flow: de Souza Neto et al.'s closed form.
    if (m.phi_deg == m.psi_deg) {
      const double t = std::tan(phi);
      EXPECT_NEAR(dp.eta, 3.0 * t / std::sqrt(9.0 + 12.0 * t * t), 1e-14);
      EXPECT_NEAR(dp.xi, 3.0 / std::sqrt(9.0 + 12.0 * t * t), 1e-14);
    }
  }
}

// A point with history: stress sigma_n at strain eps_n; return_map of the elastic predictor.
struct Point {
  DruckerPrager cone;
  Elasticity elasticity;
  Vec6 stress_n, strain_n;
  [[nodiscard]] ReturnMapping at(const Vec6& strain) const {
    return return_map(cone, elasticity, stress_n + elasticity.stiffness() * (strain - strain_n));
  }
};

Point make_point(const Material& m, ConeMatching matching) {
  Point p;
  p.cone = match_mohr_coulomb(m.phi_deg * degree, m.psi_deg * degree, m.cohesion, matching);
  p.elasticity = Elasticity::from_youngs(5e7, 0.3);
  // An oedometric stress state at rest, inside every cone of the materials above.
  p.stress_n = diagonal(-6e3, -6e3, -1e4);
  p.strain_n = Vec6::Zero();
  return p;
}

// Strain increments that take the point into each region (asserted where used).
struct Increment {
  Vec6 strain;
  ReturnRegion region;
};
const Increment increments[] = {
    {(Vec6() << 0, 0, -1e-6, 0, 0, 0).finished(), ReturnRegion::elastic},                 // small
    {(Vec6() << 2e-4, 1e-4, -6e-4, 3e-5, -5e-5, 2e-5).finished(), ReturnRegion::cone},    // deviatoric
    {(Vec6() << 1.5e-3, 1.5e-3, 1.5e-3, 1e-5, 0, -1e-5).finished(), ReturnRegion::apex},  // tension
};

TEST(DruckerPragerReturn, ElasticTrialStatesAreUntouched) {
  for (const Material& m : materials) {
    const Point p = make_point(m, ConeMatching::outer);
    const Vec6 strain = increments[0].strain;
    const Vec6 trial = p.stress_n + p.elasticity.stiffness() * strain;
    ASSERT_LT(p.cone.yield_function(trial), 0.0);
    const ReturnMapping r = p.at(strain);
    EXPECT_EQ(r.region, ReturnRegion::elastic);
    EXPECT_EQ(r.stress, trial);
    EXPECT_EQ(r.tangent, p.elasticity.stiffness());
  }
}

// The backward Euler return is defined by two conditions, checked here as such:
// Phi(sigma) = 0 (consistency) and sigma_trial - sigma = Delta gamma C : dPsi/dsigma(sigma)
// (the flow rule at the new stress). At the apex, where dPsi/dsigma is a cone of normals,
// the plastic strain C^-1 (sigma_trial - sigma) must lie in it:
// sqrt2 |dev d eps^p| <= tr(d eps^p) / eta_bar.
TEST(DruckerPragerReturn, ReturnedStressSatisfiesYieldConditionAndFlowRule) {
  for (const Material& m : materials)
    for (const ConeMatching matching :
         {ConeMatching::outer, ConeMatching::inner, ConeMatching::plane_strain}) {
      const Point p = make_point(m, matching);
      const Mat6 C = p.elasticity.stiffness();
      for (const Increment& increment : {increments[1], increments[2]}) {
        const Vec6 trial = p.stress_n + C * increment.strain;
        const ReturnMapping r = p.at(increment.strain);
        const double scale = trial.norm();
        SCOPED_TRACE(::testing::Message()
                     << "phi " << m.phi_deg << " psi " << m.psi_deg << " c " << m.cohesion);
        ASSERT_EQ(r.region, increment.region);
        EXPECT_NEAR(p.cone.yield_function(r.stress), 0.0, 1e-13 * scale);
        const Vec6 plastic_strain = C.inverse() * (trial - r.stress);
        if (r.region == ReturnRegion::cone) {
          const Vec6 s = mandel::deviator(r.stress);
          const Vec6 flow =
              s / (2.0 * std::sqrt(0.5 * s.squaredNorm())) + p.cone.eta_bar / 3.0 * mandel::identity();
          EXPECT_LT((trial - r.stress - r.plastic_multiplier * C * flow).norm(), 1e-12 * scale);
        } else {
          const double apex = p.cone.apex_pressure();
          EXPECT_NEAR(r.stress[0], apex, 1e-12 * std::max(1.0, apex));
          EXPECT_LT(mandel::deviator(r.stress).norm(), 1e-14 * std::max(1.0, apex));
          const double volumetric = mandel::trace(plastic_strain);
          EXPECT_GT(volumetric, 0.0);
          if (p.cone.eta_bar > 0.0) {
            EXPECT_LE(mandel::sqrt2 * mandel::deviator(plastic_strain).norm(), volumetric / p.cone.eta_bar);
          }
        }
      }
    }
}

// d sigma / d eps of the return map against central differences, column by column, in
// every region: elastic, smooth cone (associated and not), apex (zero).
TEST(DruckerPragerReturn, ConsistentTangentMatchesFiniteDifferences) {
  double largest_error = 0.0;
  for (const Material& m : materials)
    for (const ConeMatching matching : {ConeMatching::outer, ConeMatching::plane_strain})
      for (const Increment& increment : increments) {
        const Point p = make_point(m, matching);
        const Vec6& strain = increment.strain;
        const ReturnMapping r = p.at(strain);
        ASSERT_EQ(r.region, increment.region);
        const double h = 1e-9;  // strains are ~1e-4; stress ~1e4 Pa: central error ~h^2 E
        Mat6 fd;
        for (int k = 0; k < 6; ++k) {
          Vec6 e = Vec6::Zero();
          e[k] = h;
          const ReturnMapping plus = p.at(strain + e), minus = p.at(strain - e);
          ASSERT_EQ(plus.region, r.region);
          ASSERT_EQ(minus.region, r.region);
          fd.col(k) = (plus.stress - minus.stress) / (2.0 * h);
        }
        SCOPED_TRACE(::testing::Message() << "phi " << m.phi_deg << " psi " << m.psi_deg << " region "
                                          << static_cast<int>(r.region));
        // Round-off of the differences is ~1e-16 |sigma| / h, about 1e-11 |C|; measured: at most
        // 6e-11 |C| over all cases.
        const double error = (fd - r.tangent).norm() / p.elasticity.stiffness().norm();
        largest_error = std::max(largest_error, error);
        EXPECT_LT(error, 1e-8);
        const bool associated = m.phi_deg == m.psi_deg;
        if (r.region == ReturnRegion::cone) {
          EXPECT_EQ(associated, (r.tangent - r.tangent.transpose()).norm() < 1e-10 * r.tangent.norm());
        }
      }
  std::printf("  largest |tangent - finite differences| / |C| = %.2e\n", largest_error);
}

}  // namespace
}  // namespace upgrain::fem
