// SPDX-License-Identifier: MIT
// io::RunDirectory (docs/case-format.md, "Run directories"): --force removes only frictopt's files
// and refuses a directory holding anything else; one process at a time (flock); a resumed history
// is cut back to the checkpoint and tolerates a torn last row; stray files in the VTK series are
// left alone; checkpoint fields are validated.
#include "frictopt/io/run_directory.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;
using frictopt::testing::read_text;

class RunDirectoryTest : public frictopt::testing::TemporaryDirectoryTest {
 protected:
  void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
  std::string expect_refused(const fs::path& dir, RunOpening opening, const fs::path& case_path = {}) {
    try {
      RunDirectory run(dir, opening, case_path);
      ADD_FAILURE() << "not refused";
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return {};
  }
};

TEST_F(RunDirectoryTest, RecognizesExactlyTheFilesFrictoptWrites) {
  const std::vector<std::string> names = {"punch"};
  for (const char* ours : {"history.csv", "checkpoint.json", "punch.pvd", "punch_iter0012.vtu", "punch_iter12345.vtu",
                           "punch.vtu", "punch_contact.csv", ".summary.json.Ab3dEf.tmp", ".frictopt.lock"}) {
    write(dir_ / ours, "x");
    EXPECT_TRUE(RunDirectory::is_frictopt_output(dir_ / ours, names)) << ours;
  }
  for (const char* foreign : {"precious.txt", "punch_iterXYZW.vtu", "other.pvd", "punch_iter12.vtu", ".x.Ab3dEf.tmp"}) {
    write(dir_ / foreign, "x");
    EXPECT_FALSE(RunDirectory::is_frictopt_output(dir_ / foreign, names)) << foreign;
  }
  fs::create_symlink(dir_ / "precious.txt", dir_ / "summary.json");
  EXPECT_FALSE(RunDirectory::is_frictopt_output(dir_ / "summary.json", names));
  fs::create_directory(dir_ / "pictures");
  write(dir_ / "pictures" / "a.png", "x");
  EXPECT_TRUE(RunDirectory::is_frictopt_output(dir_ / "pictures", names));
  write(dir_ / "pictures" / "notes.txt", "x");
  EXPECT_FALSE(RunDirectory::is_frictopt_output(dir_ / "pictures", names));
}

TEST_F(RunDirectoryTest, ForceRefusesAForeignEntryAndRemovesNothing) {
  // --force once deleted foreign/precious.txt (and with -o . the case itself).
  const fs::path run = dir_ / "run";
  fs::create_directories(run / "subfolder");
  write(run / "history.csv", "iteration\n");
  write(run / "checkpoint.json", "{}");
  write(run / "precious.txt", "keep");
  const std::string message = expect_refused(run, RunOpening::kForce);
  EXPECT_NE(message.find("precious.txt"), std::string::npos) << message;
  EXPECT_NE(message.find("subfolder/"), std::string::npos) << message;
  EXPECT_NE(message.find("nothing was removed"), std::string::npos) << message;
  EXPECT_TRUE(fs::exists(run / "precious.txt"));
  EXPECT_TRUE(fs::exists(run / "history.csv"));
  EXPECT_TRUE(fs::exists(run / "subfolder"));
}

TEST_F(RunDirectoryTest, ForceRemovesOnlyOurFilesAndKeepsTheCaseArgument) {
  const fs::path run = dir_ / "run";
  fs::create_directories(run);
  write(run / "history.csv", "iteration\n");
  write(run / "checkpoint.json", "{}");
  const std::string case_text =
      read_text(fs::path(FRICTOPT_SOURCE_DIR) / "tests/cli/data/small2d.toml") + "\n[output]\nname = \"x\"\n";
  write(run / "case.toml", case_text);  // the case argument lives here (-o .)
  write(run / "x_iter0003.vtu", "v");
  {
    RunDirectory opened(run, RunOpening::kForce, run / "case.toml");
    EXPECT_TRUE(fs::exists(run / "case.toml"));
    EXPECT_FALSE(fs::exists(run / "history.csv"));
    EXPECT_FALSE(fs::exists(run / "x_iter0003.vtu"));
    EXPECT_EQ(opened.store_case(), run / "case.toml");
  }
  EXPECT_EQ(read_text(run / "case.toml"), case_text);
}

TEST_F(RunDirectoryTest, ANewRunRefusesAnExistingRun) {
  write(dir_ / "history.csv", "iteration\n");
  EXPECT_NE(expect_refused(dir_, RunOpening::kNewRun).find("--resume"), std::string::npos);
  EXPECT_NE(expect_refused(dir_ / "absent", RunOpening::kResume).find("no run to resume"), std::string::npos);
  write(dir_ / "file", "x");
  EXPECT_NE(expect_refused(dir_ / "file", RunOpening::kOutput).find("not a directory"), std::string::npos);
}

TEST_F(RunDirectoryTest, ASecondProcessIsRefusedWhileTheFirstHoldsTheLock) {
  // Two runs into one directory interleaved history.csv. flock conflicts
  // between two open file descriptions even within one process, so this models two processes.
  {
    RunDirectory first(dir_, RunOpening::kOutput);
    const std::string message = expect_refused(dir_, RunOpening::kOutput);
    EXPECT_NE(message.find("in use by another frictopt process"), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(::getpid())), std::string::npos) << message;
  }
  EXPECT_NO_THROW(RunDirectory again(dir_, RunOpening::kOutput));  // released with the object
}

TEST_F(RunDirectoryTest, AResumedHistoryIsCutBackToTheCheckpointAndDropsATornLastRow) {
  write(dir_ / "checkpoint.json", "{}");
  write(dir_ / "case.toml", "");
  write(dir_ / "history.csv", "iteration,theta\n1,5\n2,4\n3,3\n4,2.\n");
  {
    RunDirectory run(dir_, RunOpening::kResume);
    std::vector<std::string> notes;
    CsvWriter history = run.open_history({"iteration", "theta"}, 3, notes);
    EXPECT_EQ(read_text(dir_ / "history.csv"), "iteration,theta\n1,5\n2,4\n3,3\n");
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("after the checkpoint"), std::string::npos) << notes[0];
  }
  write(dir_ / "history.csv", "iteration,theta\n1,5\n2,4\n3,3\n4,2.5e");  // a row cut short by a kill: one field
  write(dir_ / "history.csv", "iteration,theta\n1,5\n2,4\n3");
  {
    RunDirectory run(dir_, RunOpening::kResume);
    std::vector<std::string> notes;
    CsvWriter history = run.open_history({"iteration", "theta"}, 3, notes);
    EXPECT_EQ(read_text(dir_ / "history.csv"), "iteration,theta\n1,5\n2,4\n");
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("incomplete"), std::string::npos) << notes[0];
  }
  write(dir_ / "history.csv", "iteration,theta\n1,5\nxx\n3,3\n");
  RunDirectory run(dir_, RunOpening::kResume);
  std::vector<std::string> notes;
  try {
    (void)run.open_history({"iteration", "theta"}, 3, notes);
    FAIL() << "a damaged middle row was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("history.csv:3"), std::string::npos) << e.what();
  }
}

TEST_F(RunDirectoryTest, AStrayFileInTheSeriesIsLeftAloneAndReported) {
  write(dir_ / "checkpoint.json", "{}");
  write(dir_ / "case.toml", "");
  for (const char* f : {"b_iter0000.vtu", "b_iter0002.vtu", "b_iter0009.vtu", "b_iterXYZW.vtu"}) write(dir_ / f, "v");
  RunDirectory run(dir_, RunOpening::kResume);
  std::vector<std::string> notes;
  run.start_series("b", 5, notes);
  EXPECT_TRUE(run.series_has(0));
  EXPECT_TRUE(run.series_has(2));
  EXPECT_FALSE(run.series_has(9));  // after the checkpoint: rewritten when the run gets there
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("b_iterXYZW.vtu"), std::string::npos) << notes[0];
  EXPECT_TRUE(fs::exists(dir_ / "b_iterXYZW.vtu"));
}

RunCheckpoint valid_checkpoint() {
  RunCheckpoint c;
  c.method.iteration = 3;
  c.method.evaluations = 5;
  c.method.serious_steps = 2;
  c.method.null_steps = 1;
  c.method.x = Eigen::VectorXd::Constant(2, 0.1);
  c.method.f = 2.0;
  c.method.t = 0.5;
  c.method.t_max = 1.0;
  c.method.z_prev = Eigen::VectorXd::Ones(2);
  c.method.bundle.push_back({Eigen::VectorXd::Ones(2), 0.0, 0.0, 0.0, c.method.x, true});
  c.fingerprint.dim = 2;
  c.fingerprint.settings = {{"material.young", "1"}};
  c.fingerprint.case_hash = hash_settings(c.fingerprint.settings);
  c.fingerprint.num_nodes = 4;
  c.warm_start = Eigen::VectorXd::LinSpaced(4, 0.1, 0.4) / 3.0;
  c.warm_start_dim = 2;
  c.initial_cost = 4.0;
  return c;
}

TEST(Checkpoint, RoundTripsEveryFieldExactly) {
  const RunCheckpoint c = valid_checkpoint();
  const RunCheckpoint back = checkpoint_from_json(parse_json(to_json_string(checkpoint_to_json(c))));
  EXPECT_EQ(back.method.iteration, 3);
  EXPECT_EQ(back.warm_start, c.warm_start);  // bit for bit
  EXPECT_EQ(back.fingerprint.settings, c.fingerprint.settings);
  EXPECT_EQ(back.initial_cost, 4.0);
}

// A piece's cut keeps the piece's gap at its point (BundleElement::piece_gap): the certificate
// of a resumed worst-case run must not take it for a subgradient of f. Checkpoints written
// before the field existed held cuts of f only and read as gap 0.
TEST(Checkpoint, RoundTripsThePieceGapOfABundleElement) {
  RunCheckpoint c = valid_checkpoint();
  frictopt::optim::BundleElement piece{Eigen::Vector2d(-1.0, 0.5), 0.3, 0.0, 0.3, c.method.x, false};
  piece.piece_gap = 0.25;
  c.method.bundle.push_back(piece);
  const RunCheckpoint back = checkpoint_from_json(parse_json(to_json_string(checkpoint_to_json(c))));
  ASSERT_EQ(back.method.bundle.size(), 2u);
  EXPECT_EQ(back.method.bundle[0].piece_gap, 0.0);
  EXPECT_EQ(back.method.bundle[1].piece_gap, 0.25);
  JsonValue older = checkpoint_to_json(c);
  JsonValue::Array bundle;
  for (const JsonValue& element : older.at("bundle").as_array()) {
    JsonValue::Object fields;
    for (const auto& field : element.as_object())
      if (field.first != "piece_gap") fields.push_back(field);
    bundle.emplace_back(std::move(fields));
  }
  older["bundle"] = JsonValue(std::move(bundle));
  older["format"] = "frictopt-run-checkpoint-2";  // as written then: no checksum, no piece gaps
  EXPECT_EQ(checkpoint_from_json(older).method.bundle[1].piece_gap, 0.0);
}

// The opt-in variable metric's state (docs/optim.md, "Variable metric") is part of the method
// state: without it a resumed run would restart from the identity metric.
TEST(Checkpoint, RoundTripsTheVariableMetricState) {
  RunCheckpoint c = valid_checkpoint();
  c.method.g_start = Eigen::Vector2d(3.0, -4.0 / 3.0);
  c.method.null_streak = 4;
  c.method.metric.h = Eigen::Vector2d(0.1, 10.0);
  c.method.metric.steps = Eigen::MatrixXd::Random(2, 3);
  c.method.metric.differences = Eigen::MatrixXd::Random(2, 3);
  c.method.metric.updates = 3;
  c.method.metric.resets = 1;
  const RunCheckpoint back = checkpoint_from_json(parse_json(to_json_string(checkpoint_to_json(c))));
  EXPECT_EQ(back.method.g_start, c.method.g_start);
  EXPECT_EQ(back.method.null_streak, 4);
  EXPECT_EQ(back.method.metric.h, c.method.metric.h);
  EXPECT_EQ(back.method.metric.steps, c.method.metric.steps);
  EXPECT_EQ(back.method.metric.differences, c.method.metric.differences);
  EXPECT_EQ(back.method.metric.updates, 3);
  EXPECT_EQ(back.method.metric.resets, 1);
  // Identity (the default): nothing written, nothing read back.
  const RunCheckpoint plain = checkpoint_from_json(checkpoint_to_json(valid_checkpoint()));
  EXPECT_TRUE(plain.method.metric.is_identity());
  EXPECT_FALSE(checkpoint_to_json(valid_checkpoint()).contains("metric"));
  // A metric entry that is not positive is refused, naming it.
  JsonValue j = checkpoint_to_json(c);
  j["metric"]["h"] = Eigen::VectorXd(Eigen::Vector2d(0.1, -1.0));
  try {
    (void)checkpoint_from_json(j, "cp.json");
    FAIL() << "a negative metric entry was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("metric.h[1]"), std::string::npos) << e.what();
  }
}

TEST(Checkpoint, OutOfRangeFieldsAreRefusedNamingThem) {
  // iteration = -5 and 10^12 (which wrapped to a negative int) were accepted.
  for (const auto& [key, value, fragment] :
       std::vector<std::tuple<std::string, JsonValue, std::string>>{
           {"iteration", JsonValue(-5), "iteration = -5"},
           {"iteration", JsonValue(std::int64_t{1000000000000}), "iteration = 1000000000000"},
           {"evaluations", JsonValue(0), "evaluations = 0"},
           {"t", JsonValue(-1.0), "t = -1"},
           {"x", JsonValue::array(), "x"}}) {
    JsonValue j = checkpoint_to_json(valid_checkpoint());
    j[key] = value;
    try {
      (void)checkpoint_from_json(j, "run/checkpoint.json");
      ADD_FAILURE() << key << " accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("run/checkpoint.json"), std::string::npos) << e.what();
    }
  }
  JsonValue edited = checkpoint_to_json(valid_checkpoint());
  edited["fingerprint"]["settings"]["material.young"] = "2";
  EXPECT_THROW((void)checkpoint_from_json(edited), InvalidInput);  // the hash no longer matches
}

TEST(Checkpoint, DifferencesNameTheChangedSettings) {
  CaseFingerprint a;
  a.dim = 2;
  a.settings = {{"contact.friction.mu", "0.3"}, {"mesh.cells", "[29, 14]"}};
  CaseFingerprint b = a;
  b.settings["contact.friction.mu"] = "0.4";
  b.settings.erase("mesh.cells");
  b.dim = 3;
  const auto d = b.differences_from(a);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0], "geometry.dim: 2 -> 3");
  EXPECT_EQ(d[1], "contact.friction.mu: 0.3 -> 0.4");
  EXPECT_EQ(d[2], "mesh.cells: [29, 14] -> (absent)");
  EXPECT_TRUE(a.differences_from(a).empty());
}

TEST(CaseCopyText, MakesARelativeMeshFileAbsoluteAndKeepsTheRest) {
  const std::string text = "# a case\n[mesh]\nfile = \"parts/die.geo\"   # the die\nsize = 0.1\n";
  const std::string copy = case_copy_text(text, "/data/study/case.toml");
  EXPECT_EQ(copy, "# a case\n[mesh]\nfile = \"/data/study/parts/die.geo\"   # the die\nsize = 0.1\n");
  // Literal strings, absolute paths, cases without a mesh file and unparsable text: unchanged
  // except the literal string's path.
  EXPECT_EQ(case_copy_text("[mesh]\nfile = 'a.msh'\n", "/x/c.toml"), "[mesh]\nfile = \"/x/a.msh\"\n");
  EXPECT_EQ(case_copy_text("[mesh]\nfile = \"/abs/a.msh\"\n", "/x/c.toml"), "[mesh]\nfile = \"/abs/a.msh\"\n");
  EXPECT_EQ(case_copy_text("[mesh]\ncells = [4, 4]\n", "/x/c.toml"), "[mesh]\ncells = [4, 4]\n");
  EXPECT_EQ(case_copy_text("[mesh\nfile = \"a\"", "/x/c.toml"), "[mesh\nfile = \"a\"");
  EXPECT_EQ(case_copy_text("mesh = { file = \"a.msh\" }\n", "/x/c.toml"), "mesh = { file = \"/x/a.msh\" }\n");
}

}  // namespace
}  // namespace frictopt::io
