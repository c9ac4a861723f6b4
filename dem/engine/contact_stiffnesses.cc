#include "dem/engine/contact_stiffnesses.h"

#include "dem/contact/contact_laws.h"
#include "dem/contact/geometry/sphere_pair.h"
#include "dem/core/error.h"

namespace upgrain::dem {

std::vector<ContactStiffness> contact_stiffnesses(const Simulation& sim) {
  if (!sim.contacts_recorded())
    throw Error(
        "the contact stiffnesses need a step that recorded its contacts (Simulation::request_contacts)");
  const ParticleStore& p = sim.particles();
  if (p.has_shapes())
    throw Error("the contact-stiffness tangent takes spheres only; the grains have shapes (ellipsoids)");
  const SceneConfig& scene = sim.scene();
  const LawConstants constants =
      find_contact_law(scene.contact_law).constants(scene.particles.material, scene.law_parameters);
  std::vector<ContactStiffness> out;
  out.reserve(sim.contacts().size());
  with_contact_law(scene.contact_law, [&]<class Law>() {
    const auto& pair = constants_of<Law>(constants).pair;
    for (const ContactSample& c : sim.contacts()) {
      if (c.with_wall() || c.a >= sim.owned()) continue;
      const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
      const Vec3 d = p.x[b] - p.x[a];
      ContactKinematics kin;
      const SpherePairArms arms = sphere_pair_kinematics(d, d.squaredNorm(), p.radius[a], p.radius[b], kin);
      if (!(kin.overlap > 0.0)) continue;  // recorded at first touch, no spring yet
      ContactParameters cp;
      cp.r_star = arms.r_star;
      const NormalResponse r = Law::Normal::response(pair, cp, kin.overlap);
      out.push_back({d, kin.normal, r.stiffness, r.tangential_stiffness});
    }
  });
  return out;
}

}  // namespace upgrain::dem
