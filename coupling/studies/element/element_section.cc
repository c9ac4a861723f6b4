// The Element test section: the isotropic and drained triaxial compressions of `upgrain --study
// element` on a fully periodic cell (docs/element-tests.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto element(Member m) {
  return at(&SceneInput::element, m);
}

}  // namespace

Section element_section() {
  return {
      "Element test",
      {numbers("pressures", element(&ElementOptions::pressures), "Pa",
               "Targets of the isotropic compression (docs/element-tests.md), comma-separated, each > 0, "
               "held in turn by a servo on the three axes of the periodic cell; the last is also sigma_3 "
               "of the drained triaxial compression."),
       real("compaction time", element(&ElementOptions::compaction_time), 1e-9, 1e6, "s",
            "Simulated time in which the servo first squeezes the scene's fill (a gas: no gravity) into a "
            "packing at the first pressure; not recorded."),
       real("hold time", element(&ElementOptions::hold_time), 1e-9, 1e6, "s",
            "Simulated time the servo holds each pressure; the state is averaged over its last quarter. The "
            "bulk modulus's strain step then takes a tenth of it, between two still cells of a fifth each."),
       real("servo gain", element(&ElementOptions::servo_gain), 1e-6, 1e6, "1/s",
            "The cell's servo: L_dd = gain (p_dd - p*) / p* (docs/periodic.md, \"A cell that deforms\")."),
       real("max strain rate", element(&ElementOptions::max_strain_rate), 1e-9, 1e4, "1/s",
            "The bound on the servo's |L_dd|."),
       real("volumetric strain step", element(&ElementOptions::volumetric_strain_step), 1e-9, 0.1, "-",
            "The isotropic compression -dV/V of the bulk modulus's step, K = dp / d eps_v."),
       real("axial strain rate", element(&ElementOptions::axial_strain_rate), 1e-9, 1e4, "1/s",
            "-L_zz of the drained triaxial compression (x and y servo to sigma_3). The study prints the "
            "inertial number I = rate d sqrt(rho / sigma_3) (quasi-static below about 1e-3)."),
       real("final axial strain", element(&ElementOptions::final_axial_strain), 0.01, 0.5, "-",
            "eps_1 = 1 - h_z / h_z0 at which the triaxial compression ends; its last 30 % is the "
            "critical state."),
       numbers(
           "shear inertial numbers", element(&ElementOptions::shear_inertial_numbers), "-",
           "Simple shear at a constant normal stress (docs/element-tests.md, \"Simple shear and mu(I)\"): "
           "from the last isotropic state, the cell is sheared along x across z (Cell/shear component = "
           "xz) at the rate gamma_dot = I sqrt(P / rho) / d of each inertial number I in turn, each in "
           "(0, 1], with z servo to P = the last pressure; x and y keep their lengths. Empty: no shear "
           "test. Three or more give the fit mu(I) = mu_s + (mu_2 - mu_s) / (1 + I0 / I)."),
       real("shear strain", element(&ElementOptions::shear_strain), 0.1, 100.0, "-",
            "The shear strain at each inertial number; its last half is the steady state averaged."),
       real("shear servo gain", element(&ElementOptions::shear_servo_gain), 1e-3, 100.0, "-",
            "The normal stress's servo during shear relative to the shear rate: L_zz = gain gamma_dot "
            "(p_zz - P) / P, bounded by gamma_dot.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
