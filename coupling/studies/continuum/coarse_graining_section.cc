// The CoarseGraining section: the coarse-grained fields on the study's mesh (docs/coarse-graining.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto cg(Member m) {
  return at(&SceneInput::study, &StudyOptions::coarse_graining, m);
}

}  // namespace

Section coarse_graining_section() {
  return {
      "CoarseGraining",
      {flags("fields",
             {{"density", [](SceneInput& in) -> bool& { return in.study.coarse_graining.density; }},
              {"velocity", [](SceneInput& in) -> bool& { return in.study.coarse_graining.velocity; }},
              {"stress", [](SceneInput& in) -> bool& { return in.study.coarse_graining.stress; }},
              {"wall force density",
               [](SceneInput& in) -> bool& { return in.study.coarse_graining.wall_force_density; }},
              {"displacement", [](SceneInput& in) -> bool& { return in.study.coarse_graining.displacement; }},
              {"momentum balance",
               [](SceneInput& in) -> bool& { return in.study.coarse_graining.momentum_balance; }}},
             "Coarse-grained fields written on the study's mesh beside the continuum "
             "(docs/coarse-graining.md), comma-separated: density (and volume fraction), velocity (and "
             "momentum), stress (total and kinetic; the contact stress by the line integral along each "
             "branch), wall force density, displacement (and its gradient, against the state at "
             "'reference time'), momentum balance (its residual and d(rho v)/dt). The stress is always "
             "compared with the continuum's. Empty: none. Needs 'Study/compare with continuum'."),
       choice("kernel", cg(&CoarseGrainingOptions::kernel),
              {{"gaussian", upscale::cg::KernelKind::gaussian}, {"lucy", upscale::cg::KernelKind::lucy}},
              "Smoothing kernel: gaussian (cut at 3 w and renormalised, as MercuryCG) or lucy (Lucy's "
              "polynomial, cut-off 2 sqrt(3) w)."),
       real("width", cg(&CoarseGrainingOptions::width), 0.05, 20.0, "mean grain diameters",
            "Kernel width w, the standard deviation of the kernel along each axis, in mean grain "
            "diameters d (of the grains' volume-equivalent spheres)."),
       choice("evaluation points", cg(&CoarseGrainingOptions::at_quadrature_points),
              {{"support points", false}, {"quadrature points", true}},
              "Where the fields are evaluated: the support points of the continuum's Q_k elements "
              "(written as continuous finite-element fields), or its quadrature points (written as cell "
              "means). The comparison with the continuum's stress is at its quadrature points either way."),
       choice("time derivative", cg(&CoarseGrainingOptions::by_differences),
              {{"accelerations", false}, {"differences", true}},
              "d(rho v)/dt in the momentum balance: from the grains' accelerations of the final force "
              "evaluation (exact), or by differences of the final state and one 'sampling interval' later"
              " (trapezoidal)."),
       real("sampling interval", cg(&CoarseGrainingOptions::sampling_interval), 0.0, 1e3, "s",
            "Time between the two states of 'time derivative = differences'; 0 = one time step. Rounded"
            " to whole time steps."),
       real("reference time", cg(&CoarseGrainingOptions::reference_time), 0.0, 1e6, "s",
            "The reference state of the displacement field: the first step at or after this time (0 = "
            "the initial state).")},
      nullptr};
}

}  // namespace upgrain::coupling::input
