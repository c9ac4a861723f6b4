#pragma once
// What a DEM-vs-continuum study writes for people and for scripts (docs/study.md):
// report.md and study.json, from everything the study computed
// (coupling/studies/continuum/continuum_study.cc).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/studies/calibration/bed_calibration.h"
#include "coupling/studies/continuum/coarse_graining_study.h"
#include "coupling/studies/continuum/dem_fem_comparison.h"
#include "fem/analytic/janssen.h"
#include "fem/elastic_column.h"
#include "fem/frictional_column.h"

namespace upgrain::coupling {

// What rank 0's DEM run hands to every rank.
struct DemOutcome {
  dem::RegularGrid grid;
  dem::GridStress stress;
  double total_mass = 0.0;
  dem::Vec3 floor_force = dem::Vec3::Zero();
  double side_wall_vertical = 0.0;  // sum of the grains' vertical force on the side walls (N, < 0 = carried)
  // Per grid level: the side walls' mean upward shear on the grains (Pa, wall_shear_profile.h);
  // empty when the final step did not record its contacts.
  std::vector<double> wall_shear;
};

// One frictional continuum of the study and how it was solved.
struct FrictionalRun {
  ContinuumVariant variant;
  std::string key, label;  // as its ContinuumResult
  fem::FrictionalColumnProblem problem;
  fem::FrictionalColumnSolution solution;
};

struct StudyRecord {
  const SceneInput& in;
  const RunResult& run;
  const DemOutcome& dem;
  fem::ColumnProblem rollers_problem;  // the elastic column on rollers
  fem::ColumnSolution rollers;
  std::vector<FrictionalRun> frictional;
  std::vector<std::pair<std::string, std::string>> failed;  // continua whose Newton failed: label, why
  fem::JanssenColumn janssen;
  DemFemComparison comparison;
  std::vector<std::pair<std::string, double>> timings;  // stage, wall seconds on rank 0
  std::vector<std::string> plots, strain_plots;
  int ranks = 1;
  CoarseGrainingOutcome cg;  // the coarse-grained fields on the mesh, when the scene asks for them
  std::optional<BedCalibration> calibration;  // the study's own (Continuum/material from)
};

void write_report(const std::filesystem::path& folder, const StudyRecord& s);
void write_study_json(const std::filesystem::path& folder, const StudyRecord& s);

}  // namespace upgrain::coupling
