#include "dem/parallel/deterministic_forces.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "dem/contact/contact_response.h"
#include "dem/contact/shaped_contact.h"

namespace upgrain::dem {

namespace {

template <class E, bool Record, bool Shapes>
DeterministicForceResult compute(const DeterministicForceInput& in) {
  ParticleStore& p = *in.particles;
  ContactLists& l = *in.lists;
  const int n_owned = in.n_owned;
  const ContactMaterial& mat = in.material;
  DeterministicForceResult out;
  TangentialSpring dummy_spring;
  constexpr bool kDampingWork = E::damping && E::energy;
  // As the serial loop: ellipsoids turn under normal forces as well.
  constexpr bool kRotation = Shapes ? E::rotation_requested : E::rotation;

  for (int i = 0; i < n_owned; ++i) {
    p.force[i].setZero();
    if constexpr (kRotation) p.torque[i].setZero();
  }
  if constexpr (Shapes) in.posed->update(p);
  if constexpr (E::energy) {
    in.energy->elastic_normal.assign(n_owned, 0.0);
    in.energy->elastic_tangential.assign(n_owned, 0.0);
    if constexpr (kDampingWork) in.energy->damping_force.assign(n_owned, Vec3::Zero());
    if constexpr (kDampingWork && Shapes) in.energy->damping_torque.assign(n_owned, Vec3::Zero());
  }
  if constexpr (Record) in.record->clear();

  // 1. Walls, straight into the owned particles: entries are sorted by (particle, wall),
  //    so each particle receives its wall forces in wall order, before any pair.
  const std::vector<PlaneWall>& walls = *in.walls;
  ContactParameters wp{mat.e_star_pw, mat.g_star_pw, 0.0, 0.0, 0.0, mat.damping_ratio, in.dt};
  for (std::size_t e = 0; e < l.wall.size(); ++e) {
    WallContact& c = l.wall[e];
    const int i = c.particle;
    const PlaneWall& wall = walls[c.wall];
    const double gap = wall.distance(p.x[i]);
    const double ri = p.radius[i];
    TangentialSpring& spring = E::wall_friction ? c.spring : dummy_spring;
    if (gap >= ri) {
      if constexpr (E::wall_friction) {
        if (spring.stiffness != 0.0) spring = TangentialSpring{};
      }
      if constexpr (Shapes) l.wall_r_star[e] = 0.0;
      l.wall_force_on_particle[e].setZero();
      continue;
    }
    ContactKinematics kin;
    kin.normal = -wall.normal;
    bool shaped = false;
    if constexpr (Shapes) shaped = p.is_ellipsoid(i);
    if (shaped) {
      if (!shaped_wall_geometry((*in.posed)[i], wall, l.wall_r_star[e], kin)) {
        if constexpr (E::wall_friction) {
          if (spring.stiffness != 0.0) spring = TangentialSpring{};
        }
        l.wall_force_on_particle[e].setZero();
        continue;
      }
      wp.r_star = l.wall_r_star[e];
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
    wp.friction = wall.friction;
    wp.m_star = p.mass(i);
    ContactEnergy ce;
    const ContactForce cf =
        contact_response<E::wall_friction, E::damping, kRotation, E::energy>(wp, kin, spring, ce);
    l.wall_force_on_particle[e] = cf.on_i;
    if constexpr (E::energy) {
      in.energy->elastic_normal[i] += ce.elastic_normal;
      in.energy->elastic_tangential[i] += ce.elastic_tangential;
      out.dissipated.dissipated_damping += ce.dissipated_damping;
      out.dissipated.dissipated_friction += ce.dissipated_friction;
      out.dissipated.tangential_stiffness_change += ce.tangential_stiffness_change;
      if constexpr (kDampingWork) in.energy->damping_force[i] -= cf.damping * kin.normal;
      if constexpr (kDampingWork && Shapes)
        in.energy->damping_torque[i] -= kin.lever_i.cross(cf.damping * kin.normal);
    }
    if constexpr (Record) in.record->push_back({i, -c.wall - 1, p.x[i] + kin.lever_i, cf.on_i});
    p.force[i] += cf.on_i;
    if constexpr (kRotation) {
      if (shaped)
        p.torque[i] += kin.lever_i.cross(cf.on_i);
      else
        p.torque[i] += gap * kin.normal.cross(cf.on_i);
    }
    ++out.wall_contacts;
    out.max_overlap_ratio = std::max(out.max_overlap_ratio, kin.overlap / (Shapes ? p.min_semi_axis(i) : ri));
  }

  // 2. Pairs into their slots, in the canonical orientation (lo = lower global id).
  ContactParameters cp{mat.e_star_pp, mat.g_star_pp, 0.0, 0.0, mat.friction_pp, mat.damping_ratio, in.dt};
  const std::size_t m = l.lo.size();
  double max_ratio = out.max_overlap_ratio;
  // A slot whose pair is apart: not touching, no spring.
  auto apart = [&](std::size_t k) {
    l.touching[k] = 0;
    if constexpr (E::friction) {
      if (l.spring[k].stiffness != 0.0) l.spring[k] = TangentialSpring{};
    }
  };
  // Ellipsoid scenes go by chunks of slots, as the serial loop by chunks of rows: the slots are
  // classified and the shaped pairs solved two at a time first (the same bits as one at a time),
  // then the forces follow in slot order.
  enum : unsigned char { kFar, kShaped, kSpheres };
  constexpr std::size_t kChunkSlots = 64;
  // One allocation per evaluation, none per chunk or contact.
  std::array<unsigned char, kChunkSlots> slot_class{};
  std::vector<ShapedPair> shaped_pairs;
  if constexpr (Shapes) shaped_pairs.reserve(kChunkSlots);
  for (std::size_t k0 = 0; k0 < m; k0 = Shapes ? std::min(m, k0 + kChunkSlots) : m) {
    const std::size_t k1 = Shapes ? std::min(m, k0 + kChunkSlots) : m;
    std::size_t shaped_next = 0;
    if constexpr (Shapes) {
      shaped_pairs.clear();
      for (std::size_t k = k0; k < k1; ++k) {
        const int i = l.lo[k];
        const int j = l.hi[k];
        const double rsum = p.radius[i] + p.radius[j];
        unsigned char& c = slot_class[k - k0];
        if ((p.x[j] - p.x[i]).squaredNorm() >= rsum * rsum) {
          c = kFar;
          apart(k);
          if (!l.memory[k].empty()) l.memory[k] = ShapedContactMemory{};
        } else if (p.is_ellipsoid(i) || p.is_ellipsoid(j)) {
          // The serial loop's geometry with lo as body i: every rank holding the pair computes
          // the same normal (lo to hi), memory and kinematics.
          c = kShaped;
          ShapedPair sp;
          sp.i = static_cast<std::size_t>(i);
          sp.j = static_cast<std::size_t>(j);
          sp.memory = &l.memory[k];
          shaped_pairs.push_back(sp);
        } else {
          c = kSpheres;
        }
      }
      if (!shaped_pairs.empty()) shaped_pair_geometries(*in.posed, shaped_pairs, *in.solver_stats);
    }
    for (std::size_t k = k0; k < k1; ++k) {
      const int i = l.lo[k];
      const int j = l.hi[k];
      const double ri = p.radius[i];
      const double rj = p.radius[j];
      ContactKinematics kin;
      double arm_i = 0.0, arm_j = 0.0;  // sphere pairs: lever lengths along the normal
      bool shaped = false;
      if constexpr (Shapes) {
        const unsigned char c = slot_class[k - k0];
        if (c == kFar) continue;
        shaped = c == kShaped;
      }
      if (shaped) {
        const ShapedPair& sp = shaped_pairs[shaped_next++];
        if (!sp.touching) {
          apart(k);
          continue;
        }
        sp.kinematics(kin, cp.r_star);
      } else {
        const Vec3 d = p.x[j] - p.x[i];
        const double rsum = ri + rj;
        const double dist2 = d.squaredNorm();
        if constexpr (!Shapes) {
          if (dist2 >= rsum * rsum) {
            apart(k);
            continue;
          }
        }
        sphere_pair_kinematics(d, dist2, ri, rj, kin, arm_i, arm_j, cp.r_star);
      }
      const double delta = kin.overlap;
      kin.v_i = p.v[i];
      kin.v_j = p.v[j];
      if constexpr (kRotation) {
        kin.omega_i = p.omega[i];
        kin.omega_j = p.omega[j];
      }
      cp.m_star = 1.0 / (p.inv_mass[i] + p.inv_mass[j]);
      TangentialSpring& spring = E::friction ? l.spring[k] : dummy_spring;
      ContactEnergy ce;
      const ContactForce cf =
          contact_response<E::friction, E::damping, kRotation, E::energy>(cp, kin, spring, ce);
      l.touching[k] = 1;
      l.force[k] = cf.on_i;
      if constexpr (E::energy) {
        l.elastic_normal[k] = ce.elastic_normal;
        l.elastic_tangential[k] = ce.elastic_tangential;
        if constexpr (kDampingWork) l.damping_on_lo[k] = -cf.damping * kin.normal;
        if constexpr (kDampingWork && Shapes) {
          l.damping_torque_lo[k] = -kin.lever_i.cross(cf.damping * kin.normal);
          l.damping_torque_hi[k] = kin.lever_j.cross(cf.damping * kin.normal);
        }
        if (i < n_owned) {
          out.dissipated.dissipated_damping += ce.dissipated_damping;
          out.dissipated.dissipated_friction += ce.dissipated_friction;
          out.dissipated.tangential_stiffness_change += ce.tangential_stiffness_change;
        }
      }
      if constexpr (Record) in.record->push_back({i, j, p.x[i] + kin.lever_i, cf.on_i});
      if constexpr (kRotation) {
        if (shaped) {
          l.torque_lo[k] = kin.lever_i.cross(cf.on_i);
          l.torque_hi[k] = -kin.lever_j.cross(cf.on_i);
        } else {
          const Vec3 arm_x_f = kin.normal.cross(cf.on_i);
          l.torque_lo[k] = arm_i * arm_x_f;
          l.torque_hi[k] = arm_j * arm_x_f;
        }
      }
      if (i < n_owned) ++out.pair_contacts;
      const double r_min = Shapes ? std::min(p.min_semi_axis(i), p.min_semi_axis(j)) : std::min(ri, rj);
      if (delta > max_ratio * r_min) max_ratio = delta / r_min;
    }
  }
  out.max_overlap_ratio = max_ratio;

  // 3. Segmented sum: each owned particle adds its slots in the order of its row, the
  //    partners' global ids.
  for (int i = 0; i < n_owned; ++i) {
    Vec3 f = p.force[i];
    Vec3 t = Vec3::Zero();
    if constexpr (kRotation) t = p.torque[i];
    [[maybe_unused]] double en = 0.0, et = 0.0;
    [[maybe_unused]] Vec3 fd = Vec3::Zero(), td = Vec3::Zero();
    if constexpr (E::energy) {
      en = in.energy->elastic_normal[i];
      et = in.energy->elastic_tangential[i];
    }
    if constexpr (kDampingWork) fd = in.energy->damping_force[i];
    if constexpr (kDampingWork && Shapes) td = in.energy->damping_torque[i];
    for (int r = l.row_start[i]; r < l.row_start[i + 1]; ++r) {
      const int e = l.row[r];
      const int k = e >> 1;
      if (!l.touching[k]) continue;
      if (e & 1) {
        f -= l.force[k];
        if constexpr (kRotation) t += l.torque_hi[k];
        if constexpr (kDampingWork) fd -= l.damping_on_lo[k];
        if constexpr (kDampingWork && Shapes) td += l.damping_torque_hi[k];
      } else {
        f += l.force[k];
        if constexpr (kRotation) t += l.torque_lo[k];
        if constexpr (kDampingWork && Shapes) td += l.damping_torque_lo[k];
        if constexpr (E::energy) {
          en += l.elastic_normal[k];
          et += l.elastic_tangential[k];
        }
        if constexpr (kDampingWork) fd += l.damping_on_lo[k];
      }
    }
    if constexpr (E::energy) {
      in.energy->elastic_normal[i] = en;
      in.energy->elastic_tangential[i] = et;
    }
    if constexpr (kDampingWork) in.energy->damping_force[i] = fd;
    if constexpr (kDampingWork && Shapes) in.energy->damping_torque[i] = td;
    p.force[i] = f;
    if constexpr (kRotation) p.torque[i] = t;
  }
  return out;
}

}  // namespace

DeterministicForceKernels select_deterministic_forces(const EffectSet& e, bool shapes) {
  if (shapes) {
    return with_effects(e, []<class E>() {
      return DeterministicForceKernels{&compute<E, false, true>, &compute<E, true, true>};
    });
  }
  return with_effects(e, []<class E>() {
    return DeterministicForceKernels{&compute<E, false, false>, &compute<E, true, false>};
  });
}

}  // namespace upgrain::dem
