#include "dem/contact/force_kernel.h"

#include <algorithm>
#include <cmath>

#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/shaped_contact.h"

namespace upgrain::dem {

namespace {

// Inertia of grain i for the rolling dashpot: its moment about its centroid (an ellipsoid's
// smallest principal moment, so the dashpot is never over-estimated) plus m l^2 for the
// lever l to the contact point (Ai et al. 2011, with the lever for the radius).
double rolling_inertia(const ParticleStore& p, std::size_t i, const Vec3& lever) {
  const double own = p.is_ellipsoid(i) ? p.inertia_body[i].minCoeff() : 1.0 / p.inv_inertia[i];
  return own + p.mass(i) * lever.squaredNorm();
}

template <class E, bool Record, bool Shapes>
void compute_forces(ForceContext& ctx) {
  ParticleStore& p = *ctx.particles;
  const std::size_t n = p.size();
  const std::vector<int>& off = ctx.neighbors->offsets();
  const std::vector<int>& nbr = ctx.neighbors->partners();
  std::vector<TangentialSpring>& springs = ctx.neighbors->springs();
  const ContactMaterial& mat = ctx.material;
  constexpr bool kTangential = E::friction;
  // Ellipsoids: normal forces off the line of centres make torques, so rotation does not
  // need friction (Effects::rotation assumes spheres).
  constexpr bool kRotation = Shapes ? E::rotation_requested : E::rotation;
  std::vector<ShapedContactMemory>* memory = Shapes ? &ctx.neighbors->contact_memory() : nullptr;
  constexpr bool kRolling = E::rolling;
  std::vector<RollingSpring>* rolling = kRolling ? &ctx.neighbors->rolling_springs() : nullptr;
  constexpr bool kRollingWork = kRolling && E::energy;
  const RollingParameters rp = ctx.rolling;

  constexpr bool kDampingWork = E::damping && E::energy;
  for (std::size_t i = 0; i < n; ++i) {
    p.force[i].setZero();
    if constexpr (kRotation) p.torque[i].setZero();
  }
  if constexpr (kDampingWork) ctx.damping_force.assign(n, Vec3::Zero());
  if constexpr (kDampingWork && Shapes) ctx.damping_torque.assign(n, Vec3::Zero());
  if constexpr (kRollingWork) ctx.rolling_damping_torque.assign(n, Vec3::Zero());
  if constexpr (Shapes) ctx.posed.update(p);
  if constexpr (Record) ctx.contacts.clear();
  ContactEnergy energy;
  long contacts = 0;
  double max_ratio = 0.0;
  TangentialSpring dummy_spring;
  Vec3 rolling_viscous;  // the dashpot part of one contact's rolling torque

  ContactParameters cp{mat.e_star_pp, mat.g_star_pp, 0.0, 0.0, mat.friction_pp, mat.damping_ratio, ctx.dt};
  // A pair slot whose grains are apart forgets its history (written only when it has one: most
  // slots of the list are not touching).
  auto forget = [&](int k) {
    if constexpr (kTangential) {
      if (springs[k].stiffness != 0.0) springs[k] = TangentialSpring{};
    }
    if constexpr (kRolling) {
      if ((*rolling)[k].stiffness != 0.0) (*rolling)[k] = RollingSpring{};
    }
  };
  // Ellipsoid scenes go by chunks of rows: first every slot of the chunk is classified (bounding
  // spheres apart, a pair with an ellipsoid, or two spheres) and the shaped pairs are solved, two
  // at a time (shaped_pair_geometries: the same bits as one at a time); then the forces follow
  // in the slots' order, as for spheres.
  enum : unsigned char { kFar, kShaped, kSpheres };
  constexpr std::size_t kChunkRows = 16;
  for (std::size_t r0 = 0; r0 < n; r0 = Shapes ? std::min(n, r0 + kChunkRows) : n) {
    const std::size_t r1 = Shapes ? std::min(n, r0 + kChunkRows) : n;
    std::vector<ShapedPair>& shaped_pairs = ctx.shaped_pairs;
    std::size_t shaped_next = 0;
    if constexpr (Shapes) {
      ctx.slot_class.resize(static_cast<std::size_t>(off[r1] - off[r0]));
      shaped_pairs.clear();
      for (std::size_t i = r0; i < r1; ++i) {
        const bool ellipsoid_i = p.is_ellipsoid(i);
        for (int k = off[i]; k < off[i + 1]; ++k) {
          const int j = nbr[k];
          const double rsum = p.radius[i] + p.radius[j];
          unsigned char& c = ctx.slot_class[static_cast<std::size_t>(k - off[r0])];
          if ((p.x[j] - p.x[i]).squaredNorm() >= rsum * rsum) {
            c = kFar;
            forget(k);
            if (!(*memory)[k].empty()) (*memory)[k] = ShapedContactMemory{};
          } else if (ellipsoid_i || p.is_ellipsoid(j)) {
            c = kShaped;
            ShapedPair sp;
            sp.i = i;
            sp.j = static_cast<std::size_t>(j);
            sp.memory = &(*memory)[k];
            shaped_pairs.push_back(sp);
          } else {
            c = kSpheres;
          }
        }
      }
      if (!shaped_pairs.empty()) shaped_pair_geometries(ctx.posed, shaped_pairs, ctx.solver_stats);
    }
    for (std::size_t i = r0; i < r1; ++i) {
      const Vec3 xi = p.x[i];
      const double ri = p.radius[i];
      const double inv_mi = p.inv_mass[i];
      Vec3 fi = Vec3::Zero();
      Vec3 ti = Vec3::Zero();
      for (int k = off[i]; k < off[i + 1]; ++k) {
        const int j = nbr[k];
        ContactKinematics kin;
        double arm_i = 0.0, arm_j = 0.0;  // sphere pairs: lever lengths along the normal
        bool shaped = false;
        if constexpr (Shapes) {
          const unsigned char c = ctx.slot_class[static_cast<std::size_t>(k - off[r0])];
          if (c == kFar) continue;
          shaped = c == kShaped;
        }
        if (shaped) {
          const ShapedPair& sp = shaped_pairs[shaped_next++];
          if (!sp.touching) {
            forget(k);
            continue;
          }
          sp.kinematics(kin, cp.r_star);
        } else {
          const Vec3 d = p.x[j] - xi;
          const double rsum = ri + p.radius[j];
          const double dist2 = d.squaredNorm();
          if constexpr (!Shapes) {
            if (dist2 >= rsum * rsum) {
              forget(k);
              continue;
            }
          }
          sphere_pair_kinematics(d, dist2, ri, p.radius[j], kin, arm_i, arm_j, cp.r_star);
        }
        kin.v_i = p.v[i];
        kin.v_j = p.v[j];
        if constexpr (kRotation) {
          kin.omega_i = p.omega[i];
          kin.omega_j = p.omega[j];
        }
        cp.m_star = 1.0 / (inv_mi + p.inv_mass[j]);  // m_i m_j / (m_i + m_j)
        TangentialSpring& spring = kTangential ? springs[k] : dummy_spring;
        const ContactForce cf =
            contact_response<kTangential, E::damping, kRotation, E::energy>(cp, kin, spring, energy);
        fi += cf.on_i;
        p.force[j] -= cf.on_i;
        if constexpr (Record) ctx.contacts.push_back({static_cast<int>(i), j, xi + kin.lever_i, cf.on_i});
        if constexpr (kDampingWork) {
          ctx.damping_force[i] -= cf.damping * kin.normal;
          ctx.damping_force[j] += cf.damping * kin.normal;
          if constexpr (Shapes) {
            ctx.damping_torque[i] -= kin.lever_i.cross(cf.damping * kin.normal);
            ctx.damping_torque[j] += kin.lever_j.cross(cf.damping * kin.normal);
          }
        }
        if constexpr (kRotation) {
          if (shaped) {
            ti += kin.lever_i.cross(cf.on_i);
            p.torque[j] -= kin.lever_j.cross(cf.on_i);
          } else {
            const Vec3 arm_x_f = kin.normal.cross(cf.on_i);
            ti += arm_i * arm_x_f;
            p.torque[j] += arm_j * arm_x_f;
          }
        }
        if constexpr (kRolling) {
          const double k_n = hertz::normal_stiffness(cp.e_star, cp.r_star, kin.overlap);
          const double inertia_i = rolling_inertia(p, i, kin.lever_i);
          const double inertia_j = rolling_inertia(p, j, kin.lever_j);
          const Vec3 m_r = rolling_resistance<E::energy>(
              rp, kin.normal, kin.omega_i - kin.omega_j, cp.r_star, k_n, cf.normal,
              inertia_i * inertia_j / (inertia_i + inertia_j), cp.dt, (*rolling)[k], energy, rolling_viscous);
          ti += m_r;
          p.torque[j] -= m_r;
          if constexpr (kRollingWork) {
            ctx.rolling_damping_torque[i] += rolling_viscous;
            ctx.rolling_damping_torque[j] -= rolling_viscous;
          }
        }
        ++contacts;
        const double delta = kin.overlap;
        const double r_min =
            Shapes ? std::min(p.min_semi_axis(i), p.min_semi_axis(j)) : std::min(ri, p.radius[j]);
        if (delta > max_ratio * r_min) max_ratio = delta / r_min;  // divides only on a new maximum
      }
      p.force[i] += fi;
      if constexpr (kRotation) p.torque[i] += ti;
    }
  }

  // Particle-wall contacts: the wall is a rigid plane of the particles' own material, so
  // R* = r and m* = m. The contact point lies on the plane, at arm r - delta.
  const std::vector<PlaneWall>& walls = *ctx.walls;
  const std::size_t nw = walls.size();
  ctx.wall_force.assign(nw, Vec3::Zero());
  long wall_contacts = 0;
  constexpr bool kWallTangential = E::wall_friction;
  std::vector<WallNeighborList::Entries>& wall_lists = ctx.wall_neighbors->walls();
  ContactParameters wp{mat.e_star_pw, mat.g_star_pw, 0.0, 0.0, 0.0, mat.damping_ratio, ctx.dt};
  for (std::size_t w = 0; w < nw; ++w) {
    const PlaneWall& wall = walls[w];
    WallNeighborList::Entries& near = wall_lists[w];
    wp.friction = wall.friction;
    Vec3 wall_total = Vec3::Zero();
    const std::size_t m = near.particle.size();
    for (std::size_t k = 0; k < m; ++k) {
      const int i = near.particle[k];
      const double gap = wall.distance(p.x[i]);
      const double ri = p.radius[i];
      TangentialSpring& spring = kWallTangential ? near.spring[k] : dummy_spring;
      if (gap >= ri) {
        if constexpr (kWallTangential) {
          if (spring.stiffness != 0.0) spring = TangentialSpring{};
        }
        if constexpr (kRolling) {
          if (near.rolling[k].stiffness != 0.0) near.rolling[k] = RollingSpring{};
        }
        if constexpr (Shapes) near.r_star[k] = 0.0;
        continue;
      }
      ContactKinematics kin;
      kin.normal = -wall.normal;
      bool shaped = false;
      if constexpr (Shapes) shaped = p.is_ellipsoid(i);
      if (shaped) {
        double& r_held = near.r_star[k];
        if (!shaped_wall_geometry(ctx.posed[i], wall, r_held, kin)) {
          if constexpr (kWallTangential) {
            if (spring.stiffness != 0.0) spring = TangentialSpring{};
          }
          if constexpr (kRolling) {
            if (near.rolling[k].stiffness != 0.0) near.rolling[k] = RollingSpring{};
          }
          continue;
        }
        wp.r_star = r_held;
      } else {
        kin.overlap = ri - gap;
        kin.lever_i = gap * kin.normal;
        wp.r_star = ri;
      }
      kin.lever_j = Vec3::Zero();
      kin.v_i = p.v[i];
      kin.v_j = Vec3::Zero();
      if constexpr (kRotation) {
        kin.omega_i = p.omega[i];
        kin.omega_j = Vec3::Zero();
      }
      wp.m_star = p.mass(i);
      const ContactForce cf =
          contact_response<kWallTangential, E::damping, kRotation, E::energy>(wp, kin, spring, energy);
      p.force[i] += cf.on_i;
      wall_total -= cf.on_i;
      if constexpr (Record)
        ctx.contacts.push_back({i, -static_cast<int>(w) - 1, p.x[i] + kin.lever_i, cf.on_i});
      if constexpr (kDampingWork) {
        ctx.damping_force[i] -= cf.damping * kin.normal;
        if constexpr (Shapes) ctx.damping_torque[i] -= kin.lever_i.cross(cf.damping * kin.normal);
      }
      if constexpr (kRotation) {
        if (shaped)
          p.torque[i] += kin.lever_i.cross(cf.on_i);
        else
          p.torque[i] += gap * kin.normal.cross(cf.on_i);
      }
      if constexpr (kRolling) {
        // The wall neither turns nor moves: omega_j = 0, and the grain's own inertia.
        const double k_n = hertz::normal_stiffness(wp.e_star, wp.r_star, kin.overlap);
        const Vec3 m_r = rolling_resistance<E::energy>(rp, kin.normal, kin.omega_i, wp.r_star, k_n, cf.normal,
                                                       rolling_inertia(p, i, kin.lever_i), wp.dt,
                                                       near.rolling[k], energy, rolling_viscous);
        p.torque[i] += m_r;
        if constexpr (kRollingWork) ctx.rolling_damping_torque[i] += rolling_viscous;
      }
      ++wall_contacts;
      max_ratio = std::max(max_ratio, kin.overlap / (Shapes ? p.min_semi_axis(i) : ri));
    }
    ctx.wall_force[w] = wall_total;
  }

  ctx.energy = energy;
  ctx.particle_contacts = contacts;
  ctx.wall_contacts = wall_contacts;
  ctx.max_overlap_ratio = max_ratio;
}

}  // namespace

ForceKernels select_force_kernels(const EffectSet& e, bool shapes) {
  if (e.rolling_resistance) {
    if (shapes) {
      return with_rolling_effects(e, []<class E>() {
        return ForceKernels{&compute_forces<E, false, true>, &compute_forces<E, true, true>};
      });
    }
    return with_rolling_effects(e, []<class E>() {
      return ForceKernels{&compute_forces<E, false, false>, &compute_forces<E, true, false>};
    });
  }
  if (shapes) {
    return with_effects(e, []<class E>() {
      return ForceKernels{&compute_forces<E, false, true>, &compute_forces<E, true, true>};
    });
  }
  return with_effects(e, []<class E>() {
    return ForceKernels{&compute_forces<E, false, false>, &compute_forces<E, true, false>};
  });
}

}  // namespace upgrain::dem
