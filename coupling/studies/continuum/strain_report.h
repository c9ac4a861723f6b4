#pragma once
// The "Strain" section of report.md (docs/strain.md): what the run's grid strain is
// relative to, per definition the share of valid cells and the spread of ln J and the
// equivalent shear strain at the last output, and the plots of plot_strain.py (ln J and
// gamma_eq per cell against time, a map of the final state). For a run without the
// continuum study, report.md holds a short account of the run and this section.
#include <filesystem>
#include <string>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/run/scene_run.h"

namespace upgrain::coupling {

// Runs plot_strain.py on the folder with Debian's /usr/bin/python3; returns the plots made
// (file names relative to the folder), empty when python or matplotlib is missing.
std::vector<std::string> plot_strain(const std::filesystem::path& folder);

// Every strain output of the run (grid_strain/*.h5) on the deal.II mesh
// (upscale/strain_fields.h), as cell data: <folder>/strain_mesh/strain_<step>.pvtu with its
// piece, and strain_mesh/strain.pvd, the time series ParaView opens. Call on one rank: the
// meshes are built on MPI_COMM_SELF (the files are rank 0's). Returns the .pvd path
// relative to the folder.
std::string write_strain_mesh(const std::filesystem::path& folder);

// The section, Markdown, from "## Strain" on. `final_strain` is the last evaluation.
std::string strain_section(const SceneInput& in, const upscale::GridStrain& final_strain,
                           const std::filesystem::path& folder, const std::vector<std::string>& plots);

// report.md of a run without the continuum study (Study/compare with continuum = false)
// whose strain is enabled: the scene, the run's figures and the strain section.
void write_run_report(const std::filesystem::path& folder, const SceneInput& in, const RunResult& r,
                      const std::vector<std::string>& plots);

}  // namespace upgrain::coupling
