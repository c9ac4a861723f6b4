// The output manifest and its journal (docs/output.md, "Manifest"): every file written through
// the library is listed with its size and checksum, an append continues the checksum exactly,
// and the audit tells the run's files from foreign, changed, missing and half-written ones.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/output_manifest.h"
#include "dem/files/undated_vtk.h"
#include "dem/io/csv_series.h"

namespace fs = std::filesystem;
using namespace upgrain::dem::io;

namespace {

fs::path fresh_folder(const std::string& name) {
  const fs::path f =
      fs::temp_directory_path() / ("upgrain_manifest_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(f);
  fs::create_directories(f);
  return f;
}

void put(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// Opens a journal for the test and closes it on every way out.
struct OpenJournal {
  explicit OpenJournal(const fs::path& folder) {
    OutputManifest m;
    m.run_id = "test-run";
    m.scene_hash = "0123456789abcdef";
    open_output_journal(folder, m);
  }
  ~OpenJournal() { close_output_journal("finished"); }
};

}  // namespace

TEST(OutputManifest, TextRoundTripKeepsEveryEntry) {
  OutputManifest m;
  m.run_id = "20261206T000000Z-host-1-abcd";
  m.scene_hash = "00ff00ff00ff00ff";
  m.status = "stopped";
  m.entries["snapshots"] = {ManifestEntry::Kind::folder, 0, 0};
  m.entries["snapshots/particles_000000001.h5"] = {ManifestEntry::Kind::file, 1234, 0xfedcba9876543210ULL};
  m.entries["a name with spaces.csv"] = {ManifestEntry::Kind::file, 0, 0xcbf29ce484222325ULL};
  m.entries["report.md"] = {ManifestEntry::Kind::being_written, 0, 0};
  const OutputManifest back = OutputManifest::parse(m.to_text(), "manifest");
  EXPECT_EQ(back.run_id, m.run_id);
  EXPECT_EQ(back.scene_hash, m.scene_hash);
  EXPECT_EQ(back.status, "stopped");
  ASSERT_EQ(back.entries.size(), m.entries.size());
  for (const auto& [path, e] : m.entries) {
    ASSERT_EQ(back.entries.count(path), 1u) << path;
    EXPECT_EQ(back.entries.at(path).kind, e.kind) << path;
    EXPECT_EQ(back.entries.at(path).size, e.size) << path;
    EXPECT_EQ(back.entries.at(path).hash, e.hash) << path;
  }
}

TEST(OutputManifest, MalformedTextIsRefusedWithItsLine) {
  EXPECT_THROW(OutputManifest::parse("", "m"), upgrain::Error);
  EXPECT_THROW(OutputManifest::parse("not a manifest\n", "m"), upgrain::Error);
  OutputManifest m;
  m.run_id = "r";
  const std::string good = m.to_text();
  try {
    OutputManifest::parse(good + "F 12 nothex path\n", "m");
    FAIL() << "a bad checksum was accepted";
  } catch (const upgrain::Error& e) {
    EXPECT_NE(std::string(e.what()).find("m:5:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OutputManifest::parse(good + "X - - path\n", "m"), upgrain::Error);
  EXPECT_THROW(OutputManifest::parse(good + "F 1 0123456789abcdef\n", "m"), upgrain::Error);
}

TEST(OutputJournal, ListsWhatTheLibraryWritesWithSizeAndChecksum) {
  const fs::path folder = fresh_folder("journal");
  {
    OpenJournal journal(folder);
    create_folder(folder / "tables" / "deep");
    write_text_atomically(folder / "tables" / "deep" / "a.txt", "alpha\n");
    CsvSeries series(folder / "series.csv", "# t,x\n");
    series.append("0,1\n");
    series.append("1,2\n3,4\n");  // continued checksum, not a re-read
    write_text_atomically(folder / "outside_of_nothing.txt", "x");
    // Outside the folder: not listed.
    write_text_atomically(
        fs::temp_directory_path() / ("upgrain_manifest_outside_" + std::to_string(::getpid())), "y");
    const OutputManifest m = *journal_manifest();
    for (const char* f : {"tables/deep/a.txt", "series.csv", "outside_of_nothing.txt"}) {
      ASSERT_EQ(m.entries.count(f), 1u) << f;
      const ManifestEntry& e = m.entries.at(f);
      EXPECT_EQ(e.kind, ManifestEntry::Kind::file) << f;
      const FileDigest d = digest_file(folder / f);
      EXPECT_EQ(e.size, d.size) << f;
      EXPECT_EQ(e.hash, d.hash) << f;
    }
    EXPECT_EQ(m.entries.at("tables").kind, ManifestEntry::Kind::folder);
    EXPECT_EQ(m.entries.at("tables/deep").kind, ManifestEntry::Kind::folder);
    EXPECT_EQ(m.entries.size(), 5u);
  }
  fs::remove(fs::temp_directory_path() / ("upgrain_manifest_outside_" + std::to_string(::getpid())));
  // Saved on disk as it was in memory, with its final status.
  const OutputManifest saved = read_manifest(folder);
  EXPECT_EQ(saved.status, "finished");
  EXPECT_EQ(saved.entries.size(), 5u);
  const FolderAudit a = audit_folder(folder, saved);
  EXPECT_TRUE(a.foreign.empty());
  EXPECT_TRUE(a.changed.empty());
  EXPECT_TRUE(a.missing.empty());
  EXPECT_TRUE(a.leftovers.empty());
  EXPECT_EQ(a.ours.size(), 4u);                 // three files and the bookkeeping folder
  EXPECT_EQ(a.folders.front(), "tables/deep");  // deepest first
  fs::remove_all(folder);
}

TEST(OutputJournal, AuditTellsForeignChangedMissingAndHalfWritten) {
  const fs::path folder = fresh_folder("audit");
  fs::create_directories(folder / "premade");  // the user's folder, which the run writes into
  {
    OpenJournal journal(folder);
    write_text_atomically(folder / "premade" / "run.txt", "the run's");
    create_folder(folder / "snapshots");
    write_text_atomically(folder / "snapshots" / "s_1.h5", "one");
    write_text_atomically(folder / "summary.json", "{}");
    write_text_atomically(folder / "report.md", "report");
    write_text_atomically(folder / "gone.csv", "g");
    note_writing(folder / "being.csv");  // killed while writing it
    put(folder / "being.csv", "half");
  }
  put(folder / "summary.json", "{\"edited\": 1}");      // changed
  fs::remove(folder / "gone.csv");                      // missing
  put(folder / "report.md.tmp.4242", "half a report");  // a temporary file of a listed name
  fs::create_directories(folder / "thesis");
  put(folder / "thesis" / "a.tex", "x");        // foreign folder
  put(folder / "snapshots" / "mine.txt", "x");  // foreign file in a listed folder
  put(folder / "premade" / "notes.txt", "x");   // and in a folder the run did not make
  const FolderAudit a = audit_folder(folder, read_manifest(folder));
  ASSERT_EQ(a.changed.size(), 1u);
  EXPECT_EQ(a.changed[0].rfind("summary.json", 0), 0u);
  EXPECT_EQ(a.missing, std::vector<std::string>{"gone.csv"});
  EXPECT_EQ(a.foreign, (std::vector<std::string>{"premade/notes.txt", "snapshots/mine.txt", "thesis/"}));
  EXPECT_NE(std::find(a.ours.begin(), a.ours.end(), "premade/run.txt"), a.ours.end());
  EXPECT_EQ(a.leftovers, (std::vector<std::string>{"being.csv", "report.md.tmp.4242"}));
  EXPECT_EQ(a.folders, std::vector<std::string>{"snapshots"});
  fs::remove_all(folder);
}

TEST(OutputJournal, ClosedJournalListsNothing) {
  const fs::path folder = fresh_folder("closed");
  EXPECT_FALSE(output_journal_open());
  write_text_atomically(folder / "a.txt", "a");
  EXPECT_FALSE(has_manifest(folder));
  EXPECT_TRUE(journal_paths().empty());
  fs::remove_all(folder);
}

// deal.II's creation date in both orders it writes (a .pvtu record: date, then time; write_vtu
// with its default flags: time, then date) goes, and nothing else of the file changes.
TEST(UndatedVtk, TakesOutTheDateInEitherOrder) {
  const std::string tail = "\n-->\n<VTKFile type=\"UnstructuredGrid\">\n";
  const std::string undated =
      "# vtk DataFile Version 3.0\n#This file was generated by the deal.II library." + tail;
  EXPECT_EQ(upgrain::dem::io::undated_vtk("# vtk DataFile Version 3.0\n#This file was generated by the "
                                          "deal.II library on 2026/12/6 at 8:37:05" +
                                          tail),
            undated);
  EXPECT_EQ(upgrain::dem::io::undated_vtk("# vtk DataFile Version 3.0\n#This file was generated by the "
                                          "deal.II library on 8:37:05 at 2026/12/6" +
                                          tail),
            undated);
  EXPECT_EQ(upgrain::dem::io::undated_vtk(undated), undated);
}
