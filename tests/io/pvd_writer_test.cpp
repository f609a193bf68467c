// SPDX-License-Identifier: MIT
// PVD collections: content, relative paths, ordering of times, and that the file on disk is
// complete after every addition.
#include "frictopt/io/pvd_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;

using frictopt::testing::read_text;

class PvdFiles : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(PvdFiles, CollectionListsEveryDatasetWithItsTime) {
  const std::vector<PvdEntry> entries = {
      {0, "run_0000.vtu"}, {1.5, "sub dir/run_0001.vtu"}, {2, "a&b.vtu"}};
  write_pvd(dir_ / "run.pvd", entries);
  EXPECT_EQ(read_text(dir_ / "run.pvd"),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"run_0000.vtu\"/>\n"
            "    <DataSet timestep=\"1.5\" group=\"\" part=\"0\" file=\"sub dir/run_0001.vtu\"/>\n"
            "    <DataSet timestep=\"2\" group=\"\" part=\"0\" file=\"a&amp;b.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  EXPECT_FALSE(fs::exists(dir_ / "run.pvd.tmp")) << "the temporary file is renamed away";
}

TEST_F(PvdFiles, WriterKeepsTheFileCompleteAfterEveryAddition) {
  PvdWriter writer(dir_ / "series.pvd");
  EXPECT_NE(read_text(dir_ / "series.pvd").find("<Collection>\n  </Collection>"),
            std::string::npos);
  writer.add(0, "it_0.vtu");
  const std::string after_one = read_text(dir_ / "series.pvd");
  EXPECT_NE(after_one.find("file=\"it_0.vtu\""), std::string::npos);
  EXPECT_NE(after_one.find("</VTKFile>"), std::string::npos);
  writer.add(1, dir_ / "it_1.vtu");  // absolute: stored relative to the .pvd
  const std::string after_two = read_text(dir_ / "series.pvd");
  EXPECT_NE(after_two.find("timestep=\"1\" group=\"\" part=\"0\" file=\"it_1.vtu\""),
            std::string::npos)
      << after_two;
  EXPECT_EQ(writer.entries().size(), 2u);
}

TEST_F(PvdFiles, NonIncreasingTimesAreRejected) {
  PvdWriter writer(dir_ / "series.pvd");
  writer.add(3, "a.vtu");
  EXPECT_THROW(writer.add(3, "b.vtu"), InvalidInput);
  EXPECT_THROW(writer.add(2, "b.vtu"), InvalidInput);
  EXPECT_EQ(writer.entries().size(), 1u);
}

TEST_F(PvdFiles, BadEntriesAndPathsAreInvalidInput) {
  const std::vector<PvdEntry> nan_time = {{std::nan(""), "a.vtu"}};
  EXPECT_THROW(write_pvd(dir_ / "x.pvd", nan_time), InvalidInput);
  const std::vector<PvdEntry> absolute = {{0, "/tmp/a.vtu"}};
  EXPECT_THROW(write_pvd(dir_ / "x.pvd", absolute), InvalidInput);
  EXPECT_THROW(PvdWriter(dir_ / "missing" / "x.pvd"), FileSystemError);  // the file system's refusal (exit 5)
}

}  // namespace
}  // namespace frictopt::io
