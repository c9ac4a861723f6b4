#include "coupling/studies/femxdem/femxdem_checkpoints.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <utility>

#include "coupling/run/checkpoint.h"
#include "coupling/run/checkpoint_clock.h"
#include "coupling/run/stop_request.h"
#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/parallel/exchange.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStudy = "femxdem";
constexpr const char* kTables = "point_history.csv";  // the block of the study's own record
constexpr const char* kStem = "state";                // the solver's files: state, state.info, ...

std::vector<char> file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in.good() && !in.eof()) throw Error("cannot read " + file.string());
  return bytes;
}

}  // namespace

FemxdemCheckpoints::FemxdemCheckpoints(const SceneInput& in, MPI_Comm comm)
    : in_(in), comm_(comm), clock_(in.output.checkpoint, /*dt=*/0.0, /*output=*/true) {
  MPI_Comm_rank(comm, &rank_);
  work_ = fs::path(in.output.folder) / "checkpoints" / "femxdem_state";
  if (!in.restarting) return;
  long step = -1;
  dem::run_on_root(comm, [&] {
    const Checkpoint& c = *in.resume;
    if (!c.study || c.study->study != kStudy)
      throw Error("checkpoint " + c.file.string() + " holds no FEM x DEM state");
    fs::remove_all(work_);
    fs::create_directories(work_);
    for (const auto& [name, bytes] : c.study->blocks) {
      // A file of the working folder, never a path out of it.
      if (name.empty() || name.find('/') != std::string::npos || name.front() == '.')
        throw Error("checkpoint " + c.file.string() + ": its FEM x DEM state has a block named '" + name +
                    "', which is not a file name");
      if (name == kTables)
        restored_tables_.assign(bytes.begin(), bytes.end());
      else
        dem::io::write_bytes(work_ / name, bytes.data(), bytes.size(), (work_ / name).string());
    }
    (void)c.study->block(std::string(kStem) + ".solver", c.file);
    step = c.step;
  });
  MPI_Bcast(&step, 1, MPI_LONG, 0, comm);
  resumed_after_ = step;
  resume_stem_ = (work_ / kStem).string();
}

FemxdemCheckpoints::~FemxdemCheckpoints() {
  if (rank_ != 0) return;
  std::error_code ec;
  fs::remove_all(work_, ec);
}

fem::QuasiStaticCheckpoints FemxdemCheckpoints::for_solver(
    std::function<std::string()> tables,
    std::function<void(const std::vector<fem::LoadStepRecord>&, const std::string&)> restored) {
  fem::QuasiStaticCheckpoints c;
  c.resume = resume_stem_;
  c.resumed = [this, restored](const std::vector<fem::LoadStepRecord>& steps) {
    // Every rank has read the files (the solver's collective calls after its load): they go.
    if (rank_ == 0) {
      std::error_code ec;
      fs::remove_all(work_, ec);
    }
    restored(steps, restored_tables_);
    restored_tables_.clear();
  };
  // The wall clock and the stop request are each rank's own: the ranks agree on them here, in one
  // reduction after each converged step.
  c.stem = [this](const fem::LoadStepRecord& record) -> std::string {
    const CheckpointClock::Decision d = clock_.at(static_cast<long>(record.step), true, comm_);
    stop_ = d.stop;
    if (!d.write) return {};
    dem::run_on_root(comm_, [&] {
      fs::remove_all(work_);
      fs::create_directories(work_);
    });
    saving_since_ = std::chrono::steady_clock::now();
    return (work_ / kStem).string();
  };
  // A signal is served inside a load step (minutes long): the step is abandoned at the cells' next
  // answers, which a cell cuts short itself (RveCell), and the last converged step is saved.
  c.stop_requested = [] { return stop_signal() != 0; };
  c.saved = [this, tables](const fem::LoadStepRecord& record, const std::string&) {
    fs::path written;
    dem::run_on_root(comm_, [&] {
      Checkpoint k;
      k.step = record.step;
      k.scene = in_.output.checkpoint.scene;
      StudyState s;
      s.study = kStudy;
      std::vector<fs::path> files;
      for (const fs::directory_entry& e : fs::directory_iterator(work_)) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) s.blocks.emplace_back(f.filename().string(), file_bytes(f));
      const std::string t = tables();
      s.blocks.emplace_back(kTables, std::vector<char>(t.begin(), t.end()));
      k.study = std::move(s);
      written = write_checkpoint(in_.output.folder, k, in_.output.checkpoint.keep);
      fs::remove_all(work_);
      std::printf("  femxdem: checkpoint %s after load step %u (%.3g MB in %.2g s)\n", written.c_str(),
                  record.step, static_cast<double>(fs::file_size(written)) / 1e6,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - saving_since_).count());
      std::fflush(stdout);
    });
    clock_.written();
    if (stop_ != 0)
      throw RunStopped(stop_, static_cast<long>(record.step),
                       written.empty() ? fs::path(in_.output.folder) / "checkpoints" : written);
  };
  return c;
}

}  // namespace upgrain::coupling
