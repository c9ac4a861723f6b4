#include "coupling/femxdem/rve_point.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "coupling/femxdem/cell_increment.h"
#include "coupling/femxdem/held_cell.h"
#include "coupling/femxdem/rve_tangent.h"
#include "coupling/run/stop_request.h"
#include "coupling/studies/element/element_cell.h"
#include "dem/core/error.h"
#include "dem/io/hdf5_snapshot.h"
#include "dem/parallel/byte_stream.h"

namespace upgrain::coupling {

namespace {

// The grains' mean angular velocity about z (rad/s).
double mean_spin_z(const dem::Simulation& sim) {
  double sum = 0.0;
  for (int i = 0; i < sim.owned(); ++i) sum += sim.particles().omega[i].z();
  return sim.owned() > 0 ? sum / sim.owned() : 0.0;
}

// The first word of a cell's bytes: their layout's name and version, so that bytes of another
// layout (an older checkpoint) are refused by name instead of being misread.
constexpr std::uint64_t kCellBytesTag = 0x55706772524556'02ull;  // "UpgrREV", layout 2

void put(dem::ByteWriter& w, const dem::Mat3& m) {
  for (int k = 0; k < 9; ++k) w.put(m.data()[k]);
}
void get(dem::ByteReader& r, dem::Mat3& m) {
  for (int k = 0; k < 9; ++k) r.get(m.data()[k]);
}

// How often a trial looks at the stop request (a flag read: nothing against a step's cost), and
// what a dropped trial answers.
constexpr long kStopCheckEvery = 64;
constexpr const char* kDropped = "the trial was dropped: the run was asked to stop";

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

}  // namespace

RveCell::RveCell(std::shared_ptr<const RveTemplate> prepared, const RveOptions& o)
    : source_{[prepared] { return prepared; }, [prepared] { return prepared; }}, options_(o) {
  start();
}

RveCell::RveCell(RveSource source, const RveOptions& o) : source_(std::move(source)), options_(o) {}

void RveCell::start() {
  prepared_ = source_.prepared();
  committed_ = prepared_->state;
  committed_h_ = fem::Mat3x3::Zero();
  committed_record_ = {};
  committed_record_.unbalanced_force = prepared_->unbalanced_force;
  committed_record_.contacts = prepared_->contacts;
  committed_record_.cell = prepared_->reference_cell;
  trial_.reset();
}

const RveTemplate& RveCell::packing() const {
  if (!prepared_) throw std::logic_error("the DEM cell was asked before it was started or loaded");
  return *prepared_;
}

RveCell::Trial RveCell::run_trial(const fem::Mat3x3& h) const {
  const RveTemplate& prepared = packing();
  const CellFactor f = upper_triangular_factor(fem::Mat3x3::Identity() + h);
  check_one_tilt(f.stretch);
  const dem::Mat3 target = f.stretch * prepared.reference_cell;
  const double dt = prepared.scene.time_step;
  const long n = increment_steps(h - committed_h_, options_);
  const dem::Mat3 l = increment_velocity_gradient(committed_record_.cell, target, n, dt);
  dem::CellMotion m;
  m.axis = {cell_rate(l(0, 0)), cell_rate(l(1, 1)), cell_rate(l(2, 2))};
  m.shear = {{kTiltShear, kTiltGradient}, l(kTiltShear, kTiltGradient)};
  dem::SceneConfig scene = prepared.scene;
  dem::EngineState s = committed_;
  continue_under(scene, s, m);
  dem::Simulation sim(scene, s, MPI_COMM_SELF, prepared.engine);
  double rotation = committed_record_.grain_rotation;
  // A run asked to stop (coupling/run/stop_request.h) drops the trial within kStopCheckEvery steps:
  // the solver abandons the load step and saves the last converged one (docs/femxdem.md,
  // "Checkpoints and restart").
  struct Interrupted {};
  long stepped = 0;
  const auto turn = [&] {
    rotation += mean_spin_z(sim) * dt;
    if (++stepped % kStopCheckEvery == 0 && stop_signal() != 0) throw Interrupted{};
  };
  HeldCellRelaxation r;
  try {
    for (long k = 0; k < n; ++k) {
      sim.step();
      turn();
    }
    r = relax_held_cell(sim, options_.relaxation, options_.unbalanced_force_tolerance,
                        options_.relaxation_step_cap, turn);
  } catch (const Interrupted&) {
    Trial t;
    t.converged = false;
    t.interrupted = true;
    t.grain_steps = sim.particle_count() * stepped;
    return t;
  }
  Trial t;
  t.h = h;
  t.record = {n,       r.steps, r.unbalanced_force, sim.diagnostics().particle_contacts, sim.cell_matrix(),
              rotation};
  t.converged = r.converged;
  t.grain_steps = sim.particle_count() * (n + r.steps);
  // The stress of the cell R h0, turned back into the solver's frame: that of F h0.
  const dem::Mat3 sigma = f.rotation * sim.cell_stress() * f.rotation.transpose();
  t.stress = fem::mandel::from_matrix(0.5 * (sigma + sigma.transpose()));
  t.contact_tangent = contact_tangent(sim, f.rotation);
  t.state = sim.capture_state();
  return t;
}

fem::PointResponse RveCell::respond(const fem::Mat3x3& h) {
  Trial t = run_trial(h);
  fem::PointResponse out;
  out.stress = t.stress;
  out.cost = static_cast<double>(t.grain_steps);
  std::string failure;
  if (t.interrupted) {
    out.converged = false;
    out.failure = kDropped;
    return out;
  }
  if (!t.converged)
    failure = "the DEM cell did not relax: unbalanced-force ratio " + number(t.record.unbalanced_force) +
              " above the tolerance " + number(options_.unbalanced_force_tolerance) + " after the cap of " +
              std::to_string(options_.relaxation_step_cap) + " relaxation steps";
  switch (options_.tangent) {
    case RveTangent::contact_stiffness:
      out.tangent = t.contact_tangent;
      break;
    case RveTangent::elastic:
      out.tangent = packing().elastic_tangent;
      break;
    case RveTangent::perturbation: {
      // Forward differences in the strain components the cell can take (xx, yy, zz, xy); the
      // out-of-plane shears xz and yz would tilt the cell across z (refused), so their columns
      // are the trial's contact-stiffness tangent's.
      out.tangent = t.contact_tangent;
      const double e = options_.perturbation;
      for (int k = 0; k < 4; ++k) {
        const Trial p = run_trial(h + e * fem::mandel::to_matrix(fem::Vec6::Unit(k)));
        if (p.interrupted) {
          out.converged = false;
          out.failure = kDropped;
          return out;
        }
        out.tangent.col(k) = (p.stress - t.stress) / e;
        out.cost += static_cast<double>(p.grain_steps);
        if (!p.converged && failure.empty())
          failure = "the DEM cell did not relax in the perturbation of strain component " +
                    std::to_string(k) + ": unbalanced-force ratio " + number(p.record.unbalanced_force) +
                    " after the cap of " + std::to_string(options_.relaxation_step_cap) + " relaxation steps";
      }
      break;
    }
  }
  out.converged = failure.empty();
  out.failure = failure;
  record_ = t.record;
  trial_ = std::move(t);
  return out;
}

void RveCell::commit() {
  if (!trial_) return;
  committed_ = trial_->state;
  committed_h_ = trial_->h;
  committed_record_ = trial_->record;
}

std::vector<fem::PointMeasure> RveCell::measures() const {
  const RveTrialRecord& r = committed_record_;
  const RveTemplate& prepared = packing();
  return {{"solid_fraction", prepared.grain_volume / std::abs(r.cell.determinant())},
          {"coordination", 2.0 * static_cast<double>(r.contacts) / static_cast<double>(prepared.grains)},
          {"grain_rotation", r.grain_rotation},
          {"held_steps", static_cast<double>(r.relaxation_steps)},
          {"unbalanced_force", r.unbalanced_force}};
}

std::optional<double> RveCell::density() const {
  const RveTemplate& prepared = packing();
  return prepared.grain_mass / std::abs(prepared.reference_cell.determinant());
}

std::vector<char> RveCell::save() const {
  const RveTemplate& prepared = packing();
  dem::ByteWriter w;
  w.put(kCellBytesTag);
  put(w, prepared.reference_cell);
  w.put(prepared.grain_volume);
  for (int k = 0; k < 36; ++k) w.put(prepared.elastic_tangent.data()[k]);
  w.put(dem::to_bytes(committed_));
  put(w, committed_h_);
  const RveTrialRecord& r = committed_record_;
  w.put(r.increment_steps);
  w.put(r.relaxation_steps);
  w.put(r.unbalanced_force);
  w.put(r.contacts);
  put(w, r.cell);
  w.put(r.grain_rotation);
  return std::move(w.bytes());
}

void RveCell::load(const std::vector<char>& bytes) {
  dem::ByteReader reader(bytes);
  std::uint64_t tag = 0;
  reader.get(tag);
  if (tag != kCellBytesTag)
    throw Error(
        "the DEM cell's saved bytes are of another layout (a checkpoint of another version of "
        "Upgrain); continue that run with the version that wrote it");
  // The frame (scene, engine, grains) from the source, the rest of the packing from the bytes: a
  // loaded cell is not prepared again. The frame's own state (its unprepared fill) is not kept.
  auto t = std::make_shared<RveTemplate>(*source_.frame());
  t->state = {};
  get(reader, t->reference_cell);
  reader.get(t->grain_volume);
  for (int k = 0; k < 36; ++k) reader.get(t->elastic_tangent.data()[k]);
  prepared_ = std::move(t);
  std::vector<char> state;
  reader.get(state);
  committed_ = dem::from_bytes(state);
  get(reader, committed_h_);
  RveTrialRecord& r = committed_record_;
  reader.get(r.increment_steps);
  reader.get(r.relaxation_steps);
  reader.get(r.unbalanced_force);
  reader.get(r.contacts);
  get(reader, r.cell);
  reader.get(r.grain_rotation);
  record_ = r;
  trial_.reset();
}

void RveCell::write_snapshot(const std::filesystem::path& file, double time, long step) const {
  dem::io::write_snapshot(file, committed_.particles, {}, {}, time, step, /*images=*/true);
}

std::unique_ptr<fem::PointState> RveCell::clone() const { return std::make_unique<RveCell>(*this); }

}  // namespace upgrain::coupling
