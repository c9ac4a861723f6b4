#include "upscale/cg/coarse_grained_fields.h"

#include <algorithm>

#include "dem/core/error.h"
#include "upscale/cg/cell_bins.h"

namespace upgrain::upscale::cg {

void CoarseGrainedFields::resize(std::size_t n) {
  for (auto* v : {&density, &volume_fraction}) v->assign(n, 0.0);
  for (auto* v : {&momentum, &velocity, &wall_force_density, &displacement, &momentum_rate,
                  &net_force_density, &residual})
    v->assign(n, Vec3::Zero());
  for (auto* v : {&kinetic_stress, &contact_stress, &stress, &displacement_gradient})
    v->assign(n, Mat3::Zero());
}

namespace {

// A grain near the point, kept between the two passes over the grains.
struct Near {
  int grain;
  double phi;
  Vec3 grad;  // grad phi at the point
};

}  // namespace

template <Kernel K>
CoarseGrainedFields coarse_grain(const GrainState& s, std::span<const Vec3> points, const K& kernel) {
  const double c = kernel.cutoff(), c2 = c * c;
  // Branches are binned by their midpoints: a branch reaches at most c + half its length.
  std::vector<Vec3> midpoints(s.branches());
  for (std::size_t k = 0; k < s.branches(); ++k) midpoints[k] = 0.5 * (s.branch_from[k] + s.branch_to[k]);
  const double reach = c + 0.5 * s.longest_branch, reach2 = reach * reach;
  const CellBins grains(s.x, c), branches(midpoints, reach), walls(s.wall_point, c);
  const bool displaced = s.has_displacement();

  CoarseGrainedFields f;
  f.resize(points.size());
  std::vector<Near> near;
  near.reserve(256);
  for (std::size_t q = 0; q < points.size(); ++q) {
    const Vec3& r = points[q];
    // Pass 1 over the grains: the sums linear in the grains.
    near.clear();
    double rho = 0.0, nu = 0.0;
    Vec3 p = Vec3::Zero(), ma = Vec3::Zero(), mvv_grad = Vec3::Zero(), grad_rho = Vec3::Zero(),
         mu = Vec3::Zero();
    Mat3 grad_p = Mat3::Zero(), grad_mu = Mat3::Zero();
    grains.for_each_near(r, [&](int i) {
      const Vec3 d = r - s.x[i];
      const double d2 = d.squaredNorm();
      if (d2 >= c2) return;
      const KernelValue k = kernel.value_and_gradient_factor(d2);
      if (k.phi == 0.0 && k.gradient_factor == 0.0) return;
      const Vec3 grad = k.gradient_factor * d;
      const double m = s.mass[i];
      const Vec3& v = s.v[i];
      rho += m * k.phi;
      nu += s.volume[i] * k.phi;
      p += m * k.phi * v;
      ma += m * k.phi * s.acceleration[i];
      grad_rho += m * grad;
      grad_p += (m * v) * grad.transpose();
      mvv_grad += (m * v.dot(grad)) * v;
      if (displaced) {
        mu += m * k.phi * s.displacement[i];
        grad_mu += (m * s.displacement[i]) * grad.transpose();
      }
      near.push_back({i, k.phi, grad});
    });
    const Vec3 V = rho > 0.0 ? Vec3(p / rho) : Vec3::Zero();
    // Pass 2: the kinetic stress, from the fluctuations about the velocity at the point.
    Mat3 sigma_k = Mat3::Zero();
    Vec3 div_sigma_k = Vec3::Zero();
    for (const Near& n : near) {
      const Vec3 dv = s.v[n.grain] - V;
      const double m = s.mass[n.grain];
      sigma_k -= (m * n.phi * dv) * dv.transpose();
      div_sigma_k -= (m * dv.dot(n.grad)) * dv;
    }
    // Contact stress and its divergence along each branch. A branch whose midpoint is
    // farther than c + half the longest branch cannot reach the point. The contact point's
    // term -f phi(r - c) of a pair's two branches cancels (their forces are opposite), so only
    // a branch that ends at a grain takes its far end's term, and a wall contact's is -b.
    Mat3 sigma_c = Mat3::Zero();
    Vec3 div_sigma_c = Vec3::Zero();
    branches.for_each_near(r, [&](int k) {
      if ((r - midpoints[k]).squaredNorm() >= reach2) return;
      const Vec3 d = r - s.branch_from[k];
      const Vec3 l = s.branch_to[k] - s.branch_from[k];
      const double psi = kernel.line_integral(d, l);
      const double phi_from = kernel.value(d.squaredNorm());
      const double phi_to = s.ends_at_grain[k] ? kernel.value((d - l).squaredNorm()) : 0.0;
      if (psi == 0.0 && phi_from == 0.0 && phi_to == 0.0) return;
      const Vec3& force = s.branch_force[k];
      sigma_c += (psi * force) * l.transpose();
      div_sigma_c += (phi_from - phi_to) * force;
    });
    Vec3 b = Vec3::Zero();
    walls.for_each_near(r, [&](int k) {
      const double phi = kernel.value((r - s.wall_point[k]).squaredNorm());
      if (phi != 0.0) b += phi * s.wall_force[k];
    });
    div_sigma_c -= b;

    f.density[q] = rho;
    f.volume_fraction[q] = nu;
    f.momentum[q] = p;
    f.velocity[q] = V;
    f.kinetic_stress[q] = sigma_k;
    f.contact_stress[q] = sigma_c;
    f.stress[q] = sigma_k + sigma_c;
    f.wall_force_density[q] = b;
    if (displaced && rho > 0.0) {
      const Vec3 U = mu / rho;
      f.displacement[q] = U;
      f.displacement_gradient[q] = (grad_mu - U * grad_rho.transpose()) / rho;
    }
    // div(rho V V) = (grad p) V + V div p - V (V . grad rho), with grad p_ij = dp_i / dx_j.
    const Vec3 div_flux = grad_p * V + grad_p.trace() * V - V.dot(grad_rho) * V;
    f.momentum_rate[q] = ma - mvv_grad;
    f.net_force_density[q] = div_sigma_k + div_sigma_c + rho * s.gravity + b - div_flux;
    f.residual[q] = f.momentum_rate[q] - f.net_force_density[q];
  }
  return f;
}

template CoarseGrainedFields coarse_grain(const GrainState&, std::span<const Vec3>, const GaussianKernel&);
template CoarseGrainedFields coarse_grain(const GrainState&, std::span<const Vec3>, const LucyKernel&);

CoarseGrainedFields coarse_grain(const GrainState& s, std::span<const Vec3> points,
                                 const KernelChoice& kernel) {
  return with_kernel(kernel, [&](const auto& k) { return coarse_grain(s, points, k); });
}

std::vector<Vec3> residual_by_differences(const CoarseGrainedFields& earlier,
                                          const CoarseGrainedFields& later, double interval) {
  if (earlier.size() != later.size())
    throw Error("coarse graining: the two evaluations of the balance have different points");
  if (!(interval > 0.0)) throw Error("coarse graining: the sampling interval must be positive");
  std::vector<Vec3> r(earlier.size());
  for (std::size_t q = 0; q < r.size(); ++q)
    r[q] = (later.momentum[q] - earlier.momentum[q]) / interval -
           0.5 * (earlier.net_force_density[q] + later.net_force_density[q]);
  return r;
}

}  // namespace upgrain::upscale::cg
