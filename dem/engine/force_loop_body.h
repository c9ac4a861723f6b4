#pragma once
// The one source of the force loop (force_loop.h), included by the two translation units that
// instantiate it, one per summation, so that they compile side by side.
//
// Where the two summations differ (dem/engine/summation.h, dem/neighbor/verlet_list.h):
//  - fast: rows are owned particles in local order; a row's sum starts from zero and is added
//    to the particle at its end, partners (ghosts included) receive their share at once, and
//    walls come after the pairs. The ghosts' sums go back to their owners afterwards
//    (Domain::return_ghost_sums). Every contact's energy is one running sum.
//  - deterministic: rows and partners in global-id order, walls first; a row's sum starts
//    from the particle's force so far, so each particle adds walls by index, then partners
//    by increasing global id. A pair across two ranks is evaluated on both, in the same
//    orientation, and each keeps the share of its own particle. A contact's energies, elastic
//    and dissipated, go to the pair's first particle (each pair once over the ranks).
#include <algorithm>
#include <cmath>

#include "dem/contact/contact_laws.h"
#include "dem/contact/geometry/pair_geometries.h"
#include "dem/engine/force_loop.h"

namespace upgrain::dem::force_loop_detail {

// A contact whose grains are apart forgets its history: written only when it has one, since
// most slots of the list are not touching.
template <bool Tangential, bool Rolling>
inline __attribute__((always_inline)) void forget_history(TangentialSpring* springs, RollingSpring* rolling,
                                                          std::size_t k) {
  if constexpr (Tangential) {
    if (springs[k].stiffness != 0.0) springs[k] = TangentialSpring{};
  }
  if constexpr (Rolling) {
    if (rolling[k].stiffness != 0.0 || rolling[k].twist_stiffness != 0.0) rolling[k] = RollingSpring{};
  }
}

// Inertia of grain i for the rolling dashpot: its moment about its centroid (an ellipsoid's
// smallest principal moment, so the dashpot is never over-estimated) plus m l^2 for the
// lever l to the contact point (Ai et al. 2011, with the lever for the radius).
inline double rolling_inertia(const ParticleStore& p, std::size_t i, const Vec3& lever) {
  const double own = p.oriented(i) ? p.inertia_body[i].minCoeff() : 1.0 / p.inv_inertia[i];
  return own + p.mass(i) * lever.squaredNorm();
}

template <class Law, class E, bool Shapes, bool Record, Summation S>
void compute(const ForceInput& in) {
  constexpr bool kDeterministic = S == Summation::deterministic;
  constexpr bool kTangential = E::friction;
  constexpr bool kWallTangential = E::wall_friction;
  // Ellipsoids: normal forces off the line of centres make torques, so rotation does not
  // need friction (Effects::rotation assumes spheres).
  constexpr bool kRotation = Shapes ? E::rotation_requested : E::rotation;
  constexpr bool kRolling = E::rolling;
  constexpr bool kEnergy = E::energy;
  constexpr bool kDampingWork = E::damping && E::energy;
  constexpr bool kRollingWork = kRolling && E::energy;
  constexpr bool kEnergyPerParticle = kDeterministic && kEnergy;

  ParticleStore& p = *in.particles;
  ForceOutput& out = *in.out;
  ContactHistory& h = *in.history;
  const PairList& pl = *in.pairs;
  const WallList& wl = *in.wall_entries;
  const std::vector<PlaneWall>& walls = *in.walls;
  const ContactMaterial& mat = in.material;
  const RollingParameters rp = in.rolling;
  const std::size_t n = p.size();
  const int n_owned = in.n_owned;
  const bool mean_flow = in.mean_flow != nullptr;
  const MeanFlow flow = mean_flow ? *in.mean_flow : MeanFlow{};

  for (std::size_t i = 0; i < n; ++i) {
    p.force[i].setZero();
    if constexpr (kRotation) p.torque[i].setZero();
  }
  if constexpr (kDampingWork) out.damping_force.assign(n, Vec3::Zero());
  if constexpr (kDampingWork && Shapes) out.damping_torque.assign(n, Vec3::Zero());
  if constexpr (kRollingWork) out.rolling_damping_torque.assign(n, Vec3::Zero());
  if constexpr (kEnergyPerParticle) out.particle_elastic.assign(n, ElasticEnergy{});
  DissipatedEnergy* const dissipation = in.dissipation;
  out.wall_force.assign(kDeterministic ? wl.size() : walls.size(), Vec3::Zero());
  if constexpr (kDampingWork) out.wall_damping.assign(out.wall_force.size(), Vec3::Zero());
  if constexpr (Shapes) in.posed->update(p);
  if constexpr (Record) out.contacts.clear();
  ContactEnergy energy;  // this rank's running sums (fast summation)
  long pair_contacts = 0, wall_contacts = 0;
  double max_ratio = 0.0;
  int worst_i = -1, worst_j = -1;  // the contact of max_ratio (j = -(w + 1): wall w)
  TangentialSpring dummy_spring;
  Vec3 rolling_viscous;  // the dashpot part of one contact's rolling torque

  // The law's constants, pair and wall (dem/contact/contact_laws.h), copied into locals once per
  // evaluation: no store of a force can alias them, so they stay in registers or on the stack.
  const auto law = constants_of<Law>(*in.law);

  // Particle-wall contacts: R* = r and m* = m (a rigid plane). The contact point lies on the
  // plane, at arm r - delta.
  ContactParameters wp{.r_star = 0.0, .m_star = 0.0, .friction = 0.0, .zeta = mat.damping_ratio, .dt = in.dt};
  auto forget_wall = [&](std::size_t e) {
    forget_history<kWallTangential, kRolling>(h.wall_spring.data(), h.wall_rolling.data(), e);
  };
  // The two loops are inlined into compute(): as calls, the sums they keep would live in the
  // closure, in memory, instead of registers (measured with callgrind: +3 % instructions).
  auto wall_loop = [&]() __attribute__((always_inline)) {
    for (std::size_t e = 0; e < wl.size(); ++e) {
      const int i = wl.particle[e];
      const int w = wl.wall[e];
      const PlaneWall& wall = walls[w];
      const double gap = wall.distance(p.x[i]);
      const double ri = p.radius[i];
      if (gap >= ri) {
        forget_wall(e);
        if constexpr (Shapes) h.wall_r_star[e] = 0.0;
        continue;
      }
      ContactKinematics kin;
      kin.normal = -wall.normal;
      // The grain's row of the wall-geometry table (dem/contact/geometry/pair_geometries.h).
      bool shaped = false;
      if constexpr (Shapes) shaped = !kWallClosedForm[static_cast<int>(p.shape[i])];
      if (shaped) {
        const bool touching = with_wall_geometry(p.shape[i], [&]<class G>() {
          if constexpr (G::closed_form)
            return false;
          else
            return G::touching(*in.posed, static_cast<std::size_t>(i), wall, h.wall_r_star[e], kin);
        });
        if (!touching) {
          forget_wall(e);
          continue;
        }
        wp.r_star = h.wall_r_star[e];
      } else {
        sphere_plane_kinematics(gap, ri, kin);
        wp.r_star = ri;
      }
      kin.lever_j = Vec3::Zero();
      kin.v_i = p.v[i];
      if (mean_flow) kin.v_i += flow.of(p.x[i]);  // absolute: u + L x
      kin.v_j = wall.velocity;  // a rigid translation: every point of the wall moves with it
      if constexpr (kRotation) {
        kin.omega_i = p.omega[i];
        kin.omega_j = Vec3::Zero();
      }
      wp.friction = wall.friction;
      wp.m_star = p.mass(i);
      ContactEnergy ce;
      ContactEnergy& sink = kDeterministic ? ce : energy;
      TangentialSpring& spring = kWallTangential ? h.wall_spring[e] : dummy_spring;
      const ContactForce cf = contact_response<kWallTangential, E::damping, kRotation, kEnergy, Law>(
          law.wall, wp, kin, spring, sink);
      if constexpr (kEnergy) {
        // A moving wall's work on the grain, F . v_wall dt, and the wall's part of the second
        // half of the dashpot's work, which step() books with the grain's own velocity: the
        // dashpot dissipates with the relative one. Both book the coming step's half ahead, at
        // the wall's present velocity (Simulation::energy() and set_wall_velocity() settle it;
        // docs/integrator.md "Moving walls").
        sink.wall_work += wp.dt * cf.on_i.dot(wall.velocity);
        if constexpr (E::damping)
          sink.dissipated_damping -= 0.5 * wp.dt * cf.damping * kin.normal.dot(wall.velocity);
      }
      p.force[i] += cf.on_i;
      if constexpr (kDeterministic)
        out.wall_force[e] = cf.on_i;
      else
        out.wall_force[w] -= cf.on_i;
      if constexpr (Record) out.contacts.push_back({i, -w - 1, p.x[i] + kin.lever_i, cf.on_i});
      if constexpr (kDampingWork) {
        out.damping_force[i] -= cf.damping * kin.normal;
        if constexpr (Shapes) out.damping_torque[i] -= kin.lever_i.cross(cf.damping * kin.normal);
        if constexpr (kDeterministic)
          out.wall_damping[e] = -cf.damping * kin.normal;
        else
          out.wall_damping[w] += cf.damping * kin.normal;
      }
      if constexpr (kRotation) {
        if (shaped)
          p.torque[i] += kin.lever_i.cross(cf.on_i);
        else
          p.torque[i] += gap * kin.normal.cross(cf.on_i);
      }
      if constexpr (kRolling) {
        // The wall does not turn (it may translate): omega_j = 0, and the grain's own inertia.
        const RollingContact rc{kin.normal,   kin.omega_i, wp.r_star,
                                cf.stiffness, cf.normal,   rolling_inertia(p, i, kin.lever_i),
                                wp.dt,        kin.overlap, wp.friction};
        const Vec3 m_r =
            Law::Rolling::template torque<kEnergy>(rp, rc, h.wall_rolling[e], sink, rolling_viscous);
        p.torque[i] += m_r;
        if constexpr (kRollingWork) out.rolling_damping_torque[i] += rolling_viscous;
      }
      if constexpr (kEnergyPerParticle) {
        book(ce, out.particle_elastic[i]);
        book_with_wall_work(ce, dissipation[i]);
      }
      ++wall_contacts;
      const double ratio = kin.overlap / (Shapes ? p.min_semi_axis(i) : ri);
      if (ratio > max_ratio) max_ratio = ratio, worst_i = i, worst_j = -w - 1;
    }
  };

  // Particle pairs.
  ContactParameters cp{
      .r_star = 0.0, .m_star = 0.0, .friction = mat.friction_pp, .zeta = mat.damping_ratio, .dt = in.dt};
  auto forget = [&](int k) {
    forget_history<kTangential, kRolling>(h.pair_spring.data(), h.pair_rolling.data(),
                                          static_cast<std::size_t>(k));
  };
  auto pair_loop = [&]() __attribute__((always_inline)) {
    // Raw views of the arrays the loop indexes: a vector's data pointer lives in memory, and
    // the compiler reloads it where a store might have changed it.
    const int* const start = pl.row_start.data();
    const int* const nbr = pl.partner.data();
    const Vec3* const x = p.x.data();
    const Vec3* const v = p.v.data();
    const Vec3* const omega = p.omega.data();
    const double* const radius = p.radius.data();
    const double* const inv_mass = p.inv_mass.data();
    Vec3* const force = p.force.data();
    Vec3* const torque = p.torque.data();
    const std::size_t rows = pl.num_rows();
    // Scenes with non-spherical grains go by chunks of rows: first every slot of the chunk is
    // classified by the pair-geometry table (bounding spheres apart, two spheres, or the batch of
    // its geometry) and each batch is solved (the support-function pairs two at a time: the same
    // bits as one at a time); then the forces follow in the slots' order, as for spheres.
    constexpr std::size_t kChunkRows = 16;
    constexpr int kBatches = kBatchedPairGeometries;
    for (std::size_t r0 = 0; r0 < rows; r0 = Shapes ? std::min(rows, r0 + kChunkRows) : rows) {
      const std::size_t r1 = Shapes ? std::min(rows, r0 + kChunkRows) : rows;
      std::array<std::size_t, kBatches> batch_next{};
      // The chunk's slot classes, from its first slot (a raw pointer: the stores into it, of
      // bytes, might otherwise alias every vector the loop reads).
      unsigned char* slot_class = nullptr;
      const int first_slot = start[r0];
      if constexpr (Shapes) {
        out.slot_class.resize(static_cast<std::size_t>(start[r1] - first_slot));
        slot_class = out.slot_class.data();
        for (std::vector<ShapedPair>& b : out.shaped_pairs) b.clear();
        const ShapeKind* const kind = p.shape.data();
        for (std::size_t r = r0; r < r1; ++r) {
          const int i = pl.row_particle[r];
          const auto& class_of = kPairClass[static_cast<int>(kind[i])];
          for (int k = start[r]; k < start[r + 1]; ++k) {
            const int j = nbr[k];
            const double rsum = p.radius[i] + p.radius[j];
            unsigned char& c = slot_class[k - first_slot];
            if ((p.x[j] - p.x[i]).squaredNorm() >= rsum * rsum) {
              c = kApartClass;
              forget(k);
              if (!h.pair_memory[k].empty()) h.pair_memory[k] = ShapedContactMemory{};
            } else {
              c = class_of[static_cast<int>(kind[j])];
              if (c != kSpherePairClass) {
                ShapedPair sp;
                sp.i = static_cast<std::size_t>(i);
                sp.j = static_cast<std::size_t>(j);
                sp.memory = &h.pair_memory[k];
                out.shaped_pairs[kBatches == 1 ? 0 : c - kFirstBatchClass].push_back(sp);
              }
            }
          }
        }
        [&]<class... G>(std::tuple<G...>*) {
          int g = 0;
          ((out.shaped_pairs[g].empty()
                ? void()
                : G::solve(*in.posed, out.shaped_pairs[g], in.solver_settings, *in.solver_stats),
            ++g),
           ...);
        }(static_cast<BatchedPairGeometries*>(nullptr));
      }
      std::array<const ShapedPair*, kBatches> batch_data;
      for (int g = 0; g < kBatches; ++g) batch_data[g] = out.shaped_pairs[g].data();
      for (std::size_t r = r0; r < r1; ++r) {
        const int i = pl.row_particle[r];
        const Vec3 xi = x[i];
        const double ri = radius[i];
        const double inv_mi = inv_mass[i];
        const bool owned_i = i < n_owned;
        // The row's sums: from zero, added at the end (fast); or from the particle's sums so
        // far, in order (deterministic).
        Vec3 fi = kDeterministic ? force[i] : Vec3::Zero();
        Vec3 ti = Vec3::Zero();
        if constexpr (kDeterministic && kRotation) ti = torque[i];
        // The particle's shares so far: elastic, of this evaluation; dissipated, since the last
        // rebuild (a ghost's is its owner's to keep).
        [[maybe_unused]] ElasticEnergy elastic_i;
        [[maybe_unused]] DissipatedEnergy dissipated_i;
        if constexpr (kEnergyPerParticle) {
          elastic_i = out.particle_elastic[i];
          if (owned_i) dissipated_i = dissipation[i];
        }
        for (int k = start[r]; k < start[r + 1]; ++k) {
          const int j = nbr[k];
          ContactKinematics kin;
          double arm_i = 0.0, arm_j = 0.0;  // sphere pairs: lever lengths along the normal
          bool shaped = false;
          int batch = 0;  // the geometry whose batch holds the pair
          if constexpr (Shapes) {
            const unsigned char c = slot_class[k - first_slot];
            if (c == kApartClass) continue;
            shaped = c != kSpherePairClass;
            if constexpr (kBatches > 1) batch = c - kFirstBatchClass;
          }
          if (shaped) {
            const ShapedPair& sp = batch_data[batch][batch_next[batch]++];
            if (!sp.touching) {
              forget(k);
              continue;
            }
            sp.kinematics(kin, cp.r_star);
          } else {
            const Vec3 d = x[j] - xi;
            const double rsum = ri + radius[j];
            const double dist2 = d.squaredNorm();
            if constexpr (!Shapes) {
              if (dist2 >= rsum * rsum) {
                forget(k);
                continue;
              }
            }
            const SpherePairArms arms = sphere_pair_kinematics(d, dist2, ri, radius[j], kin);
            arm_i = arms.arm_i;
            arm_j = arms.arm_j;
            cp.r_star = arms.r_star;
          }
          kin.v_i = v[i];
          kin.v_j = v[j];
          if (mean_flow) kin.v_j += flow.of(x[j] - xi);
          if constexpr (kRotation) {
            kin.omega_i = omega[i];
            kin.omega_j = omega[j];
          }
          cp.m_star = 1.0 / (inv_mi + inv_mass[j]);  // m_i m_j / (m_i + m_j)
          ContactEnergy ce;
          ContactEnergy& sink = kDeterministic ? ce : energy;
          TangentialSpring& spring = kTangential ? h.pair_spring[k] : dummy_spring;
          const ContactForce cf = contact_response<kTangential, E::damping, kRotation, kEnergy, Law>(
              law.pair, cp, kin, spring, sink);
          fi += cf.on_i;
          force[j] -= cf.on_i;
          if constexpr (Record) out.contacts.push_back({i, j, xi + kin.lever_i, cf.on_i});
          if constexpr (kDampingWork) {
            out.damping_force[i] -= cf.damping * kin.normal;
            out.damping_force[j] += cf.damping * kin.normal;
            if constexpr (Shapes) {
              out.damping_torque[i] -= kin.lever_i.cross(cf.damping * kin.normal);
              out.damping_torque[j] += kin.lever_j.cross(cf.damping * kin.normal);
            }
          }
          if constexpr (kRotation) {
            if (shaped) {
              ti += kin.lever_i.cross(cf.on_i);
              torque[j] -= kin.lever_j.cross(cf.on_i);
            } else {
              const Vec3 arm_x_f = kin.normal.cross(cf.on_i);
              ti += arm_i * arm_x_f;
              torque[j] += arm_j * arm_x_f;
            }
          }
          if constexpr (kRolling) {
            const double inertia_i = rolling_inertia(p, i, kin.lever_i);
            const double inertia_j = rolling_inertia(p, j, kin.lever_j);
            const RollingContact rc{kin.normal,
                                    kin.omega_i - kin.omega_j,
                                    cp.r_star,
                                    cf.stiffness,
                                    cf.normal,
                                    inertia_i * inertia_j / (inertia_i + inertia_j),
                                    cp.dt,
                                    kin.overlap,
                                    E::friction ? cp.friction : 0.0};
            const Vec3 m_r =
                Law::Rolling::template torque<kEnergy>(rp, rc, h.pair_rolling[k], sink, rolling_viscous);
            ti += m_r;
            torque[j] -= m_r;
            if constexpr (kRollingWork) {
              out.rolling_damping_torque[i] += rolling_viscous;
              out.rolling_damping_torque[j] -= rolling_viscous;
            }
          }
          if constexpr (kEnergyPerParticle) {
            book(ce, elastic_i);
            book(ce, dissipated_i);
          }
          if (!kDeterministic || owned_i) ++pair_contacts;
          const double delta = kin.overlap;
          const double r_min =
              Shapes ? std::min(p.min_semi_axis(i), p.min_semi_axis(j)) : std::min(ri, radius[j]);
          if (delta > max_ratio * r_min) {  // divides only on a new maximum
            max_ratio = delta / r_min;
            worst_i = i, worst_j = j;
          }
        }
        if constexpr (kDeterministic) {
          force[i] = fi;
          if constexpr (kRotation) torque[i] = ti;
        } else {
          force[i] += fi;
          if constexpr (kRotation) torque[i] += ti;
        }
        if constexpr (kEnergyPerParticle) {
          out.particle_elastic[i] = elastic_i;
          if (owned_i) dissipation[i] = dissipated_i;
        }
      }
    }
  };

  if constexpr (kDeterministic) {
    wall_loop();
    pair_loop();
  } else {
    pair_loop();
    wall_loop();
  }
  out.energy = energy;
  out.pair_contacts = pair_contacts;
  out.wall_contacts = wall_contacts;
  out.max_overlap_ratio = max_ratio;
  out.max_overlap_particle = worst_i < 0 ? -1 : p.id[worst_i];
  out.max_overlap_partner = worst_j < 0 ? worst_j : p.id[worst_j];
}

// Every instantiation of one summation: per contact law (dem/contact/contact_laws.h), shape
// class and effect set (dem/contact/effects.h), each through its one dispatch point.
template <Summation S>
ForceLoops force_loops_for(const EffectSet& e, bool shapes, std::string_view law) {
  return with_contact_law(law, [&]<class Law>() {
    auto make = [&]<bool Shapes>() {
      auto pick = []<class E>() {
        EffectSet compiled;
        compiled.gravity = false;
        compiled.friction = E::friction;
        compiled.damping = E::damping;
        compiled.wall_friction = E::wall_friction;
        compiled.rotation = Shapes ? E::rotation_requested : E::rotation;
        compiled.energy_tracking = E::energy;
        compiled.rolling_resistance = E::rolling;
        return ForceLoops{&compute<Law, E, Shapes, false, S>, &compute<Law, E, Shapes, true, S>, compiled,
                          Law::name};
      };
      return e.rolling_resistance ? with_rolling_effects(e, pick) : with_effects(e, pick);
    };
    return shapes ? make.template operator()<true>() : make.template operator()<false>();
  });
}

}  // namespace upgrain::dem::force_loop_detail
