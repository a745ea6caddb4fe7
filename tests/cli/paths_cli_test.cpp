// Paths, outputs and writes of the `feedplan` command (regressions from a new user and a fuzzing probe):
// - no output may be one of the command's inputs or another output — through `./x`, symbolic links and
//   the default database too — exit 2 naming both flags, every input byte for byte as it was;
// - a plan that fails (the target cannot be met) leaves existing outputs as they were and writes its
//   report, CSV and plot only to new files;
// - a write error (a full device) is exit 1 naming the path and the reason, never "wrote", and a run
//   whose one output cannot be written writes none;
// - plan reports store absolute database and spec paths, so `learn` works from another folder; a moved
//   database or another one is named as such, a missing one is never answered with "create one";
// - two `learn` runs racing on one database: one lands, the other is refused, never a wrong parent;
// - `learn` killed with SIGKILL at random points leaves the database whole, with the old or new state.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "feedplan/gcode/reader.hpp"
#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;
using nlohmann::json;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;
const std::string kTestData = FEEDPLAN_TEST_DATA_DIR;

// Built with append: GCC 12 warns falsely (-Wrestrict) on "'" + std::string when inlined.
std::string quoted(const fs::path& path) {
  std::string text = "'";
  return text.append(path.string()).append("'");
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// A folder holding a database with the sample model (t.db) and the corner spec (corner.yaml).
class PathsCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = dir_ / "t.db";
    ASSERT_EQ(run_feedplan("db init --db " + quoted(db_)).exit_code, 0);
    const RunResult imported = run_feedplan("db import " + kTestData + "/cli/s50c_d10_model.json --db " + quoted(db_));
    ASSERT_EQ(imported.exit_code, 0) << imported.output;
    spec_ = dir_ / "corner.yaml";
    fs::copy_file(kSamples + "/corner.yaml", spec_);
  }

  // Runs `arguments` in the test's folder and expects exit 2 with every fragment in the output and every
  // file in `inputs` as it was.
  void expect_refused(const std::string& arguments, const std::vector<fs::path>& inputs,
                      const std::vector<std::string>& fragments) {
    std::vector<std::string> before;
    for (const fs::path& input : inputs) before.push_back(read_text(input));
    const RunResult r = run_feedplan(arguments, dir_);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    for (const std::string& fragment : fragments) EXPECT_TRUE(contains(r.output, fragment)) << fragment << " in\n" << r.output;
    EXPECT_FALSE(contains(r.output, "wrote")) << r.output;
    for (std::size_t i = 0; i < inputs.size(); ++i) EXPECT_EQ(read_text(inputs[i]), before[i]) << inputs[i];
  }

  // The versions of the sample model in `db`, as `db history --json` lists them.
  json versions(const fs::path& db) {
    const RunResult r = run_feedplan("db history --tool \"SC EM D10 Z4\" --material S50C --json --db " + quoted(db));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return json::parse(r.output.substr(r.output.find('{')))["versions"];
  }

  fs::path db_;
  fs::path spec_;
};

// And the corner planned with it from its folder with relative paths (c.nc, c.json) and cut on the
// virtual machine (log.csv).
class PlannedPathsCliTest : public PathsCliTest {
 protected:
  void SetUp() override {
    PathsCliTest::SetUp();
    if (HasFatalFailure()) return;
    const RunResult planned = run_feedplan("plan corner.yaml --db t.db -o c.nc --report c.json", dir_);
    ASSERT_EQ(planned.exit_code, 0) << planned.output;
    const RunResult cut = run_feedplan("simulate c.nc --spec corner.yaml --log log.csv", dir_);
    ASSERT_EQ(cut.exit_code, 0) << cut.output;
    fs::create_directory(dir_ / "elsewhere");
  }
};

TEST_F(PathsCliTest, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  fs::create_symlink(spec_, dir_ / "link.yaml");
  expect_refused("plan corner.yaml -o corner.yaml --db t.db", {spec_}, {"-o = 'corner.yaml'", "same file as SPEC"});
  expect_refused("plan link.yaml -o ./corner.yaml --db t.db", {spec_}, {"-o = './corner.yaml'", "same file as SPEC ('link.yaml')"});
  expect_refused("plan corner.yaml -o c.nc --report t.db --db ./t.db", {db_}, {"--report = 't.db'", "same file as --db ('./t.db')"});
  expect_refused("plan corner.yaml -o c.nc --report c.nc --db t.db", {}, {"--report = 'c.nc'", "same file as -o"});
  expect_refused("db export t.db --db t.db", {db_}, {"FILE = 't.db'", "same file as --db"});
  expect_refused("cycle corner.yaml --engagement corner.yaml", {spec_}, {"--engagement", "same file as SPEC"});
  const std::string program = "G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X20 F500\nM30\n";
  std::ofstream(dir_ / "p.ngc") << program;
  expect_refused("simulate p.ngc --log p.ngc --tool diameter_mm=10,flutes=4 --material S50C", {dir_ / "p.ngc"},
                 {"--log = 'p.ngc'", "same file as PROGRAM"});
  EXPECT_EQ(read_text(dir_ / "p.ngc"), program);
  EXPECT_FALSE(fs::exists(dir_ / "c.nc"));
}

TEST_F(PathsCliTest, TheDatabaseFromTheEnvironmentIsAnInputToo) {
  ::setenv("FEEDPLAN_DB", db_.c_str(), 1);
  expect_refused("plan corner.yaml -o c.nc --csv t.db", {db_}, {"--csv = 't.db'", "same file as --db"});
  ::unsetenv("FEEDPLAN_DB");
}

TEST_F(PathsCliTest, AFailedPlanLeavesExistingOutputsAsTheyWere) {
  for (const char* name : {"c.nc", "c.json", "c.csv"}) std::ofstream(dir_ / name) << "old " << name << "\n";
  // 5 N cannot be held anywhere in the material: status "target not met", exit 1.
  const RunResult r =
      run_feedplan("plan corner.yaml --db t.db --target-force 5 -o c.nc --report c.json --csv c.csv --plot c.svg", dir_);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "target not met")) << r.output;
  for (const char* name : {"c.nc", "c.json", "c.csv"}) EXPECT_EQ(read_text(dir_ / name), "old " + std::string(name) + "\n") << name;
  EXPECT_TRUE(contains(r.output, "no program written to c.nc")) << r.output;
  for (const char* name : {"c.json", "c.csv"}) {
    EXPECT_TRUE(contains(r.output, std::string(name) + " exists: left as it was")) << r.output;
  }
  // The plot did not exist: it is written, to show where the target cannot be met.
  EXPECT_TRUE(contains(read_text(dir_ / "c.svg"), "<svg")) << r.output;
  EXPECT_TRUE(contains(r.output, "wrote c.svg")) << r.output;
}

TEST_F(PathsCliTest, AWriteErrorIsAnErrorAndARunWritesAllOutputsOrNone) {
  if (!fs::is_character_file("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const RunResult full = run_feedplan("plan corner.yaml --db t.db -o /dev/full", dir_);
  EXPECT_EQ(full.exit_code, 1) << full.output;
  EXPECT_TRUE(contains(full.output, "cannot write /dev/full: No space left on device")) << full.output;
  EXPECT_FALSE(contains(full.output, "wrote")) << full.output;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  // The program could be written, the report not: neither is.
  std::ofstream(dir_ / "c.nc") << "old program\n";
  const RunResult report = run_feedplan("plan corner.yaml --db t.db -o c.nc --csv c.csv --report /dev/full", dir_);
  EXPECT_EQ(report.exit_code, 1) << report.output;
  EXPECT_TRUE(contains(report.output, "cannot write /dev/full: No space left on device")) << report.output;
  EXPECT_EQ(read_text(dir_ / "c.nc"), "old program\n");
  EXPECT_FALSE(fs::exists(dir_ / "c.csv"));
  const RunResult exported = run_feedplan("db export /dev/full --db t.db", dir_);
  EXPECT_EQ(exported.exit_code, 1) << exported.output;
  EXPECT_TRUE(contains(exported.output, "No space left on device")) << exported.output;
  // /dev/null takes the text: that is a success.
  EXPECT_EQ(run_feedplan("plan corner.yaml --db t.db -o /dev/null", dir_).exit_code, 0);
  // Standard output is an output too: a summary that cannot be printed is a failure.
  EXPECT_EQ(run_feedplan("db list --db t.db > /dev/full", dir_).exit_code, 1);
  EXPECT_EQ(run_feedplan("db list --db t.db > /dev/null", dir_).exit_code, 0);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_NE(entry.path().filename().string()[0], '.') << "a temporary file was left behind: " << entry.path();
  }
}

TEST_F(PathsCliTest, AMissingDatabaseIsNeverAnsweredWithCreateOne) {
  for (const std::string& command : {std::string("plan corner.yaml -o c.nc --db sample.db"), std::string("db list --db sample.db"),
                                     std::string("db history --tool T --material M --db sample.db")}) {
    const RunResult r = run_feedplan(command, dir_);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, "sample.db cannot be opened: no such file (looked for " +
                                       (fs::canonical(dir_) / "sample.db").string()))
        << r.output;
    EXPECT_FALSE(contains(r.output, "db init")) << r.output;
    EXPECT_FALSE(contains(r.output, "create")) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "sample.db"));
  }
}

TEST_F(PlannedPathsCliTest, TheReportStoresAbsolutePathsAndLearnWorksFromAnotherFolder) {
  const json report = json::parse(read_text(dir_ / "c.json"));
  EXPECT_EQ(report["model"]["database"], fs::canonical(db_).string());
  EXPECT_EQ(report["spec"], fs::canonical(spec_).string());
  // learn R -o R would destroy the plan the parts were cut with.
  expect_refused("learn c.json log.csv -o c.json", {dir_ / "c.json"}, {"-o = 'c.json'", "same file as PLAN"});
  expect_refused("learn c.json log.csv -o n.nc --report log.csv", {dir_ / "log.csv"}, {"--report = 'log.csv'", "same file as LOG"});
  expect_refused("learn c.json log.csv -o t.db", {db_}, {"-o = 't.db'", "same file as the model database"});

  const RunResult r = run_feedplan("learn ../c.json ../log.csv -o next.nc --report next.json --json", dir_ / "elsewhere");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json h = versions(db_);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[1]["parent_version"], 1);
  EXPECT_FALSE(feedplan::gcode::load_program(dir_ / "elsewhere" / "next.nc").blocks.empty());
  const json next = json::parse(read_text(dir_ / "elsewhere" / "next.json"));
  EXPECT_EQ(next["model"]["database"], fs::canonical(db_).string());
  EXPECT_EQ(next["spec"], fs::canonical(spec_).string());
}

TEST_F(PlannedPathsCliTest, LearnSaysWhenTheDatabaseMovedOrIsAnotherOne) {
  fs::rename(db_, dir_ / "moved.db");
  const RunResult moved = run_feedplan("learn ../c.json ../log.csv -o next.nc", dir_ / "elsewhere");
  EXPECT_EQ(moved.exit_code, 2) << moved.output;
  EXPECT_TRUE(contains(moved.output, "model.database = '" + fs::weakly_canonical(db_).string() +
                                         "': the model database the plan was made with is not there"))
      << moved.output;
  EXPECT_TRUE(contains(moved.output, "give its path with --db")) << moved.output;
  EXPECT_FALSE(contains(moved.output, "db init")) << moved.output;
  EXPECT_FALSE(fs::exists(dir_ / "elsewhere" / "next.nc"));

  // Another database, with no model of that id: named, and the one the plan was made with said.
  ASSERT_EQ(run_feedplan("db init --db other.db", dir_).exit_code, 0);
  const RunResult other = run_feedplan("learn c.json log.csv -o next.nc --db other.db", dir_);
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_TRUE(contains(other.output, "the plan's model (SC EM D10 Z4 in S50C v1) is not in other.db")) << other.output;
  EXPECT_TRUE(contains(other.output, "the plan was made with " + fs::weakly_canonical(db_).string())) << other.output;

  // The moved database given with --db: learning goes on.
  const RunResult found = run_feedplan("learn c.json log.csv -o next.nc --db moved.db", dir_);
  EXPECT_EQ(found.exit_code, 0) << found.output;
  EXPECT_EQ(versions(dir_ / "moved.db").size(), 2u);
}

TEST_F(PlannedPathsCliTest, AnOlderReportsRelativeDatabaseIsFoundBesideTheReport) {
  json report = json::parse(read_text(dir_ / "c.json"));
  report["model"]["database"] = "t.db";  // as reports stored it before: as typed, relative to where plan ran
  report["spec"] = "corner.yaml";
  std::ofstream(dir_ / "c.json") << report.dump(2);
  const RunResult r = run_feedplan("learn ../c.json ../log.csv -o next.nc", dir_ / "elsewhere");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(versions(db_).size(), 2u);
}

TEST_F(PlannedPathsCliTest, TwoLearnsRacingOnOneDatabaseOneLandsTheOtherIsRefused) {
  // Both start from the same report (v1) at once: whichever stores first lands, the other is refused —
  // when it checks before learning or inside its write transaction — and never filed under v2.
  std::vector<FILE*> pipes;
  for (const char* program : {"a.nc", "b.nc"}) {
    const std::string command = "cd " + quoted(dir_) + " && " + FEEDPLAN_BINARY + " learn c.json log.csv -o " + program + " 2>&1";
    pipes.push_back(popen(command.c_str(), "r"));
    ASSERT_NE(pipes.back(), nullptr);
  }
  std::vector<RunResult> results(2);
  for (std::size_t i = 0; i < 2; ++i) {
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipes[i])) results[i].output += buffer;
    const int status = pclose(pipes[i]);
    results[i].exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  const int landed = results[0].exit_code == 0 ? 0 : 1;
  ASSERT_EQ(results[landed].exit_code, 0) << results[0].output << "\n---\n" << results[1].output;
  const RunResult& refused = results[1 - landed];
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_TRUE(contains(refused.output, "v2 (id 2, learned")) << refused.output;
  EXPECT_TRUE(contains(refused.output, "is the active version now")) << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / (landed == 0 ? "b.nc" : "a.nc")));
  const json h = versions(db_);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[1]["parent_version"], 1);
}

// Starts `feedplan learn` of the corner into `db`, writing `program`, its output discarded; returns its pid.
pid_t start_learn(const fs::path& dir, const fs::path& db, const fs::path& program) {
  const pid_t child = ::fork();
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execl(FEEDPLAN_BINARY, FEEDPLAN_BINARY, "learn", (dir / "c.json").c_str(), (dir / "log.csv").c_str(), "-o",
            program.c_str(), "--db", db.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return child;
}

TEST_F(PlannedPathsCliTest, LearnKilledAtRandomPointsLeavesTheOldOrTheNewState) {
  // How long one learn takes here, so that the kills spread over it. Only where the kills land depends on
  // it; what is checked holds wherever they land.
  const auto started = std::chrono::steady_clock::now();
  int status = 0;
  fs::copy_file(db_, dir_ / "timing.db");
  const pid_t timed = start_learn(dir_, dir_ / "timing.db", dir_ / "timing.nc");
  ASSERT_EQ(::waitpid(timed, &status, 0), timed);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const auto learn_us = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - started).count();
  const unsigned seed = 7001u;
  std::mt19937 random(seed);
  for (int trial = 0; trial < 8; ++trial) {
    // Most of a learn is reading and fitting; the kills go where it stores and writes, near its end.
    const auto delay_us = static_cast<long long>(std::uniform_real_distribution<double>(0.5, 1.1)(random) * learn_us);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial) + ": killed after " +
                 std::to_string(delay_us) + " us of " + std::to_string(learn_us));
    const fs::path db = dir_ / ("trial" + std::to_string(trial) + ".db");
    fs::copy_file(db_, db);
    const fs::path program = dir_ / ("trial" + std::to_string(trial) + ".nc");
    const pid_t child = start_learn(dir_, db, program);
    ::usleep(static_cast<useconds_t>(delay_us));
    ::kill(child, SIGKILL);
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    const RunResult check = run_feedplan("db list --db " + quoted(db));  // opens with quick_check
    ASSERT_EQ(check.exit_code, 0) << check.output;
    const json h = versions(db);
    ASSERT_TRUE(h.size() == 1u || h.size() == 2u) << h.dump();
    if (h.size() == 2u) {
      EXPECT_EQ(h[1]["parent_version"], 1);
    }
    if (fs::exists(program)) {  // written only after the learned version was stored, and whole
      EXPECT_EQ(h.size(), 2u);
      EXPECT_FALSE(feedplan::gcode::load_program(program).blocks.empty());
    }
    if (WIFEXITED(status)) {
      EXPECT_EQ(WEXITSTATUS(status), 0);  // it finished before the kill
    }
  }
}

}  // namespace
