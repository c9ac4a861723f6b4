#pragma once
// The element study (`upgrain --study element scene.prm`, docs/element-tests.md): the scene's
// grains in a fully periodic cell, without gravity or walls, compressed isotropically to each
// pressure of its Element test section, then sheared in drained triaxial compression
// (element_run.h). Writes <Output/folder>/element/: isotropic.csv, triaxial.csv, material.prm
// (the Continuum entries they give, a scene-file fragment), report.md (its section "Element
// test") and the plots of plot_element.py; and <Output/folder>/summary.json. Collective.
#include <mpi.h>

#include "coupling/studies/study.h"

namespace upgrain::coupling {

int run_element_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);

}  // namespace upgrain::coupling
