// The Calibration section: the oedometric and friction-angle tests of `upgrain --study calibration`
// (docs/calibration.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto calibration(Member m) {
  return at(&SceneInput::calibration, m);
}

}  // namespace

Section calibration_section() {
  return {
      "Calibration",
      {choice("tests in", calibration(&CalibrationOptions::periodic_cell),
              {{"walls", false}, {"periodic cell", true}},
              "Where both tests load the bed's grains (docs/calibration.md): walls, the bed's box with "
              "servo walls (the oedometer by 'oedometer loading'); periodic cell, the bed's grains without "
              "walls or gravity in a fully periodic cell of its box (its footprint, the height of its "
              "highest point), loaded by the cell's servo (Element test/servo gain, max strain rate): the "
              "oedometric test x and y still, z to each of 'lid stresses' (seated at the first for "
              "'seating time'), the friction-angle test drained triaxial compression at 'confining stress'."),
       choice("oedometer loading", calibration(&CalibrationOptions::oedometer_by_lid),
              {{"gravity", false}, {"lid", true}},
              "How the oedometric test (docs/calibration.md) loads the bed: gravity raises its weight by "
              "each of 'gravity factors' (no wall on the top: nothing to seat; the modulus at the bed's "
              "own stress, as a continuum loaded by gravity needs it); lid holds each of 'lid stresses' "
              "with a servo lid placed on the bed's highest grain."),
       numbers("gravity factors", calibration(&CalibrationOptions::gravity_factors), "-",
               "The bed's weight times each of these in turn (oedometer loading = gravity), "
               "comma-separated, ascending, each > 1; the weight rises linearly over the first half of "
               "each hold."),
       numbers("lid stresses", calibration(&CalibrationOptions::lid_stress_factors), "bed weight / footprint",
               "Targets of the oedometric test's servo lid (oedometer loading = lid) or of the periodic "
               "cell's servo along z (tests in = periodic cell), as multiples of the bed's weight over the "
               "box's footprint, comma-separated, ascending; at least two."),
       real("hold time", calibration(&CalibrationOptions::hold_time), 1e-9, 1e6, "s",
            "Simulated time each gravity factor or lid target is held before the bed's stress and "
            "strain are taken."),
       real("seating time", calibration(&CalibrationOptions::seating_time), 0.0, 1e6, "s",
            "Simulated time before the first hold in which the lid comes down onto the bed and seats at"
            " the first target (its first contacts with the uneven top are impacts); not recorded "
            "(oedometer loading = lid); in the periodic cell, the time its servo first squeezes the "
            "grains to the first target (tests in = periodic cell)."),
       real("gain factor", calibration(&CalibrationOptions::gain_factor), 1e-6, 1.0, "-",
            "alpha of the lid's servo (as Lid/gain factor)."),
       real("max speed", calibration(&CalibrationOptions::max_speed), 1e-9, 1e3, "m/s",
            "Largest speed of the lid."),
       integer("update interval", calibration(&CalibrationOptions::update_every), 1, 1000000, "steps",
               "Steps between the servo walls' updates (the lid's, the friction-angle test's walls); also "
               "the longest stair of the oedometric test's gravity ramp."),
       real("side wall friction", calibration(&CalibrationOptions::side_wall_friction), 0.0, 10.0, "-",
            "Coulomb coefficient of the side walls in the bed of upgrain --study calibration (0: a "
            "lubricated oedometer ring, so that the test measures the grains, not the walls); the floor"
            " keeps Container/floor friction. A study's own bed keeps the scene's walls "
            "(docs/calibration.md)."),
       real("confining stress", calibration(&CalibrationOptions::confining_stress_factor), 1e-3, 1e6,
            "bed weight / footprint",
            "sigma_3 of the friction-angle test (docs/calibration.md), held by the four servo side "
            "walls, as a multiple of the bed's weight over the box's footprint; the bed is first "
            "consolidated to it isotropically (without gravity)."),
       real("axial strain rate", calibration(&CalibrationOptions::axial_strain_rate), 1e-6, 1e3, "1/s",
            "Axial strain rate of the friction-angle test: the lid comes down at this rate times the "
            "consolidated height. The driver prints the inertial number I = rate d sqrt(rho / sigma_3) "
            "(quasi-static below about 1e-3)."),
       real("final axial strain", calibration(&CalibrationOptions::final_axial_strain), 0.01, 0.5, "-",
            "Axial strain at which the friction-angle test ends; its last 30 % is the critical state."),
       real("consolidation time", calibration(&CalibrationOptions::consolidation_time), 1e-9, 1e6, "s",
            "Simulated time in which the lid and the side walls consolidate the bed to the confining "
            "stress before the shearing."),
       choice("continuum strength", calibration(&CalibrationOptions::critical_state_strength),
              {{"peak", false}, {"critical state", true}},
              "The strength the calibrated material file gives the Drucker–Prager continuum: the peak "
              "friction angle with the dilatancy angle at the peak, or the critical-state friction angle "
              "with no dilatancy.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
