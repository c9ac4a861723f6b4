#pragma once
// The FEM x DEM study (`upgrain --study femxdem scene.prm`, docs/femxdem.md): a plane-strain
// biaxial specimen meshed by deal.II (fem/quasi_static/), confined on its sides and shortened by a
// platen, whose material at every Gauss point is a periodic DEM cell of the scene's grains
// (coupling/femxdem/), prepared once at the confining pressure and copied to every point. Writes
// <Output/folder>/femxdem/: load_displacement.csv, points.csv, femxdem-NNNN.pvtu per load step
// with femxdem.pvd, load_displacement.png (plot_femxdem.py); and <Output/folder>/summary.json.
// Collective.
#include <mpi.h>

#include "coupling/studies/study.h"
#include "fem/quasi_static/quasi_static_problem.h"

namespace upgrain::coupling {

// The continuum problem of the FEMxDEM section, with gravity's magnitude for a column (plain: the
// tests build it too).
fem::QuasiStaticProblem femxdem_problem(const FemxdemOptions& o, double gravity);

int run_femxdem_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);

}  // namespace upgrain::coupling
