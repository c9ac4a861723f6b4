// The Output section: the run's folder and what is written into it (docs/output.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto output(Member m) {
  return at(&SceneInput::output, m);
}

}  // namespace

Section output_section() {
  return {
      "Output",
      {text("folder", output(&OutputOptions::folder), "-", "Folder for all results of the run."),
       boolean("overwrite", at(&SceneInput::overwrite),
               "Replace an earlier run in the folder: its files are removed before the new run writes any,"
               " so the two never mix (otherwise a folder with results is refused). Only a folder holding "
               "a run (time_series.csv, summary.json or checkpoints/) is replaced."),
       real("snapshot interval", output(&OutputOptions::snapshot_interval), 0.0, 1e6, "s",
            "Simulated time between HDF5 snapshots; 0 = first and last only."),
       real("time series interval", output(&OutputOptions::series_interval), 0.0, 1e6, "s",
            "Simulated time between rows of time_series.csv."),
       boolean("force network", output(&OutputOptions::force_network),
               "Write every contact with each snapshot after the first: force_network/contacts_<step>.h5 "
               "(ids, point, normal and tangential force, overlap) and force_network.xdmf, the contacts as"
               " lines between the centres for ParaView (docs/output.md)."),
       boolean("energy balance", output(&OutputOptions::energy_balance),
               "Write the elastic energies, the dissipation and the balance error into time_series.csv and"
               " summary.json. false: with Effects/energy tracking = auto the contacts track no energy "
               "(faster), and those columns are nan (null in summary.json).")},
      nullptr};
}

}  // namespace upgrain::coupling::input
