#include "dem/io/engine_state_file.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/engine/wall_columns.h"
#include "dem/shape/grain_shapes.h"

namespace upgrain::dem::io {

namespace {

using hdf5::Handle;
using hdf5::write_attribute;
using hdf5::write_dataset;
using hdf5::write_vectors;

// Values per contact-history record: 13 in version 1, and the twisting spring's two after them
// in version 2 (a version-1 file reads with no twist).
constexpr int kHistoryValues = 15;
int history_values(int version) { return version == 1 ? 13 : kHistoryValues; }

// The initial energy's terms, by name (EnergyBalance, dem/engine/energy.h).
struct EnergyTerm {
  const char* name;
  double EnergyBalance::*value;
};
constexpr EnergyTerm kEnergyTerms[] = {
    {"kinetic_translational", &EnergyBalance::kinetic_translational},
    {"kinetic_rotational", &EnergyBalance::kinetic_rotational},
    {"potential", &EnergyBalance::potential},
    {"elastic_normal", &EnergyBalance::elastic_normal},
    {"elastic_tangential", &EnergyBalance::elastic_tangential},
    {"dissipated_damping", &EnergyBalance::dissipated_damping},
    {"dissipated_friction", &EnergyBalance::dissipated_friction},
    {"tangential_stiffness_change", &EnergyBalance::tangential_stiffness_change},
    {"elastic_rolling", &EnergyBalance::elastic_rolling},
    {"dissipated_rolling", &EnergyBalance::dissipated_rolling},
    {"rolling_stiffness_change", &EnergyBalance::rolling_stiffness_change},
    {"removed_by_relaxation", &EnergyBalance::removed_by_relaxation},
    {"work_by_walls", &EnergyBalance::work_by_walls},
};

std::vector<double> flat(const std::vector<ElasticEnergy>& e) {
  std::vector<double> out;
  for (const ElasticEnergy& x : e) out.insert(out.end(), {x.normal, x.tangential, x.rolling});
  return out;
}
std::vector<double> flat(const std::vector<DissipatedEnergy>& d) {
  std::vector<double> out;
  for (const DissipatedEnergy& x : d)
    out.insert(out.end(), {x.damping, x.friction, x.stiffness_change, x.rolling, x.rolling_stiffness_change,
                           x.wall_work});
  return out;
}

void write_particles(hid_t parent, const EngineState& s) {
  Handle g(hdf5::create_group(parent, "particles"), H5Gclose, "create group particles");
  const ParticleStore& p = s.particles;
  const hsize_t n = p.size();
  write_dataset(g, "id", p.id.data(), n);
  write_dataset(g, "radius", p.radius.data(), n);
  write_dataset(g, "inv_mass", p.inv_mass.data(), n);
  write_dataset(g, "inv_inertia", p.inv_inertia.data(), n);
  write_vectors(g, "x", p.x);
  write_vectors(g, "v", p.v);
  write_vectors(g, "omega", p.omega);
  write_vectors(g, "force", p.force);
  write_vectors(g, "torque", p.torque);
  write_vectors(g, "positions_at_build", s.positions_at_build);
  // The image counters of a periodic cell (docs/periodic.md); a bounded box writes none.
  if (s.domain.periodic[0] || s.domain.periodic[1] || s.domain.periodic[2]) {
    std::vector<std::int32_t> image(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) image[3 * i + d] = p.image[i][d];
    write_dataset(g, "image", image.data(), n, 3);
  }
  if (p.has_shapes()) {
    std::vector<std::int32_t> kind(n);
    std::vector<double> q(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      kind[i] = static_cast<std::int32_t>(p.shape[i]);
      const Eigen::Quaterniond& o = p.orientation[i];
      q[4 * i] = o.x(), q[4 * i + 1] = o.y(), q[4 * i + 2] = o.z(), q[4 * i + 3] = o.w();
    }
    write_dataset(g, "shape", kind.data(), n);
    for (const shapes::DescriptionColumn& c : shapes::description_columns())
      write_vectors(g, c.name, p.*c.values);
    write_dataset(g, "orientation", q.data(), n, 4);
    write_vectors(g, "inertia_body", p.inertia_body);
  }
  if (!s.damping_force.empty()) write_vectors(g, "damping_force", s.damping_force);
  if (!s.damping_torque.empty()) write_vectors(g, "damping_torque", s.damping_torque);
  if (!s.rolling_damping_torque.empty()) write_vectors(g, "rolling_damping_torque", s.rolling_damping_torque);
  if (!s.particle_elastic.empty()) {
    write_dataset(g, "elastic", flat(s.particle_elastic).data(), n, 3);
    write_dataset(g, "dissipation_share", flat(s.dissipation_share).data(), n, 6);
  }
}

void write_history(hid_t parent, const std::vector<ContactHistoryRecord>& records) {
  Handle g(hdf5::create_group(parent, "history"), H5Gclose, "create group history");
  const hsize_t n = records.size();
  std::vector<std::int64_t> a(n), b(n);
  std::vector<double> v(kHistoryValues * n);
  for (std::size_t k = 0; k < n; ++k) {
    const ContactHistoryRecord& r = records[k];
    a[k] = r.a;
    b[k] = r.b;
    double* x = v.data() + kHistoryValues * k;
    std::copy(r.tangential_force, r.tangential_force + 3, x);
    x[3] = r.tangential_stiffness;
    std::copy(r.rolling_torque, r.rolling_torque + 3, x + 4);
    x[7] = r.rolling_stiffness;
    std::copy(r.normal, r.normal + 3, x + 8);
    x[11] = r.r_star;
    x[12] = r.gap_budget;
    x[13] = r.twisting_torque;
    x[14] = r.twisting_stiffness;
  }
  write_dataset(g, "a", a.data(), n);
  write_dataset(g, "b", b.data(), n);
  write_dataset(g, "values", v.data(), n, kHistoryValues);
}

// A column of the walls group (wall_columns.h): the names as a text-list attribute, the rest as
// datasets.
void write_column(hid_t g, const char* name, const std::vector<std::string>& c) {
  write_attribute(g, name, c);
}
void write_column(hid_t g, const char* name, const std::vector<Vec3>& c) { write_vectors(g, name, c); }
void write_column(hid_t g, const char* name, const std::vector<double>& c) {
  write_dataset(g, name, c.data(), c.size());
}

void read_column(const hdf5::Reader& in, const std::string& group, const char* name, std::size_t,
                 std::vector<std::string>& c) {
  c = in.text_list_attribute(name, group);
}
void read_column(const hdf5::Reader& in, const std::string& group, const char* name, std::size_t,
                 std::vector<Vec3>& c) {
  c = in.read_vectors(group + "/" + name);
}
void read_column(const hdf5::Reader& in, const std::string& group, const char* name, std::size_t walls,
                 std::vector<double>& c) {
  c = in.read<double>(group + "/" + name, H5T_NATIVE_DOUBLE, walls);
}

void write_walls(hid_t parent, const EngineState& s) {
  Handle g(hdf5::create_group(parent, "walls"), H5Gclose, "create group walls");
  const WallColumns walls = wall_columns(s);
  WallColumns::each(walls, [&](const char* name, const auto& column) { write_column(g, name, column); });
}

void write_domain(hid_t parent, const DomainState& d) {
  Handle g(hdf5::create_group(parent, "domain"), H5Gclose, "create group domain");
  write_vectors(g, "box", {d.box.lo, d.box.hi});
  const std::int32_t blocks[3] = {d.blocks[0], d.blocks[1], d.blocks[2]};
  write_dataset(g, "blocks", blocks, 3);
  const char* names[3] = {"planes_x", "planes_y", "planes_z"};
  for (int a = 0; a < 3; ++a) write_dataset(g, names[a], d.planes[a].data(), d.planes[a].size());
  if (d.periodic[0] || d.periodic[1] || d.periodic[2]) {
    const std::int32_t periodic[3] = {d.periodic[0], d.periodic[1], d.periodic[2]};
    write_dataset(g, "periodic", periodic, 3);
  }
  const double balance[4] = {static_cast<double>(d.balance.count), static_cast<double>(d.balance.last_step),
                             d.balance.before, d.balance.after};
  write_dataset(g, "balance", balance, 4);
}

}  // namespace

void write_engine_state(hid_t parent, const std::string& group, const EngineState& s) {
  Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  write_attribute(g, "version", static_cast<double>(EngineState::kVersion));
  write_attribute(g, "history_version", static_cast<double>(ContactHistoryRecord::kVersion));
  write_attribute(g, "step", static_cast<double>(s.step));
  write_attribute(g, "pair_contacts", static_cast<double>(s.pair_contacts));
  write_attribute(g, "wall_contacts", static_cast<double>(s.wall_contacts));
  write_vectors(g, "wall_forces", s.wall_forces);
  write_vectors(g, "wall_damping_forces", s.wall_damping_forces);
  write_attribute(g, "rebuilds", static_cast<double>(s.rebuilds));
  write_attribute(g, "rebuild_pending", s.rebuild_pending ? 1.0 : 0.0);
  write_attribute(g, "last_overlap_ratio", s.last_overlap_ratio);
  write_attribute(g, "last_overlap_step", static_cast<double>(s.last_overlap_step));
  write_attribute(g, "removed_by_relaxation", s.removed_by_relaxation);
  write_attribute(g, "reference_mass", s.reference_mass);
  write_attribute(g, "next_balance_step", static_cast<double>(s.domain.next_balance_step));
  for (const EnergyTerm& t : kEnergyTerms)
    write_attribute(g, (std::string("initial_") + t.name).c_str(), s.initial_energy.*t.value);
  write_vectors(g, "gravity", {s.gravity});
  std::vector<std::int64_t> digits;
  for (const auto& channel : s.dissipated) digits.insert(digits.end(), channel.begin(), channel.end());
  write_dataset(g, "dissipated", digits.data(), s.dissipated.size(), ExactSum::kDigits + 1);
  static_assert(sizeof(ContactSolverStats) == 9 * sizeof(std::int64_t));
  write_dataset(g, "solver_stats", reinterpret_cast<const std::int64_t*>(&s.solver_stats), 9);
  write_particles(g, s);
  write_history(g, s.history);
  write_walls(g, s);
  write_domain(g, s.domain);
  // A deforming cell (docs/periodic.md, "A cell that deforms"): one row, CellRecord's order.
  if (s.cell.deforming) {
    const auto cell = s.cell.values();
    write_dataset(g, "cell", cell.data(), cell.size());
    if (s.cell.shear.any()) {
      const auto shear = s.cell.shear_values();
      write_dataset(g, "cell_shear", shear.data(), shear.size());
    }
  }
}

EngineState read_engine_state(const hdf5::Reader& in, const std::string& group) {
  EngineState s;
  const double version = in.attribute("version", group);
  if (version != EngineState::kVersion)
    throw Error(in.where() + "engine state version " + std::to_string(version) + ", this build reads " +
                std::to_string(EngineState::kVersion));
  const double history_version = in.attribute("history_version", group);
  if (history_version != 1 && history_version != ContactHistoryRecord::kVersion)
    throw Error(in.where() + "contact-history records of another version");
  auto whole = [&](const char* name) { return in.whole_attribute(name, group); };
  s.step = whole("step");
  s.pair_contacts = whole("pair_contacts");
  s.wall_contacts = whole("wall_contacts");
  s.wall_forces = in.read_vectors(group + "/wall_forces");
  s.wall_damping_forces = in.read_vectors(group + "/wall_damping_forces");
  s.rebuilds = whole("rebuilds");
  s.rebuild_pending = in.attribute("rebuild_pending", group) != 0.0;
  s.last_overlap_ratio = in.attribute("last_overlap_ratio", group);
  s.last_overlap_step = whole("last_overlap_step");
  s.removed_by_relaxation = in.attribute("removed_by_relaxation", group);
  s.reference_mass = in.attribute("reference_mass", group);
  s.domain.next_balance_step = whole("next_balance_step");
  for (const EnergyTerm& t : kEnergyTerms)
    s.initial_energy.*t.value = in.attribute((std::string("initial_") + t.name).c_str(), group);
  const std::vector<Vec3> gravity = in.read_vectors(group + "/gravity");
  if (gravity.size() != 1) throw Error(in.where() + group + "/gravity is not one vector");
  s.gravity = gravity[0];
  const std::vector<std::int64_t> digits = in.read<std::int64_t>(group + "/dissipated", H5T_NATIVE_INT64,
                                                                 s.dissipated.size(), ExactSum::kDigits + 1);
  for (std::size_t c = 0; c < s.dissipated.size(); ++c)
    std::copy(digits.begin() + c * (ExactSum::kDigits + 1),
              digits.begin() + (c + 1) * (ExactSum::kDigits + 1), s.dissipated[c].begin());
  const std::vector<std::int64_t> stats = in.read<std::int64_t>(group + "/solver_stats", H5T_NATIVE_INT64, 9);
  std::copy(stats.begin(), stats.end(), reinterpret_cast<std::int64_t*>(&s.solver_stats));
  if (in.exists(group + "/cell")) {
    const std::vector<double> v = in.read<double>(group + "/cell", H5T_NATIVE_DOUBLE, CellRecord::kValues);
    std::array<double, CellRecord::kValues> values{};
    std::copy(v.begin(), v.end(), values.begin());
    s.cell = CellRecord::from_values(values);
  }
  if (in.exists(group + "/cell_shear")) {
    const std::vector<double> v =
        in.read<double>(group + "/cell_shear", H5T_NATIVE_DOUBLE, CellRecord::kShearValues);
    std::array<double, CellRecord::kShearValues> values{};
    std::copy(v.begin(), v.end(), values.begin());
    s.cell.set_shear_values(values);
  }

  // Particles.
  const std::string pg = group + "/particles/";
  ParticleStore& p = s.particles;
  p.id = in.read_all<std::int64_t>(pg + "id");
  const hsize_t n = p.id.size();
  p.radius = in.read<double>(pg + "radius", H5T_NATIVE_DOUBLE, n);
  p.inv_mass = in.read<double>(pg + "inv_mass", H5T_NATIVE_DOUBLE, n);
  p.inv_inertia = in.read<double>(pg + "inv_inertia", H5T_NATIVE_DOUBLE, n);
  for (auto [name, field] : {std::pair{"x", &p.x},
                             {"v", &p.v},
                             {"omega", &p.omega},
                             {"force", &p.force},
                             {"torque", &p.torque},
                             {"positions_at_build", &s.positions_at_build}}) {
    *field = in.read_vectors(pg + name);
    if (field->size() != n) throw Error(in.where() + pg + name + " does not hold one row per particle");
  }
  p.image.assign(n, {0, 0, 0});
  if (in.exists(pg + "image")) {
    const std::vector<std::int32_t> image = in.read<std::int32_t>(pg + "image", H5T_NATIVE_INT32, n, 3);
    for (std::size_t i = 0; i < n; ++i) p.image[i] = {image[3 * i], image[3 * i + 1], image[3 * i + 2]};
  }
  if (in.exists(pg + "shape")) {
    const std::vector<std::int32_t> kind = in.read<std::int32_t>(pg + "shape", H5T_NATIVE_INT32, n);
    for (std::int32_t k : kind) {
      if (k < 0 || k >= kShapeKinds) throw Error(in.where() + "unknown shape kind " + std::to_string(k));
      p.shape.push_back(static_cast<ShapeKind>(k));
    }
    // Each shape's own description (dem/shape/shape_description.h).
    const auto columns = shapes::description_columns();
    for (const shapes::DescriptionColumn& c : columns) p.*c.values = in.read_vectors(pg + c.name);
    p.inertia_body = in.read_vectors(pg + "inertia_body");
    const std::vector<double> q = in.read<double>(pg + "orientation", H5T_NATIVE_DOUBLE, n, 4);
    for (std::size_t i = 0; i < n; ++i)
      p.orientation.emplace_back(q[4 * i + 3], q[4 * i], q[4 * i + 1], q[4 * i + 2]);
    if (p.inertia_body.size() != n ||
        std::ranges::any_of(columns, [&](const auto& c) { return (p.*c.values).size() != n; }))
      throw Error(in.where() + "shapes of another particle count");
  }
  s.damping_force = in.read_vectors(pg + "damping_force", true);
  s.damping_torque = in.read_vectors(pg + "damping_torque", true);
  s.rolling_damping_torque = in.read_vectors(pg + "rolling_damping_torque", true);
  if (in.exists(pg + "elastic")) {
    const std::vector<double> e = in.read<double>(pg + "elastic", H5T_NATIVE_DOUBLE, n, 3);
    const std::vector<double> d = in.read<double>(pg + "dissipation_share", H5T_NATIVE_DOUBLE, n, 6);
    for (std::size_t i = 0; i < n; ++i) {
      s.particle_elastic.push_back({e[3 * i], e[3 * i + 1], e[3 * i + 2]});
      s.dissipation_share.push_back(
          {d[6 * i], d[6 * i + 1], d[6 * i + 2], d[6 * i + 3], d[6 * i + 4], d[6 * i + 5]});
    }
  }
  if (!std::is_sorted(p.id.begin(), p.id.end()) || std::adjacent_find(p.id.begin(), p.id.end()) != p.id.end())
    throw Error(in.where() + "particle ids are not sorted and unique");

  // Histories.
  const std::string hg = group + "/history/";
  const std::vector<std::int64_t> a = in.read_all<std::int64_t>(hg + "a");
  const std::vector<std::int64_t> b = in.read<std::int64_t>(hg + "b", H5T_NATIVE_INT64, a.size());
  const int values = history_values(static_cast<int>(history_version));
  const std::vector<double> v = in.read<double>(hg + "values", H5T_NATIVE_DOUBLE, a.size(), values);
  s.history.resize(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ContactHistoryRecord& r = s.history[k];
    r.a = a[k];
    r.b = b[k];
    const double* x = v.data() + values * k;
    std::copy(x, x + 3, r.tangential_force);
    r.tangential_stiffness = x[3];
    std::copy(x + 4, x + 7, r.rolling_torque);
    r.rolling_stiffness = x[7];
    std::copy(x + 8, x + 11, r.normal);
    r.r_star = x[11];
    r.gap_budget = x[12];
    if (values > 13) {
      r.twisting_torque = x[13];
      r.twisting_stiffness = x[14];
    }
  }
  if (!std::is_sorted(s.history.begin(), s.history.end()))
    throw Error(in.where() + "contact histories are not sorted by key");

  // Walls.
  WallColumns walls;
  WallColumns::each(walls, [&](const char* name, auto& column) {
    read_column(in, group + "/walls", name, walls.names.size(), column);
  });
  set_walls(s, std::move(walls), in.where());

  // Domain.
  const std::string dg = group + "/domain/";
  const std::vector<Vec3> box = in.read_vectors(dg + "box");
  if (box.size() != 2) throw Error(in.where() + dg + "box is not two corners");
  s.domain.box = Box{box[0], box[1]};
  const std::vector<std::int32_t> blocks = in.read<std::int32_t>(dg + "blocks", H5T_NATIVE_INT32, 3);
  for (int d = 0; d < 3; ++d) s.domain.blocks[d] = blocks[d];
  const char* names3[3] = {"planes_x", "planes_y", "planes_z"};
  for (int d = 0; d < 3; ++d) s.domain.planes[d] = in.read_all<double>(dg + names3[d]);
  if (in.exists(dg + "periodic")) {
    const std::vector<std::int32_t> periodic = in.read<std::int32_t>(dg + "periodic", H5T_NATIVE_INT32, 3);
    for (int d = 0; d < 3; ++d) s.domain.periodic[d] = periodic[d] != 0;
  }
  const std::vector<double> balance = in.read<double>(dg + "balance", H5T_NATIVE_DOUBLE, 4);
  s.domain.balance = {in.whole(balance[0], dg + "balance[0]"), in.whole(balance[1], dg + "balance[1]"),
                      balance[2], balance[3]};
  return s;
}

}  // namespace upgrain::dem::io
