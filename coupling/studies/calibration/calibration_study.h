#pragma once
// The calibration study (`upgrain --study calibration scene.prm`, docs/calibration.md): the
// scene's bed is deposited, then compressed oedometrically by a servo lid in stress steps
// (oedometer_run.h); from the path, the constrained modulus and K0 of each step, and the
// equivalent linear elastic material (E, nu) at the bed's own mean vertical stress. Writes
// <Output/folder>/calibration/oedometer.csv (the stress-strain path) and material.prm (the
// calibrated Continuum entries, a scene-file fragment). Collective over `comm`.
#include <mpi.h>

#include <functional>

#include "coupling/studies/study.h"

namespace upgrain::coupling {

int run_calibration_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);

}  // namespace upgrain::coupling
