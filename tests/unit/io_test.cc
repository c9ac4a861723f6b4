// Snapshots read back sorted by id at full precision; atomic files leave nothing behind
// when abandoned.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "dem/boundary/container.h"
#include "dem/files/atomic_file.h"
#include "dem/io/csv_series.h"
#include "dem/io/hdf5_snapshot.h"

using namespace upgrain::dem;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("upgrain_io_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}
}  // namespace

TEST(AtomicFile, AbandonedFileLeavesNoTrace) {
  const fs::path target = scratch("abandoned.txt");
  {
    io::AtomicFile f(target);
    std::ofstream(f.temporary_path()) << "partial";
  }
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(target.parent_path()));
  io::write_text_atomically(target, "done");
  std::ifstream in(target);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "done");
  fs::remove_all(target.parent_path());
}

TEST(CsvSeries, AppendsRowsAfterTheHeader) {
  const fs::path target = scratch("series.csv");
  {
    // A file left by an earlier run (Output/overwrite = true) is replaced, not appended to.
    std::ofstream(target) << "old,row\n";
  }
  io::CsvSeries csv(target, "# comment\na,b\n");
  csv.append("1,2\n");
  csv.append("");
  csv.append("3,4\n5,6\n");
  std::ifstream in(target);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "# comment\na,b\n1,2\n3,4\n5,6\n");
  // Nothing but the table in the folder: no temporary files left.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(target.parent_path())) ++entries;
  EXPECT_EQ(entries, 1);
  fs::remove_all(target.parent_path());
  // A folder that has gone away is an error naming the file, not a silent loss.
  io::CsvSeries gone(target, "h\n");
  try {
    gone.append("x\n");
    ADD_FAILURE() << "no error for a missing folder";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("series.csv"), std::string::npos) << e.what();
  }
}

TEST(Snapshot, RoundTripSortedById) {
  ParticleStore p;
  p.add_sphere(42, 1e-3, 2650, Vec3(0.1, 0.2, 1.0 / 3.0), Vec3(1, 2, 3), Vec3(4, 5, 6));
  p.add_sphere(7, 2e-3, 2650, Vec3(0.4, 0.5, 0.6), Vec3(-1, -2, -3), Vec3::Zero());
  const auto walls = make_open_box({});
  const fs::path path = scratch("snap.h5");
  io::write_snapshot(path, p, walls, std::vector<Vec3>(walls.size(), Vec3(0, 0, 9.5)), 0.25, 100);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::int64_t ids[2];
  double pos[6], force[15];
  hid_t d = H5Dopen2(f, "/particles/id", H5P_DEFAULT);
  H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, ids);
  H5Dclose(d);
  d = H5Dopen2(f, "/particles/position", H5P_DEFAULT);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, pos);
  H5Dclose(d);
  d = H5Dopen2(f, "/walls/force", H5P_DEFAULT);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, force);
  H5Dclose(d);
  H5Fclose(f);
  EXPECT_EQ(ids[0], 7);
  EXPECT_EQ(ids[1], 42);
  EXPECT_EQ(pos[3], 0.1);
  EXPECT_EQ(pos[5], 1.0 / 3.0);  // full precision
  EXPECT_EQ(force[2], 9.5);
  fs::remove_all(path.parent_path());
}
