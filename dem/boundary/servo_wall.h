#pragma once
// A servo-controlled wall: the velocity that brings a wall's normal stress to a target, the
// numerical servo of Itasca's PFC (PFC manual, "servo-control of walls") as used in DEM
// element tests since Thornton (2000, Geotechnique 50(1) 43-53). Plain functions over plain
// numbers: the run layer measures the stress and moves the wall (coupling/run/lid.h).
//
// The gain (docs/calibration.md, "Servo wall"): moving the wall by v dt along its normal
// changes its force by K v dt, K the sum of the normal stiffnesses of its contacts, so its
// stress by K v dt / A. With v = G (sigma_target - sigma), the error e = sigma_target - sigma
// of the next step is e (1 - G K dt / A). The gain
//     G = alpha A / (K dt)
// makes that e (1 - alpha): the error shrinks monotonically for 0 < alpha <= 1 (alpha = 1 reaches
// the target in one step on a linear spring), oscillates for 1 < alpha < 2 and grows beyond 2.
// The speed is clamped to a maximum, which also governs the approach before any contact
// (K = 0, an infinite gain).
namespace upgrain::dem {

struct ServoSettings {
  double target_stress = 0.0;  // Pa, compression positive
  double area = 0.0;           // m^2 over which the wall's normal force is spread
  double alpha = 0.5;          // the relaxation factor, in (0, 1]
  double max_speed = 0.0;      // m/s, > 0
};

// Throws upgrain::Error naming the setting when a value is out of range.
void check_servo_settings(const ServoSettings& s);

// G = alpha A / (K dt) (m/(s Pa)); infinite when K = 0.
double servo_gain(const ServoSettings& s, double stiffness_sum, double dt);

// The wall's speed along its normal into the grains (m/s): G (target - measured), clamped to
// [-max_speed, max_speed]. Positive when the measured stress is below the target.
double servo_speed(const ServoSettings& s, double measured_stress, double stiffness_sum, double dt);

// A proportional-integral servo for a wall that must keep moving to hold its target (a side
// wall of a sample that dilates or contracts as it is sheared): the proportional servo alone
// holds such a wall only with the lag e = u / G, u the speed it must keep. The integral term
// I learns u: v = G e + I, then I += beta G e (both clamped to the maximum speed), so that at a
// steady speed e -> 0 (docs/calibration.md, "Servo wall"). On a linear spring the error and
// the scaled integral w = K dt I / A follow e' = (1 - alpha) e - w, w' = w + alpha beta e, whose
// eigenvalues solve z^2 - (2 - alpha) z + 1 - alpha + alpha beta = 0: inside the unit circle for
// 0 <= beta < 1 (Jury's criterion), real (no ringing) for beta <= alpha / 4; beta = 0 is the
// proportional servo. Before any contact (K = 0) the wall approaches at the maximum speed and
// I is left as it is.
double servo_speed_with_integral(const ServoSettings& s, double measured_stress, double stiffness_sum,
                                 double dt, double beta, double& integral_speed);

// An upper bound of K for a wall pressed by `contacts` Hertz contacts with total normal force
// F (N), for the gain: a contact's stiffness is k = dF/d(delta) = 3/2 c^(2/3) F_i^(1/3) with
// c = 4/3 E* sqrt(R) (Johnson 1985, eq. 4.23), and at a total F the sum of F_i^(1/3) over N
// contacts is largest when they share F equally (the cube root is concave): N^(2/3) F^(1/3).
// c is that of the largest Hertz radius r_max. Exact for N equal contacts of radius r_max;
// otherwise the servo is slower than alpha says, never less stable. 0 without force.
double hertz_wall_stiffness_bound(double normal_force, double contacts, double e_star, double r_max);

}  // namespace upgrain::dem
