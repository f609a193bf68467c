// SPDX-License-Identifier: MIT
// The run directory's files at the io level (docs/case-format.md, "Run directories"): every
// bundle element round-trips through the checkpoint (the aggregate has no trial point), an
// edited checkpoint fails its checksum, JSON nesting is bounded before parsing, special files
// are refused without blocking, and a write the system cuts short throws FileSystemError and
// keeps the previous file — simulated with /dev/full and with a file size limit (RLIMIT_FSIZE),
// which fails a write with EFBIG as a full disk fails it with ENOSPC.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "atomic_file.hpp"
#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/file_error.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/measurements.hpp"
#include "frictopt/io/pvd_writer.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/vtu_writer.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;
using frictopt::testing::read_text;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

RunCheckpoint checkpoint_with_every_kind_of_element() {
  RunCheckpoint c;
  c.method.iteration = 31;
  c.method.evaluations = 40;
  c.method.serious_steps = 20;
  c.method.null_steps = 11;
  c.method.x = Eigen::Vector3d(0.1, 0.2, 0.3);
  c.method.f = 2.0;
  c.method.t = 0.5;
  c.method.t_max = 1.0;
  c.method.z_prev = Eigen::Vector3d::Ones();
  c.method.bundle.push_back({Eigen::Vector3d(1, 2, 3), 0.0, 0.0, 0.0, c.method.x, true});
  optim::BundleElement piece{Eigen::Vector3d(-1, 0.5, 0), 0.3, 0.0, 0.3, c.method.x, false};
  piece.piece_gap = 0.25;
  c.method.bundle.push_back(piece);
  c.method.bundle.push_back({Eigen::Vector3d(0.5, 0.5, 1.0 / 3.0), 0.1, 0.2, 0.1, Eigen::Vector3d(0, 0, 1), false});
  optim::BundleElement aggregate{Eigen::Vector3d(0.2, -0.1, 1e-17), 0.05, 0.7, 0.06, Eigen::VectorXd(), false};
  aggregate.piece_gap = 0.125;
  c.method.bundle.push_back(aggregate);
  c.method.restarts = 2;
  c.method.tightenings = 1;
  c.method.test_factor = 0.1;
  c.method.resolution_reached = true;
  c.method.bundle_size_used = 18;
  c.method.restart_checks = 2;  // a restart check in progress (docs/optim.md, "Restart check")
  c.method.check_value = 0.75;
  c.method.check_tolerance = 1.5e-5;
  c.method.check_iteration = c.method.iteration - 1;
  c.fingerprint.dim = 3;
  c.fingerprint.settings = {{"material.young", "1"}};
  c.fingerprint.case_hash = hash_settings(c.fingerprint.settings);
  c.fingerprint.num_nodes = 8;
  c.initial_cost = 4.0;
  // A loading program's steps: a cold start and a warm one (load cases, a cost along a program).
  c.history_warm_starts = {Eigen::VectorXd(), Eigen::VectorXd::LinSpaced(6, 0.1, 0.6) / 7.0};
  return c;
}

TEST(RunFilesCheckpoint, EveryBundleElementRoundTripsTheAggregateToo) {
  // The aggregate element has no trial point (y = []): it was written and then refused as
  // "bundle[k].y = a list of 0 numbers; expected n numbers", so no run resumed past it.
  const RunCheckpoint c = checkpoint_with_every_kind_of_element();
  const RunCheckpoint back = checkpoint_from_json(parse_json(to_json_string(checkpoint_to_json(c), 2)));
  ASSERT_EQ(back.method.bundle.size(), c.method.bundle.size());
  for (std::size_t i = 0; i < c.method.bundle.size(); ++i) {
    SCOPED_TRACE(i);
    const auto& a = c.method.bundle[i];
    const auto& b = back.method.bundle[i];
    EXPECT_EQ(a.g, b.g);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.lin_err, b.lin_err);
    EXPECT_EQ(a.distance, b.distance);
    EXPECT_EQ(a.locality, b.locality);
    EXPECT_EQ(a.piece_gap, b.piece_gap);
    EXPECT_EQ(a.is_center, b.is_center);
    EXPECT_EQ(a.is_aggregate(), b.is_aggregate());
  }
  EXPECT_TRUE(back.method.bundle.back().is_aggregate());
  ASSERT_EQ(back.history_warm_starts.size(), 2u);
  EXPECT_EQ(back.history_warm_starts[0].size(), 0);
  EXPECT_EQ(back.history_warm_starts[1], c.history_warm_starts[1]);  // bit for bit
  // The method's safeguards continue after the resume.
  EXPECT_EQ(back.method.restarts, 2);
  EXPECT_EQ(back.method.tightenings, 1);
  EXPECT_EQ(back.method.test_factor, 0.1);
  EXPECT_TRUE(back.method.resolution_reached);
  EXPECT_EQ(back.method.bundle_size_used, 18);
  // So does a restart check in progress (a resume once started it again).
  EXPECT_EQ(back.method.restart_checks, 2);
  EXPECT_EQ(back.method.check_value, 0.75);
  EXPECT_EQ(back.method.check_tolerance, 1.5e-5);
  EXPECT_EQ(back.method.check_iteration, c.method.iteration - 1);
}

TEST(RunFilesCheckpoint, AnEditedValueFailsTheChecksum) {
  JsonValue j = checkpoint_to_json(checkpoint_with_every_kind_of_element());
  j["f"] = 1.8;  // a falsified centre value, well-formed and in range
  try {
    (void)checkpoint_from_json(j, "run/checkpoint.json");
    FAIL() << "a falsified centre value was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("run/checkpoint.json: checksum"), std::string::npos) << e.what();
  }
  JsonValue bad_y = checkpoint_to_json(checkpoint_with_every_kind_of_element());
  JsonValue::Array bundle = bad_y.at("bundle").as_array();
  bundle[2]["y"] = JsonValue(Eigen::VectorXd::Ones(2).eval());
  bad_y["bundle"] = JsonValue(bundle);
  EXPECT_THROW((void)checkpoint_from_json(bad_y), InvalidInput);  // neither [] nor n numbers
}

TEST(RunFilesCheckpoint, ACentreElementThatDisagreesWithXIsRefused) {
  RunCheckpoint c = checkpoint_with_every_kind_of_element();
  c.method.bundle[0].y = Eigen::Vector3d(0.1, 0.2, 0.4);  // written consistently (checksum) but not at x
  try {
    (void)checkpoint_from_json(checkpoint_to_json(c), "cp");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("bundle[0] is the centre's element"), std::string::npos) << e.what();
  }
}

TEST(RunFilesJson, NestingIsBoundedBeforeParsing) {
  for (const std::string& text : {std::string(1'000'000, '['), "{\"a\":" + std::string(100'000, '[')}) {
    try {
      (void)parse_json(text);
      FAIL() << "accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("nested deeper than 64"), std::string::npos) << e.what();
    }
  }
  // Brackets inside strings do not count; 64 levels are fine.
  EXPECT_NO_THROW((void)parse_json("{\"a\": \"" + std::string(1000, '[') + "\"}"));
  EXPECT_NO_THROW((void)parse_json(std::string(64, '[') + std::string(64, ']')));
}

class RunFilesInput : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(RunFilesInput, SpecialFilesAreRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "checkpoint.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto expect_fifo_refused = [&](const std::function<void()>& read) {
    try {
      read();
      ADD_FAILURE() << "a FIFO was read";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("a FIFO"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fifo.string()), std::string::npos) << e.what();
    }
  };
  expect_fifo_refused([&] { (void)read_checkpoint(fifo); });
  expect_fifo_refused([&] { (void)read_design_file(fifo, 3); });
  expect_fifo_refused([&] { (void)read_measurements(fifo); });
  expect_fifo_refused([&] { (void)read_json_file(fifo, "a file"); });
  EXPECT_THROW((void)read_design_file(dir_, 3), InvalidInput);  // a directory
  write(dir_ / "d.json", "{\"alpha\": [1, 2");
  try {
    (void)read_design_file(dir_ / "d.json", 2);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("d.json: the design file is not valid JSON"), std::string::npos) << e.what();
  }
}

TEST(RunFilesWrite, AShortWriteToAFullDeviceThrowsFileSystemError) {
  const int fd = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  if (fd < 0) GTEST_SKIP() << "no /dev/full on this machine";
  try {
    detail::write_all(fd, std::string(10000, 'x'), "target.vtu");
    ADD_FAILURE() << "a write to /dev/full succeeded";
  } catch (const FileSystemError& e) {
    EXPECT_EQ(e.code().value(), ENOSPC);
    EXPECT_NE(std::string(e.what()).find("target.vtu"), std::string::npos) << e.what();
  }
  ::close(fd);
}

// Runs `write` in a child whose files may not grow beyond 4 KiB; true when it threw
// FileSystemError (and nothing else).
bool fails_with_file_system_error_under_a_size_limit(const std::function<void()>& write) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    int code = 1;
    try {
      write();
      code = 2;  // no error
    } catch (const FileSystemError&) {
      code = 0;
    } catch (...) {
      code = 3;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

class RunFilesFullDisk : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(RunFilesFullDisk, EveryWriterKeepsThePreviousFile) {
  const std::string big(100000, 'x');
  // JSON (summary, checkpoint, design, certificate).
  write(dir_ / "summary.json", "{\"old\": 1}\n");
  JsonValue json = JsonValue::object();
  json["text"] = big;
  EXPECT_TRUE(fails_with_file_system_error_under_a_size_limit([&] { write_json(dir_ / "summary.json", json); }));
  EXPECT_EQ(read_text(dir_ / "summary.json"), "{\"old\": 1}\n");
  // VTU.
  write(dir_ / "state.vtu", "previous vtu");
  VtuGrid grid;
  grid.points = Eigen::MatrixXd::Random(20000, 3);
  grid.point_data.push_back(DataArray::scalars("p", Eigen::VectorXd::Random(20000)));
  EXPECT_TRUE(fails_with_file_system_error_under_a_size_limit([&] { write_vtu(dir_ / "state.vtu", grid); }));
  EXPECT_EQ(read_text(dir_ / "state.vtu"), "previous vtu");
  // A whole CSV table (contact CSV, fit.csv).
  write(dir_ / "fit.csv", "a\n1\n");
  EXPECT_TRUE(fails_with_file_system_error_under_a_size_limit([&] {
    CsvWriter csv(dir_ / "fit.csv", {"a"}, CsvWriter::Mode::kReplace);
    for (int k = 0; k < 10000; ++k) csv.write_row({std::int64_t{k}});
    csv.finish();
  }));
  EXPECT_EQ(read_text(dir_ / "fit.csv"), "a\n1\n");
  // A growing history: the failed row is an error, not silence.
  EXPECT_TRUE(fails_with_file_system_error_under_a_size_limit([&] {
    CsvWriter csv(dir_ / "history.csv", {"a"});
    for (int k = 0; k < 10000; ++k) csv.write_row({std::int64_t{k}});
  }));
  // PVD.
  write(dir_ / "s.pvd", "previous pvd");
  std::vector<PvdEntry> entries;
  for (int k = 0; k < 2000; ++k) entries.push_back({double(k), fs::path("s_iter" + std::to_string(k) + ".vtu")});
  EXPECT_TRUE(fails_with_file_system_error_under_a_size_limit([&] { write_pvd(dir_ / "s.pvd", entries); }));
  EXPECT_EQ(read_text(dir_ / "s.pvd"), "previous pvd");
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();  // no temporary left behind
}

class RunFilesDirectory : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(RunFilesDirectory, SomeonesCaseTomlIsNeverReplaced) {
  const std::string case_text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "tests/cli/data/small2d.toml");
  write(dir_ / "mine.toml", case_text);
  fs::create_directories(dir_ / "out");
  write(dir_ / "out" / "case.toml", "# someone's\n" + case_text);
  EXPECT_THROW(RunDirectory(dir_ / "out", RunOpening::kNewRun, dir_ / "mine.toml"), InvalidInput);
  EXPECT_THROW(RunDirectory(dir_ / "out", RunOpening::kForce, dir_ / "mine.toml"), InvalidInput);
  {
    RunDirectory python_run(dir_ / "out", RunOpening::kOutput);
    EXPECT_THROW(python_run.store_case_text(case_text, dir_ / "mine.toml"), InvalidInput);
  }
  EXPECT_EQ(read_text(dir_ / "out" / "case.toml"), "# someone's\n" + case_text);
  // The copy this run would write anyway (an interrupted start) is no loss.
  write(dir_ / "out" / "case.toml", case_text);
  RunDirectory again(dir_ / "out", RunOpening::kNewRun, dir_ / "mine.toml");
  EXPECT_EQ(again.store_case(), dir_ / "out" / "case.toml");
}

TEST_F(RunFilesDirectory, ThePythonCaseCopyNamesTheMeshFileAbsolutelyAsTheCliDoes) {
  const std::string text = "[mesh]\nfile = \"body.msh\"\n";
  RunDirectory run(dir_ / "run", RunOpening::kNewRun);
  run.store_case_text(text, dir_ / "cases" / "case.toml");
  EXPECT_EQ(read_text(dir_ / "run" / "case.toml"), case_copy_text(text, dir_ / "cases" / "case.toml"));
  EXPECT_NE(read_text(dir_ / "run" / "case.toml").find((dir_ / "cases" / "body.msh").string()), std::string::npos)
      << read_text(dir_ / "run" / "case.toml");
}

TEST(RunFilesCase, AnOutputNameLongerThanItsFilesAllowIsRefused) {
  const std::string base = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "tests/cli/data/small2d.toml");
  EXPECT_NO_THROW((void)parse_case(base + "\n[output]\nname = \"" + std::string(224, 'n') + "\"\n", "c.toml"));
  try {
    (void)parse_case(base + "\n[output]\nname = \"" + std::string(231, 'n') + "\"\n", "c.toml");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("output.name"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 224 bytes"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frictopt::io
