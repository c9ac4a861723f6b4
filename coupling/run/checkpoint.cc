#include "coupling/run/checkpoint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <regex>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/fnv1a.h"
#include "dem/files/output_journal.h"
#include "dem/io/checksum_block.h"
#include "dem/io/engine_state_file.h"
#include "dem/io/hdf5_reader.h"
#include "dem/io/hdf5_util.h"
#include "dem/io/output_state_file.h"
#include "upscale/strain/strain_state_file.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;
namespace hdf5 = dem::io::hdf5;

namespace {

constexpr const char* kFormat = "Upgrain checkpoint";

long step_of(const fs::path& file) {
  static const std::regex name(R"(checkpoint_(\d+)\.h5)");
  std::smatch m;
  const std::string f = file.filename().string();
  return std::regex_match(f, m, name) ? std::stol(m[1]) : -1;
}

void write_grid_state(hid_t parent, const GridEvaluationState& s) {
  hdf5::Handle g(hdf5::create_group(parent, "grids"), H5Gclose, "create group grids");
  dem::io::write_grid_stress_list(g, "stress_files", s.stress_files);
  hdf5::write_attribute(g, "stress_rows", static_cast<double>(s.stress_rows));
  hdf5::write_attribute(g, "compute_grid_rows", static_cast<double>(s.compute_grid_rows));
  upscale::write_strain_list(g, "strain_files", s.strain_files);
  hdf5::write_attribute(g, "strain_rows", static_cast<double>(s.strain_rows));
  hdf5::write_attribute(g, "block_rows", static_cast<double>(s.block_rows));
  hdf5::write_attribute(g, "cell_rows", static_cast<double>(s.cell_rows));
  if (s.reference) upscale::write_strain_reference(g, "reference", *s.reference);
  if (s.previous) upscale::write_previous_strain(g, "previous", *s.previous);
  if (s.rates) upscale::write_rate_history(g, "rates", *s.rates);
  if (s.block_reference) upscale::write_strain_reference(g, "block_reference", *s.block_reference);
  if (s.previous_blocks) upscale::write_previous_strain(g, "previous_blocks", *s.previous_blocks);
  std::vector<dem::Vec3> corners;
  for (const dem::Box& b : s.reference_blocks) corners.insert(corners.end(), {b.lo, b.hi});
  hdf5::write_vectors(g, "reference_blocks", corners);
}

GridEvaluationState read_grid_state(const hdf5::Reader& in, const std::string& group,
                                    dem::StressFormula rate_formula) {
  GridEvaluationState s;
  s.stress_files = dem::io::read_grid_stress_list(in, group + "/stress_files");
  s.stress_rows = in.whole_attribute("stress_rows", group, 0);
  s.compute_grid_rows = in.whole_attribute("compute_grid_rows", group, -1);  // -1: no compute grids
  s.strain_files = upscale::read_strain_list(in, group + "/strain_files");
  s.strain_rows = in.whole_attribute("strain_rows", group, 0);
  s.block_rows = in.whole_attribute("block_rows", group, -1);  // -1: no block strain output
  s.cell_rows = in.has_attribute("cell_rows", group) ? in.whole_attribute("cell_rows", group, -1) : -1;
  if (in.exists(group + "/reference")) s.reference = upscale::read_strain_reference(in, group + "/reference");
  if (in.exists(group + "/previous")) s.previous = upscale::read_previous_strain(in, group + "/previous");
  if (in.exists(group + "/rates")) s.rates = upscale::read_rate_history(in, group + "/rates", rate_formula);
  if (in.exists(group + "/block_reference"))
    s.block_reference = upscale::read_strain_reference(in, group + "/block_reference");
  if (in.exists(group + "/previous_blocks"))
    s.previous_blocks = upscale::read_previous_strain(in, group + "/previous_blocks");
  const std::vector<dem::Vec3> corners = in.read_vectors(group + "/reference_blocks");
  for (std::size_t k = 0; k + 1 < corners.size(); k += 2)
    s.reference_blocks.push_back({corners[k], corners[k + 1]});
  return s;
}

void write_history(hid_t run, const RunHistory& h) {
  hdf5::write_attribute(run, "wall_seconds", h.wall_seconds);
  hdf5::write_attribute(run, "scene_source", h.scene_source);
  const std::vector<std::int64_t> resumed(h.resumed_at.begin(), h.resumed_at.end());
  if (!resumed.empty()) hdf5::write_dataset(run, "resumed_at", resumed.data(), resumed.size());
}

// Absent from the checkpoints of runs before the history was kept: the earlier segments' time
// is not known (NaN), and the scene's name is the restart's.
RunHistory read_history(const hdf5::Reader& in, long step) {
  RunHistory h;
  h.wall_seconds = std::nan("");
  if (in.has_attribute("wall_seconds", "/run")) {
    h.wall_seconds = in.attribute("wall_seconds", "/run");
    if (!std::isnan(h.wall_seconds) && !(h.wall_seconds >= 0.0 && std::isfinite(h.wall_seconds)))
      throw Error(in.where() + "attribute wall_seconds of /run is not a time in seconds");
  }
  if (in.has_attribute("scene_source", "/run")) h.scene_source = in.text_attribute("scene_source", "/run");
  for (std::int64_t s : in.read_all<std::int64_t>("/run/resumed_at", 1, true)) {
    if (s < 0 || s > step) throw Error(in.where() + "/run/resumed_at holds a step outside the run so far");
    h.resumed_at.push_back(static_cast<long>(s));
  }
  return h;
}

void write_study_state(hid_t file, const StudyState& s) {
  hdf5::Handle g(hdf5::create_group(file, "study"), H5Gclose, "create group study");
  hdf5::write_attribute(g, "name", s.study);
  std::string names;
  for (std::size_t k = 0; k < s.blocks.size(); ++k) {
    const auto& [name, bytes] = s.blocks[k];
    names += name + "\n";
    hdf5::write_dataset(g, ("block_" + std::to_string(k)).c_str(),
                        reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  hdf5::write_attribute(g, "blocks", names);
}

StudyState read_study_state(const hdf5::Reader& in) {
  StudyState s;
  s.study = in.text_attribute("name", "/study");
  const std::string names = in.text_attribute("blocks", "/study");
  std::size_t from = 0;
  for (std::size_t k = 0; from < names.size(); ++k) {
    const std::size_t end = names.find('\n', from);
    if (end == std::string::npos) throw Error(in.where() + "/study: its block names do not end their line");
    const std::vector<std::uint8_t> bytes = in.read_all<std::uint8_t>("/study/block_" + std::to_string(k));
    s.blocks.emplace_back(names.substr(from, end - from), std::vector<char>(bytes.begin(), bytes.end()));
    from = end + 1;
  }
  return s;
}

void write_engine_and_run(hid_t file, const Checkpoint& c) {
  dem::io::write_engine_state(file, "engine", c.engine);
  hdf5::Handle run(hdf5::create_group(file, "run"), H5Gclose, "create group run");
  const ScheduleState& s = c.run.schedule;
  hdf5::write_attribute(run, "step", static_cast<double>(s.step));
  hdf5::write_attribute(run, "next_release", static_cast<double>(s.next_release));
  hdf5::write_attribute(run, "rest_check_from", static_cast<double>(s.rest_check_from));
  hdf5::write_attribute(run, "below_rest_since", static_cast<double>(s.below_rest_since));
  hdf5::write_attribute(run, "inserted", static_cast<double>(c.run.pour.inserted));
  hdf5::write_attribute(run, "insertion_batches", static_cast<double>(c.run.pour.batches));
  hdf5::write_attribute(run, "series_rows", static_cast<double>(c.run.files.series_rows));
  hdf5::write_attribute(run, "wall_rows", static_cast<double>(c.run.files.wall_rows));
  if (!c.run.files.wall_origins.empty()) hdf5::write_vectors(run, "wall_origins", c.run.files.wall_origins);
  dem::io::write_snapshot_list(run, "snapshots", c.run.files.snapshots);
  if (c.run.grids) write_grid_state(run, c.run.grid_state);
  write_history(run, c.run.history);
  if (c.run.cg_reference) {
    const upscale::cg::ReferencePositions& ref = *c.run.cg_reference;
    hdf5::Handle g(hdf5::create_group(run, "cg_reference"), H5Gclose, "create group cg_reference");
    hdf5::write_attribute(g, "time", ref.time);
    hdf5::write_dataset(g, "id", ref.id.data(), ref.id.size());
    hdf5::write_vectors(g, "position", ref.x);
    // A periodic cell's counters (a bounded box keeps its checkpoints' bytes).
    if (!ref.image.empty()) {
      std::vector<std::int32_t> image(3 * ref.image.size());
      for (std::size_t i = 0; i < ref.image.size(); ++i)
        for (int d = 0; d < 3; ++d) image[3 * i + d] = ref.image[i][d];
      hdf5::write_dataset(g, "image", image.data(), ref.image.size(), 3);
    }
  }
}

}  // namespace

const std::vector<char>& StudyState::block(const std::string& name, const fs::path& file) const {
  for (const auto& [n, bytes] : blocks)
    if (n == name) return bytes;
  throw Error("checkpoint " + file.string() + ": its " + study + " state has no block " + name);
}

std::string scene_hash(const std::string& scene) {
  dem::io::Fnv1a h;
  h.add(scene);
  return h.hex();
}

fs::path write_checkpoint(const fs::path& folder, const Checkpoint& c, int keep) {
  const fs::path dir = folder / "checkpoints";
  dem::io::create_folder(dir);
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint_%09ld.h5", c.step);
  dem::io::AtomicFile target(dir / name);
  {
    hdf5::Handle file(hdf5::create_file(target.temporary_path(), dem::io::kChecksumBlockBytes), H5Fclose,
                      "create " + target.temporary_path().string());
    hdf5::write_attribute(file, "format", kFormat);
    hdf5::write_attribute(file, "format_version", static_cast<double>(kCheckpointVersion));
    hdf5::write_attribute(file, "code_version", UPGRAIN_VERSION);
    hdf5::write_attribute(file, "step", static_cast<double>(c.step));
    hdf5::write_attribute(file, "time", c.time);
    hdf5::write_attribute(file, "scene", c.scene);
    hdf5::write_attribute(file, "scene_hash", scene_hash(c.scene));
    // The run's identity and the files it had written, from its open output journal.
    if (const std::optional<dem::io::OutputManifest> m = dem::io::journal_manifest()) {
      hdf5::write_attribute(file, "run_id", m->run_id);
      std::string listed;
      // The checkpoints themselves are left out: which older ones are kept depends on where the
      // run was resumed, and a restart keeps those up to its own by their step.
      for (const std::string& p : dem::io::journal_paths())
        if (p.rfind("checkpoints/", 0) != 0) listed += p + "\n";
      const std::vector<std::uint8_t> bytes(listed.begin(), listed.end());
      if (!bytes.empty()) hdf5::write_dataset(file, "outputs", bytes.data(), bytes.size());
    }
    if (c.study) write_study_state(file, *c.study);
    if (!c.study) write_engine_and_run(file, c);
    // Its checksum in its first block, written and synced: only then does it get its name.
    // The image leaves the user block out: it goes first, stamped with the rest's checksum.
    std::vector<unsigned char> image(dem::io::kChecksumBlockBytes, 0);
    const std::vector<unsigned char> rest = hdf5::file_image(file);
    image.insert(image.end(), rest.begin(), rest.end());
    dem::io::stamp_checksum(image);
    dem::io::write_bytes(target.temporary_path(), image.data(), image.size(), target.final_path().string());
  }
  target.commit();
  // The newest `keep` stay (a crash while writing the next leaves the last one whole).
  const std::vector<fs::path> all = checkpoint_files(folder);
  for (std::size_t k = static_cast<std::size_t>(std::max(keep, 1)); k < all.size(); ++k) {
    std::error_code ec;
    if (fs::remove(all[k], ec)) dem::io::note_removed(all[k]);
  }
  return target.final_path();
}

std::vector<fs::path> checkpoint_files(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder / "checkpoints", ec))
    if (e.is_regular_file() && step_of(e.path()) >= 0) out.push_back(e.path());
  std::sort(out.begin(), out.end(),
            [](const fs::path& a, const fs::path& b) { return step_of(a) > step_of(b); });
  return out;
}

Checkpoint read_checkpoint(const fs::path& file) {
  // Every byte is checked before the HDF5 library parses one (dem/io/checksum_block.h).
  dem::io::verify_checksum(file, "checkpoint");
  hdf5::QuietHdf5 quiet;
  hdf5::Reader in(file, "checkpoint");
  if (!in.has_attribute("format") || in.text_attribute("format") != kFormat)
    throw Error(in.where() + "not an Upgrain checkpoint");
  const double version = in.attribute("format_version");
  if (version != kCheckpointVersion)
    throw Error(in.where() + "checkpoint format " + std::to_string(static_cast<int>(version)) +
                ", this build reads format " + std::to_string(kCheckpointVersion));
  Checkpoint c;
  c.file = file;
  c.step = in.whole_attribute("step", "/", 0);
  c.time = in.attribute("time");
  c.scene = in.text_attribute("scene");
  c.scene_hash = in.text_attribute("scene_hash");
  if (scene_hash(c.scene) != c.scene_hash) throw Error(in.where() + "the scene does not match its hash");
  // Absent from checkpoints written without an output journal (tests, benchmarks).
  if (in.has_attribute("run_id")) c.run_id = in.text_attribute("run_id");
  if (in.exists("/outputs")) {
    const std::vector<std::uint8_t> bytes = in.read_all<std::uint8_t>("/outputs");
    std::string name;
    for (const std::uint8_t b : bytes) {
      if (b != '\n') {
        name += static_cast<char>(b);
      } else if (!name.empty()) {
        c.outputs.push_back(name);
        name.clear();
      }
    }
  }
  if (in.exists("/study")) {
    c.study = read_study_state(in);
    return c;
  }
  c.engine = dem::io::read_engine_state(in, "/engine");
  if (c.engine.step != c.step) throw Error(in.where() + "the engine's step is not the checkpoint's");
  RunState& r = c.run;
  r.schedule.step = in.whole_attribute("step", "/run", 0);
  r.schedule.next_release = static_cast<std::size_t>(in.whole_attribute("next_release", "/run", 0));
  r.schedule.rest_check_from = in.whole_attribute("rest_check_from", "/run");
  // Absent from the checkpoints of runs before the rest window existed: not below.
  if (in.has_attribute("below_rest_since", "/run"))
    r.schedule.below_rest_since = in.whole_attribute("below_rest_since", "/run", -1);
  // Absent from the checkpoints of runs before insertion existed: nothing was inserted.
  if (in.has_attribute("inserted", "/run")) {
    r.pour.inserted = in.whole_attribute("inserted", "/run", 0);
    r.pour.batches = in.whole_attribute("insertion_batches", "/run", 0);
  }
  r.files.series_rows = in.whole_attribute("series_rows", "/run", 0);
  r.files.wall_rows = in.whole_attribute("wall_rows", "/run", 0);
  r.files.wall_origins = in.read_vectors("/run/wall_origins", true);
  r.files.snapshots = dem::io::read_snapshot_list(in, "/run/snapshots");
  r.grids = in.exists("/run/grids");
  if (r.grids) {
    // The rate formula is checked against the scene's when the run resumes; read it as stored.
    const auto formula = in.exists("/run/grids/rates")
                             ? static_cast<dem::StressFormula>(in.whole_attribute(
                                   "formula", "/run/grids/rates", 0, dem::kStressFormulaCount - 1))
                             : dem::StressFormula::bagi;
    r.grid_state = read_grid_state(in, "/run/grids", formula);
  }
  r.history = read_history(in, c.step);
  if (in.exists("/run/cg_reference")) {
    upscale::cg::ReferencePositions ref;
    ref.time = in.attribute("time", "/run/cg_reference");
    ref.id = in.read_all<upscale::cg::GlobalId>("/run/cg_reference/id");
    ref.x = in.read_vectors("/run/cg_reference/position");
    if (ref.x.size() != ref.id.size())
      throw Error(in.where() + "/run/cg_reference: " + std::to_string(ref.id.size()) + " ids but " +
                  std::to_string(ref.x.size()) + " positions");
    if (in.exists("/run/cg_reference/image")) {
      const std::vector<std::int32_t> image =
          in.read<std::int32_t>("/run/cg_reference/image", H5T_NATIVE_INT32, ref.id.size(), 3);
      ref.image.resize(ref.id.size());
      for (std::size_t i = 0; i < ref.id.size(); ++i)
        ref.image[i] = {image[3 * i], image[3 * i + 1], image[3 * i + 2]};
    }
    r.cg_reference = std::move(ref);
  }
  return c;
}

Checkpoint newest_checkpoint(const fs::path& folder, std::vector<std::string>& refused, long before_step) {
  std::vector<fs::path> files = checkpoint_files(folder);
  if (before_step >= 0) {
    std::erase_if(files, [&](const fs::path& f) { return step_of(f) >= before_step; });
    if (files.empty())
      throw Error("no checkpoint in " + (folder / "checkpoints").string() + " before step " +
                  std::to_string(before_step));
  }
  if (files.empty()) throw Error("no checkpoint in " + (folder / "checkpoints").string());
  for (const fs::path& f : files) {
    try {
      return read_checkpoint(f);
    } catch (const std::exception& e) {
      // The readers' errors name the file already ("checkpoint <file>: ...").
      const std::string why = e.what();
      refused.push_back(why.find(f.string()) != std::string::npos ? why
                                                                  : "checkpoint " + f.string() + ": " + why);
    }
  }
  // Every one refused: the newest one's reason says what happened.
  throw Error("no readable checkpoint in " + (folder / "checkpoints").string() + " (" +
              std::to_string(files.size()) + " refused; the newest: " + refused.front() + ")");
}

}  // namespace upgrain::coupling
