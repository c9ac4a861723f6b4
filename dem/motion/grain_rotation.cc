#include "dem/motion/grain_rotation.h"

#include <algorithm>

#include "dem/core/lanes.h"
#include "dem/motion/rigid_rotation.h"

namespace upgrain::dem {

namespace {

// Two grains side by side in the two lanes of a vector (dem/core/lanes.h). A grain's turns are a
// chain of dependent operations, so one grain at a time waits on latencies; two at a time fill
// the pipeline and halve the instructions. Each lane computes exactly what the scalar code
// computes (rigid_rotation.h).
using lanes::Pair;

// First half for grains a and b (lanes 0 and 1), or a alone (T = double).
template <class T>
struct GrainLanes {
  RotorLanes<T> r;
  T omega[3], torque[3], inertia[3];
};

// L_b = J Q^T w + Q^T (h/2 T), and the rates (dt/2)/J of the free rotation.
template <class T>
[[gnu::always_inline]] inline void kick_into_body(GrainLanes<T>& g, T half, T dt, T inv_j[3], T rate[3]) {
  T wb[3], tb[3];
  const T t[3] = {half * g.torque[0], half * g.torque[1], half * g.torque[2]};
  rotate_vector<true>(g.r.w, g.r.v, g.omega, wb);
  rotate_vector<true>(g.r.w, g.r.v, t, tb);
  for (int k = 0; k < 3; ++k) {
    inv_j[k] = 1.0 / g.inertia[k];
    g.r.l[k] = g.inertia[k] * wb[k] + tb[k];
    rate[k] = (0.5 * dt) * inv_j[k];
  }
}

// w = Q (L_b / J) after the free rotation.
template <class T>
[[gnu::always_inline]] inline void body_into_omega(GrainLanes<T>& g, const T inv_j[3]) {
  const T lb[3] = {g.r.l[0] * inv_j[0], g.r.l[1] * inv_j[1], g.r.l[2] * inv_j[2]};
  rotate_vector<false>(g.r.w, g.r.v, lb, g.omega);
}

void load(const ParticleStore& p, std::size_t i, GrainLanes<double>& g) {
  const Eigen::Quaterniond& q = p.orientation[i];
  g.r.w = q.w();
  g.r.v[0] = q.x();
  g.r.v[1] = q.y();
  g.r.v[2] = q.z();
  for (int k = 0; k < 3; ++k) {
    g.omega[k] = p.omega[i][k];
    g.torque[k] = p.torque[i][k];
    g.inertia[k] = p.inertia_body[i][k];
  }
}

void store(ParticleStore& p, std::size_t i, const GrainLanes<double>& g) {
  p.orientation[i] = Eigen::Quaterniond(g.r.w, g.r.v[0], g.r.v[1], g.r.v[2]);
  p.omega[i] = Vec3(g.omega[0], g.omega[1], g.omega[2]);
}

void first_half_one(ParticleStore& p, std::size_t i, double half, double dt) {
  GrainLanes<double> g;
  load(p, i, g);
  double inv_j[3], rate[3];
  kick_into_body(g, half, dt, inv_j, rate);
  free_rotation(g.r, rate);
  body_into_omega(g, inv_j);
  store(p, i, g);
}

// A principal-axis turn of two grains that both turn by less than kModerateHalfAngle: each
// lane's sine and cosine by the series rigid_rotation.h's turn<K>() picks for it.
template <int K>
[[gnu::always_inline]] inline void moderate_turn(RotorLanes<Pair>& r, Pair half_step_rate, bool all_small) {
  const Pair half = r.l[K] * half_step_rate;
  Pair s, c;
  small_sine_cosine(half, s, c);
  if (!all_small) {
    Pair sm, cm;
    moderate_sine_cosine(half, sm, cm);
    for (int lane = 0; lane < 2; ++lane)
      if (!(std::abs(half[lane]) < kSmallHalfAngle)) {
        s[lane] = sm[lane];
        c[lane] = cm[lane];
      }
  }
  turn_about_axis<K>(r, s, c);
}

// Two grains: both must turn by less than kModerateHalfAngle per principal-axis turn (|L_K| <= |L|,
// with a margin for the rounding of the turns), else each goes alone.
void first_half_two(ParticleStore& p, std::size_t a, std::size_t b, double half, double dt) {
  GrainLanes<double> ga, gb;
  load(p, a, ga);
  load(p, b, gb);
  GrainLanes<Pair> g;
  auto pack = [](double x, double y) { return Pair{x, y}; };
  g.r.w = pack(ga.r.w, gb.r.w);
  for (int k = 0; k < 3; ++k) {
    g.r.v[k] = pack(ga.r.v[k], gb.r.v[k]);
    g.omega[k] = pack(ga.omega[k], gb.omega[k]);
    g.torque[k] = pack(ga.torque[k], gb.torque[k]);
    g.inertia[k] = pack(ga.inertia[k], gb.inertia[k]);
  }
  Pair inv_j[3], rate[3];
  kick_into_body(g, Pair{half, half}, Pair{dt, dt}, inv_j, rate);
  const Pair l2 = g.r.l[0] * g.r.l[0] + g.r.l[1] * g.r.l[1] + g.r.l[2] * g.r.l[2];
  Pair fastest = rate[0];
  for (int k = 1; k < 3; ++k)
    for (int lane = 0; lane < 2; ++lane) fastest[lane] = std::max(fastest[lane], rate[k][lane]);
  constexpr double kLimit = 0.99 * kModerateHalfAngle, kSmall = 0.99 * kSmallHalfAngle;
  bool all_small = true;
  for (int lane = 0; lane < 2; ++lane) {
    const double largest2 = l2[lane] * fastest[lane] * fastest[lane];
    if (!(largest2 < kLimit * kLimit)) {
      first_half_one(p, a, half, dt);
      first_half_one(p, b, half, dt);
      return;
    }
    all_small = all_small && largest2 < kSmall * kSmall;
  }
  // x(h/2) y(h/2) z(h) y(h/2) x(h/2), as free_rotation().
  moderate_turn<0>(g.r, 0.5 * rate[0], all_small);
  moderate_turn<1>(g.r, 0.5 * rate[1], all_small);
  moderate_turn<2>(g.r, rate[2], all_small);
  moderate_turn<1>(g.r, 0.5 * rate[1], all_small);
  moderate_turn<0>(g.r, 0.5 * rate[0], all_small);
  renormalise(g.r);
  body_into_omega(g, inv_j);
  for (int lane = 0; lane < 2; ++lane) {
    const std::size_t i = lane == 0 ? a : b;
    p.orientation[i] = Eigen::Quaterniond(g.r.w[lane], g.r.v[0][lane], g.r.v[1][lane], g.r.v[2][lane]);
    p.omega[i] = Vec3(g.omega[0][lane], g.omega[1][lane], g.omega[2][lane]);
  }
}

// w += Q (J^-1 (Q^T (h/2) T)) for grains a and b, or a alone.
template <class T>
[[gnu::always_inline]] inline void body_kick(T w, const T v[3], const T inertia[3], const T torque[3], T half,
                                             T omega[3]) {
  const T t[3] = {half * torque[0], half * torque[1], half * torque[2]};
  T tb[3], dw[3];
  rotate_vector<true>(w, v, t, tb);
  const T a[3] = {tb[0] / inertia[0], tb[1] / inertia[1], tb[2] / inertia[2]};
  rotate_vector<false>(w, v, a, dw);
  for (int k = 0; k < 3; ++k) omega[k] = omega[k] + dw[k];
}

void second_half_one(ParticleStore& p, std::size_t i, double half) {
  GrainLanes<double> g;
  load(p, i, g);
  body_kick(g.r.w, g.r.v, g.inertia, g.torque, half, g.omega);
  p.omega[i] = Vec3(g.omega[0], g.omega[1], g.omega[2]);
}

void second_half_two(ParticleStore& p, std::size_t a, std::size_t b, double half) {
  GrainLanes<double> ga, gb;
  load(p, a, ga);
  load(p, b, gb);
  auto pack = [](double x, double y) { return Pair{x, y}; };
  const Pair w = pack(ga.r.w, gb.r.w);
  Pair v[3], inertia[3], torque[3], omega[3];
  for (int k = 0; k < 3; ++k) {
    v[k] = pack(ga.r.v[k], gb.r.v[k]);
    inertia[k] = pack(ga.inertia[k], gb.inertia[k]);
    torque[k] = pack(ga.torque[k], gb.torque[k]);
    omega[k] = pack(ga.omega[k], gb.omega[k]);
  }
  body_kick(w, v, inertia, torque, Pair{half, half}, omega);
  p.omega[a] = Vec3(omega[0][0], omega[1][0], omega[2][0]);
  p.omega[b] = Vec3(omega[0][1], omega[1][1], omega[2][1]);
}

// Oriented grains (ellipsoids) in twos, spheres (and a last odd ellipsoid) one at a time: the pairing changes
// no bit of any grain.
template <class One, class Two>
void for_grains(ParticleStore& p, std::size_t n, double half, One one, Two two) {
  std::size_t waiting = n;  // an ellipsoid waiting for a partner
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.oriented(i)) {
      p.omega[i] += half * p.inv_inertia[i] * p.torque[i];
      continue;
    }
    if (waiting == n) {
      waiting = i;
      continue;
    }
    two(waiting, i);
    waiting = n;
  }
  if (waiting != n) one(waiting);
}

}  // namespace

void rotation_first_half(ParticleStore& p, std::size_t n, double half, double dt) {
  for_grains(
      p, n, half, [&](std::size_t i) { first_half_one(p, i, half, dt); },
      [&](std::size_t a, std::size_t b) { first_half_two(p, a, b, half, dt); });
}

void rotation_second_half(ParticleStore& p, std::size_t n, double half) {
  for_grains(
      p, n, half, [&](std::size_t i) { second_half_one(p, i, half); },
      [&](std::size_t a, std::size_t b) { second_half_two(p, a, b, half); });
}

}  // namespace upgrain::dem
