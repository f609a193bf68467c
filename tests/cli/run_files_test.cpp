// SPDX-License-Identifier: MIT
// The run directory's files through the command line (docs/case-format.md, "Run directories"):
// a resume across the aggregate element and the cuts of the pieces of a max repeats the run bit
// for bit; edited, damaged, foreign or special files are refused (exit 2, naming the file) and
// never replaced; a file system that refuses a write ends in exit 5 with the previous file kept.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>

#include "common/cli_runner.hpp"
#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::read_text;
using frictopt::testing::replace_key;
using frictopt::testing::write_text;
using frictopt::testing::RunResult;

RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

fs::path fresh(const std::string& name) {
  const fs::path dir = frictopt::testing::fresh_directory("run_files_" + name);
  fs::create_directories(dir);
  return dir;
}

// The thesis' example 5.2.1 (2D, 450 nodes): a few iterations take well under a second.
std::string ex521(int max_iterations) {
  std::string text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases2d/ex521-target-pressure/case.toml");
  text = replace_key(text, "max_iterations", std::to_string(max_iterations));
  text = replace_key(text, "every", "2");
  return replace_key(text, "name", "\"r\"");
}

std::string worst_case(int max_iterations) {
  return replace_key(read_text(fs::path(FRICTOPT_SOURCE_DIR) / "tests/cli/data/small_worst_case.toml"),
                     "max_iterations", std::to_string(max_iterations));
}

void expect_refused(const RunResult& r, std::initializer_list<std::string_view> fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (std::string_view f : fragments) EXPECT_NE(r.output.find(f), std::string::npos) << "'" << f << "' not in:\n" << r.output;
}

std::string without_timings(const std::string& csv) {  // history.csv without its last three columns
  return std::regex_replace(csv, std::regex(R"(,[^,\n]*,[^,\n]*,[^,\n]*\n)"), "\n");
}

// A run of `base` directory name made in one go, resumed at every iteration of `stops`.
void expect_resumes_repeat_the_run(const fs::path& dir, const std::function<std::string(int)>& make_case,
                                   std::initializer_list<int> stops, int total,
                                   const std::function<void(const frictopt::io::JsonValue&, int)>& check_checkpoint) {
  write_text(dir / "full.toml", make_case(total));
  const RunResult full = run("optimize " + (dir / "full.toml").string() + " -o " + (dir / "a").string());
  ASSERT_EQ(full.exit_code, 0) << full.output;
  bool first = true;
  for (int stop : stops) {
    if (first) {
      write_text(dir / "part.toml", make_case(stop));
      const RunResult r = run("optimize " + (dir / "part.toml").string() + " -o " + (dir / "b").string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
      first = false;
    } else {
      write_text(dir / "b" / "case.toml", replace_key(read_text(dir / "b" / "case.toml"), "max_iterations", std::to_string(stop)));
      const RunResult r = run("optimize " + (dir / "b" / "case.toml").string() + " -o " + (dir / "b").string() + " --resume");
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    check_checkpoint(frictopt::io::parse_json(read_text(dir / "b" / "checkpoint.json")), stop);
  }
  write_text(dir / "b" / "case.toml", replace_key(read_text(dir / "b" / "case.toml"), "max_iterations", std::to_string(total)));
  const RunResult resumed = run("optimize " + (dir / "b" / "case.toml").string() + " -o " + (dir / "b").string() + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto a = frictopt::io::parse_json(read_text(dir / "a" / "summary.json"));
  const auto b = frictopt::io::parse_json(read_text(dir / "b" / "summary.json"));
  EXPECT_EQ(a.at("iterations").as_integer(), b.at("iterations").as_integer());
  EXPECT_EQ(a.at("alpha"), b.at("alpha"));
  EXPECT_EQ(a.at("final_cost").as_number(), b.at("final_cost").as_number());
  EXPECT_EQ(a.at("evaluations").as_integer(), b.at("evaluations").as_integer());
  EXPECT_EQ(without_timings(read_text(dir / "a" / "history.csv")), without_timings(read_text(dir / "b" / "history.csv")));
  // The checkpoints of the two runs hold the same method state (but the timings).
  auto ca = frictopt::io::parse_json(read_text(dir / "a" / "checkpoint.json"));
  auto cb = frictopt::io::parse_json(read_text(dir / "b" / "checkpoint.json"));
  EXPECT_EQ(ca.at("bundle"), cb.at("bundle"));
  EXPECT_EQ(ca.at("x"), cb.at("x"));
  EXPECT_EQ(ca.at("t"), cb.at("t"));
}

// --- Resume across the aggregate and the pieces' cuts ------------------------------------

TEST(RunFiles, AResumeAcrossTheAggregateAndThePiecesCutsRepeatsTheRunBitForBit) {
  // Once the bundle is full, the update replaces the dropped cuts by the aggregate element (no
  // trial point: y = []); a max of load cases adds the cuts of its pieces. Two resumes, each
  // from a checkpoint that holds both, give the uninterrupted run's numbers.
  const fs::path dir = fresh("resume_aggregate");
  int with_aggregate = 0;
  expect_resumes_repeat_the_run(dir, worst_case, {14, 27}, 40, [&](const frictopt::io::JsonValue& c, int stop) {
    bool aggregate = false, piece_cut = false;
    for (const auto& e : c.at("bundle").as_array()) {
      aggregate = aggregate || e.at("y").as_array().empty();
      piece_cut = piece_cut || (e.at("piece_gap").as_number() > 0.0 && !e.at("y").as_array().empty());
    }
    EXPECT_TRUE(piece_cut) << "no cut of a piece in the checkpoint of iteration " << stop;
    with_aggregate += aggregate;
  });
  EXPECT_GE(with_aggregate, 1) << "no checkpoint held the aggregate element";
}

TEST(RunFiles, AResumeOfTheLongTwoDimensionalExampleRepeatsTheRunBitForBit) {
  const fs::path dir = fresh("resume_ex521");
  expect_resumes_repeat_the_run(dir, ex521, {9, 23}, 36, [](const frictopt::io::JsonValue&, int) {});
}

// --- Edited, damaged and special run files ------------------------------------------------

TEST(RunFiles, AFalsifiedCheckpointOrHistoryIsRefused) {
  const fs::path dir = fresh("falsified");
  write_text(dir / "case.toml", ex521(4));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  const fs::path checkpoint = dir / "run" / "checkpoint.json";
  const std::string good = read_text(checkpoint);
  write_text(dir / "run" / "case.toml", replace_key(read_text(dir / "run" / "case.toml"), "max_iterations", "6"));
  // The centre's value made 10 % smaller: a well-formed number in range.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(good, m, std::regex(R"("f": ([-0-9.e+]+))")));
  const std::string falsified = std::to_string(std::stod(m[1].str()) * 0.9);
  write_text(checkpoint, std::regex_replace(good, std::regex(R"("f": [-0-9.e+]+)"), "\"f\": " + falsified,
                                            std::regex_constants::format_first_only));
  expect_refused(run(args + " --resume"), {"checkpoint.json", "checksum", "edited or damaged"});
  // A consistent checkpoint with a history whose theta at its iteration was changed.
  write_text(checkpoint, good);
  const fs::path history = dir / "run" / "history.csv";
  const std::string rows = read_text(history);
  const auto last_row = rows.rfind('\n', rows.size() - 2) + 1;
  std::string edited = rows.substr(last_row);
  const auto c1 = edited.find(',', edited.find(',', edited.find(',') + 1) + 1);  // after iteration,evaluations,step
  edited = edited.substr(0, c1 + 1) + "1" + edited.substr(edited.find(',', c1 + 1));
  write_text(history, rows.substr(0, last_row) + edited);
  expect_refused(run(args + " --resume"), {"history.csv:5", "theta"});
  write_text(history, rows);
  EXPECT_EQ(run(args + " --resume").exit_code, 0);
}

TEST(RunFiles, DamagedDuplicatedOrCopiedHistoryRowsAreRefused) {
  const fs::path dir = fresh("history_rows");
  write_text(dir / "case.toml", ex521(4));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  write_text(dir / "run" / "case.toml", replace_key(read_text(dir / "run" / "case.toml"), "max_iterations", "6"));
  const fs::path history = dir / "run" / "history.csv";
  const std::string rows = read_text(history);
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < rows.size();) {
    const std::size_t end = rows.find('\n', start);
    lines.push_back(rows.substr(start, end - start + 1));
    start = end + 1;
  }
  ASSERT_EQ(lines.size(), 5u);
  const auto join = [](const std::vector<std::string>& l) {
    std::string out;
    for (const auto& s : l) out += s;
    return out;
  };
  // NUL bytes in a row before the last.
  std::vector<std::string> nul = lines;
  nul[2].insert(3, std::string(4, '\0'));
  write_text(history, join(nul));
  expect_refused(run(args + " --resume"), {"history.csv:3", "damaged row"});
  // A duplicated row.
  std::vector<std::string> duplicated = lines;
  duplicated.insert(duplicated.begin() + 3, lines[2]);
  write_text(history, join(duplicated));
  expect_refused(run(args + " --resume"), {"history.csv:4", "iteration 2 after iteration 2"});
  // 100,000 copies of a row.
  std::vector<std::string> copied = lines;
  copied.insert(copied.begin() + 2, 100000, lines[1]);
  write_text(history, join(copied));
  expect_refused(run(args + " --resume"), {"history.csv:3", "iteration 1 after iteration 1"});
  write_text(history, rows);
  EXPECT_EQ(run(args + " --resume").exit_code, 0);
}

TEST(RunFiles, CertifyRefusesARunWhoseCaseWasEditedAfterTheRun) {
  const fs::path dir = fresh("certify_edited");
  write_text(dir / "case.toml", ex521(2));
  ASSERT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string()).exit_code, 0);
  const std::string copy = read_text(dir / "run" / "case.toml");
  write_text(dir / "run" / "case.toml", replace_key(copy, "young", "2.0e11"));
  expect_refused(run("certify " + (dir / "run").string()), {"case.toml", "material.young", "checkpoint"});
  write_text(dir / "run" / "case.toml", copy);
  const RunResult r = run("certify " + (dir / "run").string());
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.output;
}

TEST(RunFiles, AFifoInPlaceOfARunFileIsRefusedAtOnce) {
  const fs::path dir = fresh("fifo");
  write_text(dir / "case.toml", ex521(2));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  fs::remove(dir / "run" / "checkpoint.json");
  ASSERT_EQ(::mkfifo((dir / "run" / "checkpoint.json").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  // `timeout`: a hang (the old behaviour) ends the command instead of the test run.
  expect_refused(run("--help >/dev/null 2>&1; timeout 60 " + std::string(FRICTOPT_BINARY) + " " + args + " --resume"),
                 {"checkpoint.json", "a FIFO"});
  ASSERT_EQ(::mkfifo((dir / "design.json").c_str(), 0600), 0);
  expect_refused(run("check-gradient " + (dir / "case.toml").string() + " --design " + (dir / "design.json").string()),
                 {"design.json", "a FIFO"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST(RunFiles, DeeplyNestedOrDamagedJsonIsRefusedNamingTheFile) {
  const fs::path dir = fresh("nested");
  write_text(dir / "case.toml", ex521(2));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  const std::string checkpoint = read_text(dir / "run" / "checkpoint.json");
  write_text(dir / "run" / "checkpoint.json", std::string(200000, '[') + std::string(200000, ']'));
  expect_refused(run(args + " --resume"), {"checkpoint.json", "nested deeper than"});
  write_text(dir / "run" / "checkpoint.json", checkpoint);
  write_text(dir / "deep.json", "{\"alpha\": " + std::string(200000, '[') + std::string(200000, ']') + "}");
  expect_refused(run("check-gradient " + (dir / "case.toml").string() + " --design " + (dir / "deep.json").string()),
                 {"deep.json", "nested deeper than"});
  write_text(dir / "run" / "final_design.json", "{\"alpha\": [0.1, ");
  expect_refused(run("certify " + (dir / "run").string()), {"final_design.json", "not valid JSON"});
  write_text(dir / "run" / "final_design.json", "{\"alpha\": [\"a\"]}");
  expect_refused(run("certify " + (dir / "run").string()), {"final_design.json", "alpha[0]"});
}

// --- Files frictopt did not write ---------------------------------------------------------

TEST(RunFiles, SomeonesCaseTomlInTheOutputDirectoryIsNeverReplaced) {
  const fs::path dir = fresh("foreign_case");
  write_text(dir / "case.toml", ex521(2));
  fs::create_directories(dir / "theirs");
  const std::string theirs = "# a colleague's case\n" + ex521(3);
  write_text(dir / "theirs" / "case.toml", theirs);
  for (const char* option : {"", " --force"}) {
    SCOPED_TRACE(option);
    const RunResult r = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "theirs").string() + option);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("case.toml"), std::string::npos) << r.output;
    EXPECT_EQ(read_text(dir / "theirs" / "case.toml"), theirs);
  }
  // A run of ours in that directory may be replaced (--force) as before.
  ASSERT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "ours").string()).exit_code, 0);
  EXPECT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "ours").string() + " --force").exit_code, 0);
}

TEST(RunFiles, GenerateSyntheticNeverOverwritesTheCasesMeasurementFile) {
  const fs::path dir = fresh("synthetic");
  const fs::path source = fs::path(FRICTOPT_SOURCE_DIR) / "cases3d/identify-anisotropic";
  fs::copy_file(source / "case.toml", dir / "case.toml");
  fs::copy_file(source / "measurements.csv", dir / "measurements.csv");
  const std::string before = read_text(dir / "measurements.csv");
  expect_refused(run("identify " + (dir / "case.toml").string() + " --generate-synthetic -o " + dir.string()),
                 {"measurements.csv", "the case's own measurement file"});
  EXPECT_EQ(read_text(dir / "measurements.csv"), before);
  fs::create_directories(dir / "other");
  write_text(dir / "other" / "measurements.csv", "quantity,location,value,sigma\n");
  expect_refused(run("identify " + (dir / "case.toml").string() + " --generate-synthetic -o " + (dir / "other").string()),
                 {"measurements.csv", "not generated by frictopt"});
  EXPECT_EQ(read_text(dir / "other" / "measurements.csv"), "quantity,location,value,sigma\n");
}

TEST(RunFiles, AnArbitraryMeasurementFileIsNotEchoed) {
  const fs::path dir = fresh("binary_measurements");
  const fs::path source = fs::path(FRICTOPT_SOURCE_DIR) / "cases3d/identify-anisotropic";
  fs::copy_file(source / "case.toml", dir / "case.toml");
  std::string binary(100000, 'A');
  binary[10] = '\x01';
  binary[20] = '\xff';
  write_text(dir / "measurements.csv", binary);
  const RunResult r = run("identify " + (dir / "case.toml").string() + " -o " + (dir / "out").string());
  expect_refused(r, {"measurements.csv:1", "header"});
  EXPECT_LT(r.output.size(), 1000u) << r.output;
  EXPECT_EQ(r.output.find('\x01'), std::string::npos);
  EXPECT_EQ(r.output.find('\xff'), std::string::npos);
}

TEST(RunFiles, AnOutputNameTooLongForItsFilesIsRefusedByTheParser) {
  const fs::path dir = fresh("long_name");
  for (std::size_t length : {225u, 231u, 255u}) {
    SCOPED_TRACE(length);
    write_text(dir / "case.toml", replace_key(ex521(2), "name", "\"" + std::string(length, 'n') + "\""));
    expect_refused(run("solve " + (dir / "case.toml").string() + " -o " + (dir / "out").string()),
                   {"output.name", "at most 224 bytes"});
  }
  write_text(dir / "case.toml", replace_key(ex521(2), "name", "\"" + std::string(224, 'n') + "\""));
  const RunResult r = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// --- A file system that refuses writes ----------------------------------------------------

// frictopt run with its files limited to `kilobytes` (RLIMIT_FSIZE, SIGXFSZ ignored): a write
// beyond it fails with EFBIG, as a write to a full disk fails with ENOSPC.
RunResult run_with_file_limit(const std::string& arguments, int kilobytes) {
  return run("--help >/dev/null 2>&1; bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(kilobytes) + "; exec " +
             std::string(FRICTOPT_BINARY) + " " + arguments + "\"");
}

TEST(RunFiles, AFailedWriteKeepsThePreviousFileAndExitsFive) {
  const fs::path dir = fresh("short_write");
  write_text(dir / "case.toml", ex521(2));
  const std::string solve = "solve " + (dir / "case.toml").string() + " -o " + (dir / "out").string();
  ASSERT_EQ(run(solve).exit_code, 0);
  const std::string vtu = read_text(dir / "out" / "r.vtu");
  ASSERT_GT(vtu.size(), 20000u);
  const RunResult r = run_with_file_limit(solve, 16);
  EXPECT_EQ(r.exit_code, 5) << r.output;
  EXPECT_NE(r.output.find("r.vtu"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("wrote"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(dir / "out" / "r.vtu"), vtu);  // the previous complete file
  for (const auto& entry : fs::directory_iterator(dir / "out"))
    EXPECT_FALSE(entry.path().extension() == ".tmp") << entry.path();  // no temporary left
  // FCLIB's HDF5 writer (the library ends the process on a failed HDF5 call).
  const fs::path fclib_case = fs::path(FRICTOPT_SOURCE_DIR) / "tests/io/data/fclib3d.toml";
  const std::string fclib = "export-fclib " + fclib_case.string() + " " + (dir / "p.hdf5").string();
  ASSERT_EQ(run(fclib).exit_code, 0);
  const std::string hdf5 = read_text(dir / "p.hdf5");
  const RunResult f = run_with_file_limit(fclib, 8);
  EXPECT_EQ(f.exit_code, 5) << f.output;
  EXPECT_NE(f.output.find("p.hdf5"), std::string::npos) << f.output;
  EXPECT_EQ(read_text(dir / "p.hdf5"), hdf5);
}

TEST(RunFiles, AFullTmpfsKeepsThePreviousFileAndExitsFive) {
  const fs::path dir = fresh("tmpfs");
  write_text(dir / "case.toml", ex521(2));
  const fs::path mount_point = dir / "disk";
  fs::create_directories(mount_point);
  if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=1m") != 0)
    GTEST_SKIP() << "cannot mount a 1 MB tmpfs here (needs root): the full-disk case is covered by "
                    "AFailedWriteKeepsThePreviousFileAndExitsFive";
  struct Unmount {
    fs::path path;
    ~Unmount() { ::umount2(path.c_str(), MNT_DETACH); }
  } unmount{mount_point};
  const std::string solve = "solve " + (dir / "case.toml").string() + " -o " + (mount_point / "out").string();
  ASSERT_EQ(run(solve).exit_code, 0);
  const std::string vtu = read_text(mount_point / "out" / "r.vtu");
  // Fill the disk.
  {
    std::ofstream filler(mount_point / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (int k = 0; k < 1024 && filler; ++k) filler << block << std::flush;
  }
  const RunResult r = run(solve);
  EXPECT_EQ(r.exit_code, 5) << r.output;
  EXPECT_EQ(read_text(mount_point / "out" / "r.vtu"), vtu);
  const RunResult o = run("optimize " + (dir / "case.toml").string() + " -o " + (mount_point / "run").string());
  EXPECT_EQ(o.exit_code, 5) << o.output;
}

}  // namespace
