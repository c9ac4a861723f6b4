#pragma once
// An accuracy study (docs/accuracy.md; `upgrain --study accuracy scene.prm`): for each knob of
// the scene's Accuracy section and each of its values, the scene is run with everything else
// unchanged, and the study measures the wall time and what changes in the bed, against the
// scene's own settings and against the spread of replicas that differ only in the fill's seed
// (the noise floor), and against an exact answer where one exists (a Hertz collision for the
// time step, the analytic column for the continuum). It writes <folder>/accuracy/: a CSV table,
// one Pareto plot per knob, and a report that names, per knob, the cheapest setting whose
// changes all stay within the tolerance.
#include <mpi.h>

#include "coupling/studies/study.h"

namespace upgrain::coupling {

// Collective over `comm`. Returns the process exit code: 0, or 1 when a result that must not
// change did (the skin's, bit for bit).
int run_accuracy_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);

}  // namespace upgrain::coupling
