#include "dem/boundary/servo_wall.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dem/core/error.h"

namespace upgrain::dem {

void check_servo_settings(const ServoSettings& s) {
  if (!std::isfinite(s.target_stress) || s.target_stress < 0.0)
    throw Error("servo wall: the target stress must be finite and >= 0 Pa, not " +
                std::to_string(s.target_stress));
  if (!(s.area > 0.0) || !std::isfinite(s.area))
    throw Error("servo wall: the area must be > 0 m^2, not " + std::to_string(s.area));
  if (!(s.alpha > 0.0 && s.alpha <= 1.0))
    throw Error("servo wall: the gain factor alpha must be in (0, 1] for a stable servo, not " +
                std::to_string(s.alpha));
  if (!(s.max_speed > 0.0) || !std::isfinite(s.max_speed))
    throw Error("servo wall: the maximum speed must be > 0 m/s, not " + std::to_string(s.max_speed));
}

double servo_gain(const ServoSettings& s, double stiffness_sum, double dt) {
  if (!(stiffness_sum > 0.0)) return std::numeric_limits<double>::infinity();
  return s.alpha * s.area / (stiffness_sum * dt);
}

double servo_speed(const ServoSettings& s, double measured_stress, double stiffness_sum, double dt) {
  const double error = s.target_stress - measured_stress;
  if (error == 0.0) return 0.0;
  const double gain = servo_gain(s, stiffness_sum, dt);
  const double speed = std::isinf(gain) ? std::copysign(s.max_speed, error) : gain * error;
  return std::clamp(speed, -s.max_speed, s.max_speed);
}

double servo_speed_with_integral(const ServoSettings& s, double measured_stress, double stiffness_sum,
                                 double dt, double beta, double& integral_speed) {
  const double error = s.target_stress - measured_stress;
  const double gain = servo_gain(s, stiffness_sum, dt);
  if (std::isinf(gain)) return error == 0.0 ? 0.0 : std::copysign(s.max_speed, error);
  const double speed = std::clamp(gain * error + integral_speed, -s.max_speed, s.max_speed);
  integral_speed = std::clamp(integral_speed + beta * gain * error, -s.max_speed, s.max_speed);
  return speed;
}

double hertz_wall_stiffness_bound(double normal_force, double contacts, double e_star, double r_max) {
  if (!(normal_force > 0.0) || !(contacts > 0.0)) return 0.0;
  const double c = 4.0 / 3.0 * e_star * std::sqrt(r_max);
  return 1.5 * std::cbrt(c * c) * std::cbrt(contacts * contacts) * std::cbrt(normal_force);
}

}  // namespace upgrain::dem
