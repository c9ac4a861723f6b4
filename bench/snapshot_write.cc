// Snapshot and force-network write time and memory, gathered on rank 0 against written
// collectively (docs/output.md, "Snapshots", "Force network"; docs/parallel.md, "Output"). N
// spheres at rest on a cubic lattice in an engine on MPI_COMM_WORLD; each mode writes `repeats`
// files into FOLDER and rank 0 prints the mean time and the throughput in MB/s of the file's
// bytes:
//   gather      the state sorted by id on rank 0 (Simulation::whole_state()), written there
//               alone (the path every snapshot took before the collective writer);
//   collective  every rank's id slice (Simulation::whole_state_slice()), written by all
//               ranks into one file with collective MPI-IO.
//   network-gather, network-collective: the same for the force network of the lattice pressed
//               together (six contacts a grain, recorded by one step): the state and every
//               contact on rank 0 (Simulation::gather_contacts_by_id()), or each rank's rows'
//               contacts with the partners they reach (Simulation::contacts_of_rows()).
// Peak memory per rank: run each mode in its own process under /usr/bin/time -v, e.g.
//   mpiexec -n 2 /usr/bin/time -v bench_snapshot_write collective 1000000 /tmp/snap
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/dense_bed_scene.h"
#include "dem/boundary/container.h"
#include "dem/engine/simulation.h"
#include "dem/files/atomic_file.h"
#include "dem/io/force_network.h"
#include "dem/io/hdf5_snapshot.h"
#include "dem/parallel/mpi_start.h"

namespace {

using namespace upgrain;

int measure(const std::string& mode, long n, const std::filesystem::path& folder, int repeats) {
  const bool network = mode.rfind("network-", 0) == 0;
  // Apart (no contacts: the snapshot alone is measured), or pressed together by 0.1 % of a radius.
  const double r = 1.5e-3, spacing = (network ? 1.999 : 2.2) * r;
  const long side = static_cast<long>(std::ceil(std::cbrt(static_cast<double>(n))));
  dem::SceneConfig scene = bench::benchmark_scene(static_cast<double>(side) * spacing);
  scene.container.height = static_cast<double>(side) * spacing;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  dem::ParticleStore p;
  if (rank == 0) {
    p.reserve(static_cast<std::size_t>(n));
    for (long k = 0; k < n; ++k) {
      const dem::Vec3 x((0.5 + static_cast<double>(k % side)) * spacing,
                        (0.5 + static_cast<double>((k / side) % side)) * spacing,
                        (0.5 + static_cast<double>(k / (side * side))) * spacing);
      p.add_sphere(k, r, scene.particles.material.density, x, dem::Vec3::Zero(), dem::Vec3::Zero());
    }
  }
  dem::Simulation sim(scene, std::move(p), MPI_COMM_WORLD);
  if (network) {
    sim.request_contacts();
    sim.step();
  }
  if (rank == 0) dem::io::create_folder(folder);
  std::optional<dem::io::ForceNetworkRecorder> recorder;
  if (mode == "network-collective") recorder.emplace(MPI_COMM_WORLD, folder);
  double seconds = 0.0;
  std::uintmax_t bytes = 0;
  for (int k = 0; k < repeats; ++k) {
    std::filesystem::path file = folder / ("snapshot_" + mode + "_" + std::to_string(k) + ".h5");
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<dem::Vec3> forces = sim.wall_forces();
    const dem::PeriodicCell& cell = sim.decomposition().cell();
    if (mode == "network-gather") {
      const dem::ParticleStore& all = sim.whole_state();
      const std::vector<dem::ContactRecord> contacts = sim.gather_contacts_by_id();
      sim.on_root([&] {
        dem::io::write_force_network(file, all, dem::io::force_network(all, sim.walls(), contacts, cell), 0.0,
                                     k);
      });
    } else if (mode == "network-collective") {
      dem::IdSlice s = sim.whole_state_slice();
      const std::vector<dem::ContactRecord> contacts = sim.contacts_of_rows(s);
      recorder->write({s.grains, s.first_row, s.rows}, s.total_rows, sim.walls(), contacts, cell, 0.0, k);
      char name[64];
      std::snprintf(name, sizeof name, "contacts_%09d.h5", k);
      file = folder / "force_network" / name;
    } else if (mode == "gather") {
      const dem::ParticleStore& all = sim.whole_state();
      sim.on_root([&] { dem::io::write_snapshot(file, all, sim.walls(), forces, 0.0, 0); });
    } else {
      const dem::IdSlice s = sim.whole_state_slice();
      dem::io::write_snapshot(MPI_COMM_WORLD, file, s.grains, {s.first_row, s.total_rows, false, s.shapes},
                              sim.walls(), forces, 0.0, 0);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (rank == 0) bytes = std::filesystem::file_size(file);
  }
  if (rank == 0) {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const double t = seconds / repeats;
    std::printf("%s: %ld grains, %d ranks: %.3f s per file of %.1f MB, %.0f MB/s\n", mode.c_str(), n, size, t,
                static_cast<double>(bytes) / 1e6, static_cast<double>(bytes) / 1e6 / t);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::MpiSession mpi(argc, argv);
  const std::string mode = argc > 1 ? argv[1] : "";
  if ((mode == "gather" || mode == "collective" || mode == "network-gather" ||
       mode == "network-collective") &&
      argc >= 4)
    return measure(mode, std::atol(argv[2]), argv[3], argc > 4 ? std::atoi(argv[4]) : 3);
  std::fprintf(stderr,
               "usage: bench_snapshot_write gather|collective|network-gather|network-collective N FOLDER "
               "[repeats]\n");
  return 2;
}
