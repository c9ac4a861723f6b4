#pragma once
// The DEM cell at one quadrature point of FEM x DEM (Guo and Zhao 2014, IJNME 99, 789;
// docs/femxdem.md, "The DEM cell at a quadrature point"): a fully periodic cell of grains that
// answers a trial displacement gradient H (fem/quasi_static/point_state.h) with its Love-Weber
// stress and a tangent. Each trial starts from the committed engine state, deforms the cell from
// its committed shape to R h0 (F = 1 + H = Q R, coupling/femxdem/cell_increment.h) at a constant
// velocity gradient over the increment's steps, holds it still and relaxes it (held_cell.h); the
// stress is turned back by Q. Plane strain in x-y (and any stretch along z) only: a tilt of R
// other than (x, y) is refused (std::invalid_argument). The engine runs on MPI_COMM_SELF.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "coupling/femxdem/rve_options.h"
#include "coupling/femxdem/rve_preparation.h"
#include "fem/quasi_static/point_state.h"

namespace upgrain::coupling {

// What a trial cost and reached besides the response (for the solver's account and the tests).
struct RveTrialRecord {
  long increment_steps = 0;   // the steps of the deformation
  long relaxation_steps = 0;  // the held cell's
  double unbalanced_force = 0.0;
  long contacts = 0;
  dem::Mat3 cell = dem::Mat3::Zero();  // the cell matrix reached
  // The grains' mean rotation about z since the preparation (rad, counter-clockwise positive):
  // their spin integrated over every step of the committed trials and this one.
  double grain_rotation = 0.0;
};

// Where a cell gets its packing (coupling/femxdem/rve_packings.h): prepared (the servo run) when
// it starts a run, or only its frame (rve_frame(): scene, engine, grains) when it is loaded from
// its bytes, which carry the rest.
struct RveSource {
  std::function<std::shared_ptr<const RveTemplate>()> prepared;
  std::function<std::shared_ptr<const RveTemplate>()> frame;
};

class RveCell : public fem::PointState {
 public:
  // A copy of the prepared cell, its committed H zero. The template is shared, read only.
  RveCell(std::shared_ptr<const RveTemplate> prepared, const RveOptions& o);
  // A cell that takes its packing from `source` when it is started or loaded (nothing before).
  RveCell(RveSource source, const RveOptions& o);

  // Takes the prepared packing (a cell made from a template already has it).
  void start() override;
  fem::PointResponse respond(const fem::Mat3x3& h) override;
  void commit() override;
  [[nodiscard]] std::unique_ptr<fem::PointState> clone() const override;
  // Of the committed cell: solid_fraction (the grains' volume over the cell's), coordination
  // (2 touching pairs per grain), grain_rotation (RveTrialRecord), held_steps and
  // unbalanced_force (of its last trial's relaxation).
  [[nodiscard]] std::vector<fem::PointMeasure> measures() const override;
  // The grains' mass over the prepared cell's volume: the density of the continuum at its point.
  [[nodiscard]] std::optional<double> density() const override;
  // The committed engine state (dem::to_bytes), H and trial record, and what the cell keeps of its
  // packing besides its frame (the reference cell, the grains' volume, the elastic tangent);
  // load() into a cell of the same source or template and options continues with the same bits,
  // without preparing the packing again.
  [[nodiscard]] std::vector<char> save() const override;
  void load(const std::vector<char>& bytes) override;
  // The committed cell's grains as an HDF5 snapshot for ParaView (dem/io/hdf5_snapshot.h: ids,
  // radii, positions, velocities, forces and the periodic images), in the cell's own frame: the
  // stretch R of F = QR, without the rotation Q.
  void write_snapshot(const std::filesystem::path& file, double time, long step) const;

  // The last respond()'s main trial (not the perturbations').
  [[nodiscard]] const RveTrialRecord& last_trial() const { return record_; }
  [[nodiscard]] const fem::Mat3x3& committed_displacement_gradient() const { return committed_h_; }

 private:
  struct Trial {
    dem::EngineState state;
    fem::Mat3x3 h = fem::Mat3x3::Zero();
    fem::Vec6 stress = fem::Vec6::Zero();
    fem::Mat6 contact_tangent = fem::Mat6::Zero();
    RveTrialRecord record;
    bool converged = true;
    bool interrupted = false;  // dropped because the run was asked to stop
    long grain_steps = 0;
  };
  // A trial from the committed state, without keeping it.
  [[nodiscard]] Trial run_trial(const fem::Mat3x3& h) const;

  // The packing, once started or loaded; throws std::logic_error before.
  [[nodiscard]] const RveTemplate& packing() const;

  RveSource source_;
  std::shared_ptr<const RveTemplate> prepared_;
  RveOptions options_;
  dem::EngineState committed_;
  fem::Mat3x3 committed_h_ = fem::Mat3x3::Zero();
  RveTrialRecord committed_record_;  // the committed trial's (the prepared cell's at first)
  std::optional<Trial> trial_;
  RveTrialRecord record_;
};

}  // namespace upgrain::coupling
