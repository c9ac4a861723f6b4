// The Accuracy section: the knobs of `upgrain --study accuracy` and their values (docs/accuracy.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "coupling/studies/accuracy/accuracy_knobs.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto accuracy(Member m) {
  return at(&SceneInput::accuracy, m);
}

// The knobs as the file lists them (accuracy_knobs.h checks each name).
Entry knobs(std::string doc) {
  return {"knobs",
          Kind::multiple_selection,
          0,
          0,
          join(knob_names(), "|"),
          "-",
          std::move(doc),
          [](SceneInput& in, const EntryValue& v, const std::string&) {
            in.accuracy.knobs = split_list(std::get<std::string>(v));
          },
          [](SceneInput& in) { return join(in.accuracy.knobs); }};
}

// "nx ny nz; nx ny nz; ..."
Entry grids(std::string doc) {
  return {"grids",
          Kind::text,
          0,
          0,
          "",
          "-",
          std::move(doc),
          [](SceneInput& in, const EntryValue& v, const std::string& path) {
            in.accuracy.grids.clear();
            for (const std::string& g : split_list(std::get<std::string>(v), ';')) {
              const std::vector<double> n = numbers_of(g, path, ' ');
              if (n.size() != 3) throw Error(path + ": '" + g + "' is not three cell counts");
              in.accuracy.grids.push_back(
                  {static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2])});
            }
          },
          [](SceneInput& in) {
            std::vector<std::string> out;
            for (const auto& g : in.accuracy.grids)
              out.push_back(std::to_string(g[0]) + " " + std::to_string(g[1]) + " " + std::to_string(g[2]));
            return join(out, "; ");
          }};
}

}  // namespace

Section accuracy_section() {
  return {
      "Accuracy",
      {knobs("What `upgrain --study accuracy` turns, one at a time, every other setting as the scene "
             "gives it (docs/accuracy.md). Knobs that do not apply to the scene are skipped with a note."),
       numbers("time step fractions", accuracy(&AccuracyOptions::time_step_fractions), "-",
               "Time steps to try, as fractions of the scene's safe step (the scene's own step is added)."),
       numbers("modulus factors", accuracy(&AccuracyOptions::modulus_factors), "-",
               "Young's modulus scaled by these factors, each with the safe step it allows (at the scene's"
               " own fraction of it)."),
       numbers("skins", accuracy(&AccuracyOptions::skins), "-",
               "Neighbour skins to try, in largest diameters: every result must be the same bits."),
       numbers("solver tolerances", accuracy(&AccuracyOptions::solver_tolerances), "eps x size",
               "Ellipsoid contact solver gradient tolerances to try (Contact/solver gradient tolerance)."),
       numbers("solver iteration caps", accuracy(&AccuracyOptions::solver_iteration_caps), "-",
               "Ellipsoid contact solver iteration caps to try (Contact/solver iterations)."),
       numbers("relaxation tolerances", accuracy(&AccuracyOptions::relaxation_tolerances), "-",
               "FIRE tolerances to try (Study/relaxation tolerance)."),
       grids("Stress grids to try, cells along x y z, separated by ';' (Yan and Regueiro's grid-size study, "
             "docs/stress.md)."),
       numbers("fem degrees", accuracy(&AccuracyOptions::fem_degrees), "-",
               "Polynomial degrees of the continuum to try against its analytic solution."),
       numbers("fem refinements", accuracy(&AccuracyOptions::fem_refinements), "-",
               "Global refinements to try with each degree."),
       integer("replicas", accuracy(&AccuracyOptions::replicas), 1, 20, "-",
               "Runs of the scene as given that differ only in Fill/seed; their spread is the noise floor "
               "below which a change is reported as no measurable change."),
       real("tolerance", accuracy(&AccuracyOptions::tolerance), 0.0, 1.0, "-",
            "Relative change a setting may make in every measure of the bed (or the noise floor, if "
            "larger) for the report to call it within tolerance.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
