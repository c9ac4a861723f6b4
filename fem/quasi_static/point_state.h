#pragma once
// The material at one quadrature point of a quasi-static continuum solved by Newton's method
// (docs/femxdem.md): a state that answers a trial displacement gradient with a stress and a
// tangent, always from its last converged state, and keeps the answer only when the global
// iteration converges (commit). The elastic stand-ins (fem/quasi_static/elastic_point.h) and the
// DEM cell of FEM x DEM (docs/femxdem.md) are such states; the solver holds one per point in
// deal.II's CellDataStorage, as step-18 and step-42 hold their quadrature-point histories.
//
// Small strain: the trial is the total displacement gradient H = grad u from the reference
// configuration (3 x 3; a plane-strain problem in x-y passes zeros in the z row and column), the
// strain its symmetric part. A state may use the whole of H (a DEM cell deforms by F = 1 + H);
// the stress it returns is the Cauchy stress in the solver's frame. Plain C++ and Eigen.
#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/plasticity/mandel.h"

namespace upgrain::fem {

struct PointResponse {
  Vec6 stress = Vec6::Zero();   // sigma, tension positive (Pa), Mandel (mandel.h)
  Mat6 tangent = Mat6::Zero();  // d sigma / d eps in Mandel notation: what Newton's matrix uses
  bool converged = true;        // false: the point could not reach its answer (a cap)
  std::string failure;          // why not, in words, when !converged
  double cost = 0.0;            // work spent on this answer (DEM grain-steps; 0 for a closed form)
};

// Where a point is: its cell (deal.II's id, "level_index"), its index in the cell, its position.
struct PointPlace {
  std::string cell;
  unsigned index = 0;
  std::array<double, 3> position{};
};

// A scalar of a point's committed state, written beside its stress (a DEM cell's solid fraction).
struct PointMeasure {
  std::string name;
  double value = 0.0;
};

class PointState {
 public:
  virtual ~PointState() = default;
  // Called once on a point that starts a run afresh, before anything else is asked of it, and
  // never on one that is then loaded from its bytes (a restart, a move to another rank): the
  // place for a costly set-up that a loaded point does without (a DEM cell's preparation). It
  // may throw; the solver stops every rank with the first rank's words.
  virtual void start() {}
  // The response to the total displacement gradient `h`, from the last committed state; the
  // state keeps it as its trial.
  virtual PointResponse respond(const Mat3x3& h) = 0;
  // The last trial becomes the committed state.
  virtual void commit() = 0;
  // An independent copy (committed state and trial).
  [[nodiscard]] virtual std::unique_ptr<PointState> clone() const = 0;
  // Scalars of the committed state for the output: the same names in the same order for every
  // point of a problem. None by default.
  [[nodiscard]] virtual std::vector<PointMeasure> measures() const { return {}; }
  // The mass per unit reference volume that the body force acts on (kg/m^3), when the state has
  // one of its own (a DEM cell: its grains' mass over its reference cell's volume); none: the
  // problem's (QuasiStaticProblem::density).
  [[nodiscard]] virtual std::optional<double> density() const { return std::nullopt; }
  // The committed state as bytes, every bit kept, and back into a point that the same factory
  // made at the same place: a point that moves to another rank when the mesh is repartitioned by
  // cost. A trial in progress is not kept. A state that cannot do this says so when it is asked.
  [[nodiscard]] virtual std::vector<char> save() const {
    throw std::logic_error("this material cannot be moved to another rank (PointState::save)");
  }
  virtual void load(const std::vector<char>& /*bytes*/) {
    throw std::logic_error("this material cannot be moved to another rank (PointState::load)");
  }
};

}  // namespace upgrain::fem
