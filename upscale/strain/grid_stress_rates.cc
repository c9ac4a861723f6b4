#include "upscale/strain/grid_stress_rates.h"

#include <sstream>

#include "dem/core/error.h"
#include "upscale/strain/objective_rates.h"
#include "upscale/strain/strain_measures.h"

namespace upgrain::upscale {

void CellStressRates::resize(int cells) {
  const auto n = static_cast<std::size_t>(cells);
  for (auto* m : {&stress_rate, &jaumann, &green_naghdi, &truesdell, &oldroyd}) m->assign(n, Mat3::Zero());
  reason.assign(n, StrainReason::no_history);
  green_naghdi_reason.assign(n, StrainReason::no_history);
}

GridStressRates StressRateHistory::push(std::span<const Mat3> stress, const GridStrain& strain) {
  const int cells = strain.grid.num_cells();
  if (static_cast<int>(stress.size()) != cells) {
    std::ostringstream m;
    m << "stress rates: the stress has " << stress.size() << " cells, the strain grid " << cells;
    throw Error(m.str());
  }
  if (!outputs_.empty() &&
      (static_cast<int>(outputs_.back().stress.size()) != cells || !(strain.time > outputs_.back().time))) {
    std::ostringstream m;
    m << "stress rates: output at t = " << strain.time << " s (" << cells
      << " cells) does not follow the previous one at t = " << outputs_.back().time << " s ("
      << outputs_.back().stress.size() << " cells)";
    throw Error(m.str());
  }
  Output now;
  now.time = strain.time;
  now.stress.assign(stress.begin(), stress.end());
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    if (!strain.computed[d]) continue;
    now.rotation[d] = strain.fields[d].rotation;
    now.f_reason[d] = strain.fields[d].f_reason;
  }
  outputs_.push_back(std::move(now));
  if (outputs_.size() > 3) outputs_.pop_front();

  GridStressRates out;
  out.formula = formula_;
  out.outputs_used = static_cast<int>(outputs_.size());
  out.computed = strain.computed;
  out.stress = outputs_.back().stress;
  const std::size_t n = outputs_.size();
  std::vector<double> times;
  for (const Output& o : outputs_) times.push_back(o.time);
  std::vector<Mat3> sigma(n), rotation(n);
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    if (!strain.computed[d]) continue;
    CellStressRates& r = out.fields[d];
    r.resize(cells);
    if (n < 2) continue;  // the first output: no_history
    const CellStrainFields& f = strain.fields[d];
    for (int c = 0; c < cells; ++c) {
      bool finite = true;
      for (std::size_t k = 0; k < n; ++k) {
        sigma[k] = outputs_[k].stress[static_cast<std::size_t>(c)];
        finite = finite && sigma[k].allFinite();
      }
      if (f.l_reason[c] != StrainReason::valid || !finite) {
        r.reason[c] = r.green_naghdi_reason[c] = finite ? f.l_reason[c] : StrainReason::non_finite;
        continue;
      }
      // sigma_dot at the newest output: the last entry of eq. (10) over these outputs.
      const Mat3 sigma_dot = time_derivative(times, sigma).back();
      const Mat3& s = sigma.back();
      const Mat3& l = f.velocity_gradient[c];
      r.reason[c] = StrainReason::valid;
      r.stress_rate[c] = sigma_dot;
      r.jaumann[c] = jaumann_rate(sigma_dot, s, spin(l));
      r.truesdell[c] = truesdell_rate(sigma_dot, s, l);
      r.oldroyd[c] = oldroyd_rate(sigma_dot, s, l);
      // Green-Naghdi needs R at every output differenced.
      StrainReason gn = f.f_reason[c];
      for (std::size_t k = 0; k + 1 < n && gn == StrainReason::valid; ++k)
        if (outputs_[k].f_reason[d].empty() || outputs_[k].f_reason[d][c] != StrainReason::valid)
          gn = StrainReason::previous_invalid;
      r.green_naghdi_reason[c] = gn;
      if (gn != StrainReason::valid) continue;
      for (std::size_t k = 0; k < n; ++k) rotation[k] = outputs_[k].rotation[d][static_cast<std::size_t>(c)];
      // R_dot R^T is skew for the exact R_dot; differencing leaves an O(h^2) symmetric part,
      // removed by taking the skew part (as in objective_rates).
      const Mat3 omega = spin(time_derivative(times, rotation).back() * rotation.back().transpose());
      r.green_naghdi[c] = green_naghdi_rate(sigma_dot, s, omega);
    }
  }
  return out;
}

}  // namespace upgrain::upscale
