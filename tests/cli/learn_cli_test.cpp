// End-to-end tests of `feedplan learn` and `feedplan loop` on a database holding the sample model of the
// Ø10 4-flute end mill in S50C (tests/data/cli/s50c_d10_model.json). The corner sample is planned with it
// and cut on the virtual machine; learning from that log stores version 2 (learned, parent 1) with one
// learning entry and writes the re-planned program and report. Logs that cannot be learned from — another
// program, positions in inches, no cut, broken cells, a missing file — and a malformed plan report exit
// 2 (bad input) or 1 (nothing to learn) with the database content unchanged and no program written.
// The logs are edited here, from the CSV text, not through the log reader under test.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/gcode/reader.hpp"
#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;
using nlohmann::json;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;
const std::string kToolMaterial = "--tool \"SC EM D10 Z4\" --material S50C";

// A force log as CSV text: the lines before the data (metadata, header), the column names, the rows' cells.
struct CsvLog {
  std::vector<std::string> head;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  int column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i] == name) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double number(std::size_t row, const std::string& name) const { return std::stod(rows[row][column(name)]); }
  //! The 1-based line of the file data row `row` is on.
  std::size_t line_of(std::size_t row) const { return head.size() + row + 1; }
  std::string text() const {
    std::string out;
    for (const auto& line : head) out += line + "\n";
    for (const auto& cells : rows) {
      for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + cells[i];
      out += "\n";
    }
    return out;
  }
};

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells(1);
  for (char c : line) {
    if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

CsvLog parse_csv_log(const std::string& text) {
  CsvLog log;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (log.columns.empty()) {
      log.head.push_back(line);
      if (!line.empty() && line[0] != '#') log.columns = split_cells(line);
      continue;
    }
    EXPECT_FALSE(!line.empty() && line[0] == '#') << "metadata among the rows: " << line;
    if (!line.empty()) log.rows.push_back(split_cells(line));
  }
  EXPECT_FALSE(log.columns.empty());
  return log;
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// The JSON object printed on stdout; messages on stderr (merged into the output) come before it.
json json_of(const std::string& output) {
  const auto begin = output.find("\n{") != std::string::npos && output[0] != '{' ? output.find("\n{") + 1 : 0;
  const auto end = output.rfind('}');
  if (end == std::string::npos || end < begin) {
    ADD_FAILURE() << "no JSON in:\n" << output;
    return json::object();
  }
  try {
    return json::parse(output.substr(begin, end - begin + 1));
  } catch (const json::exception& e) {
    ADD_FAILURE() << e.what() << " in:\n" << output;
    return json::object();
  }
}

// A database holding the sample model (version 1).
class ModelDbCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult imported =
        run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(imported.exit_code, 0) << imported.output;
  }

  // Every tool, material, model version, cutting test and learning entry, as `db export` writes them.
  std::string content() {
    const fs::path out = dir_ / "content.json";
    const RunResult r = run_feedplan("db export " + out.string() + " --all-versions --db " + db_);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_text(out);
  }

  std::string db_;
};

// And the corner sample planned with it (c.nc, c.json) and cut on the virtual machine (log.csv).
class LearnCliTest : public ModelDbCliTest {
 protected:
  void SetUp() override {
    ModelDbCliTest::SetUp();
    if (HasFatalFailure()) return;
    plan_ = dir_ / "c.json";
    log_ = dir_ / "log.csv";
    plan_and_cut(kSamples + "/corner.yaml", dir_ / "c.nc", plan_, log_);
    next_ = dir_ / "next.nc";
  }

  // Plans `spec` with the test database and cuts the program on the virtual machine.
  void plan_and_cut(const std::string& spec, const fs::path& program, const fs::path& report, const fs::path& log) {
    const RunResult planned =
        run_feedplan("plan " + spec + " --db " + db_ + " -o " + program.string() + " --report " + report.string());
    ASSERT_EQ(planned.exit_code, 0) << planned.output;
    const RunResult cut = run_feedplan("simulate " + program.string() + " --spec " + spec + " --log " + log.string());
    ASSERT_EQ(cut.exit_code, 0) << cut.output;
  }

  std::string learn_args(const fs::path& log) {
    return "learn " + plan_.string() + " " + log.string() + " -o " + next_.string() + " --db " + db_;
  }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  // Runs `arguments`, expects `exit_code` with every fragment in the output, the database content as it
  // was and no program written.
  void expect_refused(const std::string& arguments, int exit_code, const std::vector<std::string>& fragments) {
    const std::string before = content();
    const RunResult r = run_feedplan(arguments);
    EXPECT_EQ(r.exit_code, exit_code) << arguments << "\n" << r.output;
    for (const auto& fragment : fragments) {
      EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
    }
    EXPECT_EQ(content(), before) << arguments;
    EXPECT_FALSE(fs::exists(next_)) << arguments;
  }

  fs::path plan_;
  fs::path log_;
  fs::path next_;
};

using LoopCliTest = ModelDbCliTest;

TEST_F(LearnCliTest, StoresVersionTwoWithItsLearningEntryAndReplans) {
  const fs::path next_report = dir_ / "next.json";
  const RunResult r = run_feedplan(learn_args(log_) + " --report " + next_report.string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json out = json_of(r.output);
  ASSERT_TRUE(out.contains("model_after")) << r.output;
  EXPECT_EQ(out["model_before"]["version"], 1);
  EXPECT_EQ(out["model_after"]["version"], 2);
  EXPECT_GT(out["samples"].get<int>(), 100);

  // The store: version 2, learned, parent 1, active; version 1 kept.
  const RunResult history = run_feedplan("db history " + kToolMaterial + " --db " + db_ + " --json");
  ASSERT_EQ(history.exit_code, 0) << history.output;
  const json h = json_of(history.output);
  ASSERT_EQ(h["versions"].size(), 2u) << history.output;
  EXPECT_EQ(h["versions"][0]["version"], 1);
  EXPECT_EQ(h["versions"][0]["active"], false);
  EXPECT_EQ(h["versions"][1]["version"], 2);
  EXPECT_EQ(h["versions"][1]["source"], "learned");
  EXPECT_EQ(h["versions"][1]["parent_version"], 1);
  EXPECT_EQ(h["versions"][1]["active"], true);
  EXPECT_EQ(h["versions"][1]["id"], out["model_after"]["id"]);
  EXPECT_EQ(h["versions"][0]["id"], out["model_before"]["id"]);
  ASSERT_EQ(h["learning"].size(), 1u) << history.output;
  EXPECT_EQ(h["learning"][0]["part"], "c.json");
  EXPECT_GT(h["learning"][0]["n_samples"].get<int>(), 100);
  EXPECT_EQ(h["learning"][0]["n_samples"], out["samples"]);

  const RunResult list = run_feedplan("db list --db " + db_ + " --json");
  ASSERT_EQ(list.exit_code, 0) << list.output;
  const json l = json_of(list.output);
  int s50c_models = 0;
  for (const auto& m : l["models"]) {
    if (m["material"] != "S50C") continue;
    ++s50c_models;
    EXPECT_EQ(m["version"], 2);
    EXPECT_EQ(m["source"], "learned");
  }
  EXPECT_EQ(s50c_models, 1) << list.output;

  // The learning entry as exported: the model before and after by version.
  const json exported = json::parse(content());
  ASSERT_EQ(exported["learning_history"].size(), 1u);
  const json& entry = exported["learning_history"][0];
  EXPECT_EQ(entry["model_before"]["version"], 1);
  EXPECT_EQ(entry["model_after"]["version"], 2);
  EXPECT_EQ(entry["model_after"]["material"], "S50C");
  EXPECT_GT(entry["n_samples"].get<int>(), 100);

  // The program reads back; the report is a plan report of the same model with the correction learned
  // along the path, naming the learned version beside it (what the next part's learning builds on).
  const feedplan::geometry::Program program = feedplan::gcode::load_program(next_);
  int feeds = 0;
  for (const auto& block : program.blocks) {
    if (block.feed_mm_per_min > 0.0) ++feeds;
  }
  EXPECT_GT(feeds, 10);
  const std::string report_text = read_text(next_report);
  EXPECT_NE(report_text.find("feedplan-plan"), std::string::npos);
  const json report = json::parse(report_text);
  EXPECT_EQ(report["model"]["version"], 1);
  EXPECT_EQ(report["model"]["id"], out["model_before"]["id"]);
  EXPECT_EQ(out["planned_with"]["id"], out["model_before"]["id"]);
  EXPECT_EQ(report["path_learning"]["learned_model"]["version"], 2);
  EXPECT_EQ(report["path_learning"]["learned_model"]["id"], out["model_after"]["id"]);
  // Learning along the path goes with it to the next part: per plan sample, the correction and what
  // was measured there (t_m, L, force, tooth-period window).
  ASSERT_TRUE(report.contains("force_correction"));
  ASSERT_TRUE(report.contains("path_learning"));
  const std::size_t n = report["force_correction"].size();
  EXPECT_EQ(report["path_learning"]["place_correction"].size(), n);
  ASSERT_EQ(report["path_learning"]["measurements"].size(), n);
  int measured = 0;
  for (const auto& m : report["path_learning"]["measurements"]) {
    ASSERT_EQ(m.size(), 4u);
    if (m[2].get<double>() > 0.0) {
      ++measured;
      EXPECT_GT(m[0].get<double>(), 0.0);  // t_m
      EXPECT_GT(m[3].get<double>(), 0.0);  // window
    }
  }
  EXPECT_GT(measured, 100);
}

// With the dynamometer's mode given and the tool's mechanistic model in the database, learning says that
// the steady cut's factor comes from the kernel's force too — and learns as it does without.
TEST_F(LearnCliTest, TheDynamometersModeIsTakenOffWithTheMechanisticModelsShape) {
  ASSERT_EQ(run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_mechanistic.json --db " + db_)
                .exit_code,
            0);
  const RunResult r = run_feedplan(learn_args(log_) + " --sensor-hz 3600 --sensor-damping 0.7 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("more where the engagement is steady and the mechanistic model's force gives more on every machine"),
            std::string::npos) << r.output;
  EXPECT_GT(json_of(r.output)["samples"].get<int>(), 100);
}

TEST_F(LearnCliTest, TheNextPartLearnsOnFromThePathLearningOfTheFirst) {
  // Part 1 → learn → part 2 cut with the re-planned program → learn from part 2's report: the state
  // along the path read back, updated where part 2 measured, and carried on to part 3.
  const fs::path report_2 = dir_ / "part2.json";
  const RunResult first = run_feedplan(learn_args(log_) + " --report " + report_2.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const fs::path log_2 = dir_ / "log2.csv";
  const RunResult cut = run_feedplan("simulate " + next_.string() + " --spec " + kSamples + "/corner.yaml --log " + log_2.string());
  ASSERT_EQ(cut.exit_code, 0) << cut.output;
  const fs::path report_3 = dir_ / "part3.json";
  const fs::path program_3 = dir_ / "part3.nc";
  const fs::path plot_3 = dir_ / "part3.svg";
  const RunResult second = run_feedplan("learn " + report_2.string() + " " + log_2.string() + " -o " + program_3.string() +
                                        " --report " + report_3.string() + " --plot " + plot_3.string() + " --db " + db_ +
                                        " --json");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(json_of(second.output)["model_before"]["version"], 2);  // built on part 1's learned version
  EXPECT_EQ(json_of(second.output)["model_after"]["version"], 3);
  EXPECT_EQ(json_of(second.output)["planned_with"]["version"], 1);   // the program keeps its model
  const json part_2 = json::parse(read_text(report_2));
  const json part_3 = json::parse(read_text(report_3));
  ASSERT_EQ(part_3["path_learning"]["measurements"].size(), part_2["path_learning"]["measurements"].size());
  int remeasured = 0;
  for (std::size_t i = 0; i < part_3["path_learning"]["measurements"].size(); ++i) {
    const json& before = part_2["path_learning"]["measurements"][i];
    const json& after = part_3["path_learning"]["measurements"][i];
    if (before[2].get<double>() > 0.0 && after[2].get<double>() > 0.0 && after[0] != before[0]) ++remeasured;
    // The look-ahead window is the longest tooth period seen at a place over all parts.
    EXPECT_GE(after[3].get<double>(), before[3].get<double>()) << "sample " << i;
  }
  EXPECT_GT(remeasured, 100);  // part 2 ran other feeds at the same places

  // The history: part 1 in part 2's report, parts 1 and 2 in part 3's, each with the time of the plan it
  // was cut with; part 2's measured force per place is the measurement part 3's report carries.
  const json& history_2 = part_2["path_learning"]["history"];
  const json& history_3 = part_3["path_learning"]["history"];
  ASSERT_EQ(history_2.size(), 1u);
  ASSERT_EQ(history_3.size(), 2u);
  EXPECT_EQ(history_3[0], history_2[0]);
  EXPECT_EQ(history_3[1]["cycle"], 2);
  EXPECT_DOUBLE_EQ(history_3[1]["cycle_time_s"].get<double>(), part_2["summary"]["cycle_time_s"].get<double>());
  const json& measured = history_3[1]["measured_n"];
  ASSERT_EQ(measured.size(), part_3["path_learning"]["measurements"].size());
  int compared = 0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double now = part_3["path_learning"]["measurements"][i][2].get<double>();
    const double before = part_2["path_learning"]["measurements"][i][2].get<double>();
    if (measured[i].get<double>() > 0.0) {
      EXPECT_NEAR(measured[i].get<double>(), now, 0.051) << "sample " << i;
      ++compared;
    } else {
      EXPECT_EQ(now, before) << "sample " << i;  // not measured by part 2: the older measurement stays
    }
  }
  EXPECT_GT(compared, 100);
  const std::string svg = read_text(plot_3);
  for (const char* series : {"measured cycle-1", "measured cycle-2", "feed cycle-2", "next-force", "next-feed"}) {
    EXPECT_NE(svg.find(std::string("class=\"") + series + "\""), std::string::npos) << series;
  }
}

// A Ø8 corner planned with the Ø10 model (borrowed): learning must not change the Ø10's model. It is
// refused with the command that registers the Ø8 tool; following that advice, the learned version is the
// first of the Ø8 tool in S50C (its history's step names the Ø10 v1 it started from), the Ø10's stays
// as it was, and the next part learns on into the Ø8's own model.
TEST_F(LearnCliTest, ABorrowedModelLearnsIntoTheSpecsOwnToolNotTheLenders) {
  std::string text = read_text(kSamples + "/corner.yaml");
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"diameter_mm: 10", "diameter_mm: 8"}, {"name: \"SC EM D10 Z4\"", "name: \"SC EM D8 Z4\""}}) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const fs::path spec = write_spec("corner_d8.yaml", text);
  const fs::path report = dir_ / "d8.json";
  const fs::path log = dir_ / "d8_log.csv";
  plan_and_cut(spec.string(), dir_ / "d8.nc", report, log);
  ASSERT_NE(read_text(report).find("\"match_status\": \"borrowed\""), std::string::npos);
  const std::string learn = "learn " + report.string() + " " + log.string() + " -o " + next_.string() + " --db " + db_;
  const std::string advice = "feedplan db add-tool \"SC EM D8 Z4\" --diameter-mm 8 --flutes 4 --helix-deg 30 --db " + db_;
  expect_refused(learn, 2, {"tool.name", "borrowed the model of SC EM D10 Z4 in S50C v1", advice});

  const RunResult registered = run_feedplan(advice.substr(std::string("feedplan ").size()));
  ASSERT_EQ(registered.exit_code, 0) << registered.output;
  const fs::path next_report = dir_ / "d8_next.json";
  const RunResult learned = run_feedplan(learn + " --report " + next_report.string());
  ASSERT_EQ(learned.exit_code, 0) << learned.output;

  const json lender = json_of(run_feedplan("db history " + kToolMaterial + " --db " + db_ + " --json").output);
  ASSERT_EQ(lender["versions"].size(), 1u);
  EXPECT_EQ(lender["versions"][0]["active"], true);
  const std::string d8 = "--tool \"SC EM D8 Z4\" --material S50C";
  const json own = json_of(run_feedplan("db history " + d8 + " --db " + db_ + " --json").output);
  ASSERT_EQ(own["versions"].size(), 1u) << own.dump();
  EXPECT_EQ(own["versions"][0]["source"], "learned");
  EXPECT_EQ(own["versions"][0]["active"], true);
  ASSERT_EQ(own["learning"].size(), 1u) << own.dump();
  const json exported = json::parse(content());
  ASSERT_EQ(exported["learning_history"].size(), 1u);
  EXPECT_EQ(exported["learning_history"][0]["model_before"]["tool"], "SC EM D10 Z4");
  EXPECT_EQ(exported["learning_history"][0]["model_after"]["tool"], "SC EM D8 Z4");

  // The next part: cut with the new plan, learned into the Ø8's model (version 2, parent 1).
  const fs::path log_2 = dir_ / "d8_log_2.csv";
  ASSERT_EQ(run_feedplan("simulate " + next_.string() + " --spec " + spec.string() + " --log " + log_2.string()).exit_code, 0);
  const RunResult second = run_feedplan("learn " + next_report.string() + " " + log_2.string() + " -o " +
                                        (dir_ / "d8_3.nc").string() + " --db " + db_);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const json own_2 = json_of(run_feedplan("db history " + d8 + " --db " + db_ + " --json").output);
  ASSERT_EQ(own_2["versions"].size(), 2u) << own_2.dump();
  EXPECT_EQ(own_2["versions"][1]["parent_version"], 1);
  EXPECT_EQ(json_of(run_feedplan("db history " + kToolMaterial + " --db " + db_ + " --json").output)["versions"].size(), 1u);
}

// A Ø8 tool named like the stored Ø10 one borrows its model; its cut cannot be filed under that name.
TEST_F(LearnCliTest, ABorrowedModelUnderTheSameToolNameIsNotOverwritten) {
  std::string text = read_text(kSamples + "/corner.yaml");
  text.replace(text.find("diameter_mm: 10"), std::string("diameter_mm: 10").size(), "diameter_mm: 8");
  const fs::path spec = write_spec("corner_d8_same_name.yaml", text);
  const fs::path report = dir_ / "d8.json";
  const fs::path log = dir_ / "d8_log.csv";
  plan_and_cut(spec.string(), dir_ / "d8.nc", report, log);
  expect_refused("learn " + report.string() + " " + log.string() + " -o " + next_.string() + " --db " + db_, 2,
                 {"tool.name", "the spec's tool is a Ø8 4-flute 30° helix", "Ø10 4-flute 30° helix",
                  "give the spec's tool a name of its own"});
}

TEST_F(LearnCliTest, ALogOfAnotherProgramIsRefused) {
  std::string text = read_text(kSamples + "/corner.yaml");
  const std::string angle = "corner_angle_deg: 90";
  ASSERT_NE(text.find(angle), std::string::npos);
  text.replace(text.find(angle), angle.size(), "corner_angle_deg: 60");
  const fs::path spec = write("corner60.yaml", text);
  const fs::path other_log = dir_ / "corner60.csv";
  plan_and_cut(spec.string(), dir_ / "c60.nc", dir_ / "c60.json", other_log);
  expect_refused(learn_args(other_log), 2, {"corner60.csv", "not this program"});
}

TEST_F(LearnCliTest, PositionsInInchesAreRefused) {
  CsvLog log = parse_csv_log(read_text(log_));
  ASSERT_GT(log.rows.size(), 1000u);
  const int x = log.column("x_mm");
  const int y = log.column("y_mm");
  const int z = log.column("z_mm");
  for (auto& cells : log.rows) {
    for (int c : {x, y, z}) {
      if (!cells[c].empty()) cells[c] = fixed(std::stod(cells[c]) / 25.4, 6);
    }
  }
  const fs::path inches = write("inches.csv", log.text());
  expect_refused(learn_args(inches), 2, {"inches.csv", "units look wrong", "inches"});
}

// Landmarks of the virtual machine's log of the corner, found from the log itself.
struct LogLandmarks {
  std::size_t contact = 0;        //!< first row with |F_xy| above 10 % of its largest value
  double contact_s = 0.0;         //!< its time, s
  std::size_t program_start = 0;  //!< the highest row before contact: the machine at the program's first point
  std::vector<double> force_n;    //!< |F_xy| per row, N
  double max_force_n = 0.0;       //!< its largest value, N
};

LogLandmarks landmarks_of(const CsvLog& log) {
  LogLandmarks m;
  m.force_n.resize(log.rows.size());
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    m.force_n[i] = std::hypot(log.number(i, "fx_n"), log.number(i, "fy_n"));
    m.max_force_n = std::max(m.max_force_n, m.force_n[i]);
  }
  while (m.contact < m.force_n.size() && m.force_n[m.contact] < 0.1 * m.max_force_n) ++m.contact;
  EXPECT_LT(m.contact, m.force_n.size());
  if (m.contact == m.force_n.size()) return m;
  m.contact_s = log.number(m.contact, "t_s");
  for (std::size_t i = 0; i < m.contact; ++i) {
    if (log.number(i, "z_mm") > log.number(m.program_start, "z_mm")) m.program_start = i;
  }
  return m;
}

// The rows from `first` to 0.1 s (1.5 mm at the entry feed) before the tool touches the stock, each checked
// to be in the air.
std::vector<std::vector<std::string>> air_rows(const CsvLog& log, const LogLandmarks& m, std::size_t first) {
  std::vector<std::vector<std::string>> air;
  for (std::size_t i = first; i < log.rows.size() && log.number(i, "t_s") < m.contact_s - 0.1; ++i) {
    EXPECT_LT(m.force_n[i], 0.05 * m.max_force_n) << "row " << i;
    air.push_back(log.rows[i]);
  }
  return air;
}

// The log starts where the machine reaches the program's first point (acquisition started with the program):
// see the disabled test below for one that starts at the machine's home position.
TEST_F(LearnCliTest, ALogWithoutTheCutHasNothingToLearn) {
  CsvLog log = parse_csv_log(read_text(log_));
  const LogLandmarks m = landmarks_of(log);
  ASSERT_GT(m.contact_s, 0.15) << "the log should start before the tool reaches the stock";
  log.rows = air_rows(log, m, m.program_start);
  ASSERT_GT(log.rows.size(), 100u);
  const fs::path approach = write("approach.csv", log.text());
  expect_refused(learn_args(approach), 1, {"nothing to learn", "no cut"});
}

TEST_F(LearnCliTest, ATruncatedLogIsLearnedFromAndSaysSo) {
  CsvLog log = parse_csv_log(read_text(log_));
  const LogLandmarks m = landmarks_of(log);
  const std::size_t half = log.rows.size() / 2;
  ASSERT_LT(m.program_start, half);
  log.rows = std::vector<std::vector<std::string>>(log.rows.begin() + static_cast<long>(m.program_start),
                                                   log.rows.begin() + static_cast<long>(half));
  const fs::path first_half = write("half.csv", log.text());
  const RunResult r = run_feedplan(learn_args(first_half) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  const json out = json_of(r.output);
  EXPECT_EQ(out["model_after"]["version"], 2);
  EXPECT_GT(out["samples"].get<int>(), 100);
  const json h = json_of(run_feedplan("db history " + kToolMaterial + " --db " + db_ + " --json").output);
  ASSERT_EQ(h["versions"].size(), 2u);
  EXPECT_EQ(h["versions"][1]["source"], "learned");
  EXPECT_EQ(h["versions"][1]["parent_version"], 1);
  ASSERT_EQ(h["learning"].size(), 1u);
  EXPECT_EQ(h["learning"][0]["n_samples"], out["samples"]);
  EXPECT_TRUE(fs::exists(next_));
}

// Known problem (learning/src/log_alignment.cpp, match_positions): the virtual machine starts at (0, 0, 0)
// and its first rapid, G0 X-50 Y5 at Z0, ends on the plan's plunge line (X-50 Y5, Z5 → Z-10) at s ≈ 4.9 mm.
// That first match is not "at the path's start" (≤ 2 mm), so every row before it, and the rise to Z5 that
// progress can no longer go back to, counts as off the path: 2674 rows. The whole log passes (1.7 % of its
// rows, 2 % allowed); its first half (3.5 %) or its approach alone is called "not this program" (exit 2)
// instead of truncated (exit 0) or no cut (exit 1). Enable when the alignment treats the approach as the
// machine before the program.
TEST_F(LearnCliTest, TheApproachFromTheMachinesHomeIsNotOffThePath) {
  CsvLog log = parse_csv_log(read_text(log_));
  const LogLandmarks m = landmarks_of(log);
  CsvLog approach = log;
  approach.rows = air_rows(log, m, 0);
  expect_refused(learn_args(write("approach.csv", approach.text())), 1, {"nothing to learn", "no cut"});
  log.rows.resize(log.rows.size() / 2);
  const RunResult r = run_feedplan(learn_args(write("half.csv", log.text())));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
}

TEST_F(LearnCliTest, MissingOrNonNumericForceCellsNameTheLine) {
  CsvLog log = parse_csv_log(read_text(log_));
  ASSERT_GT(log.rows.size(), 2000u);
  const std::size_t empty_row = log.rows.size() / 2;
  const std::size_t nan_row = empty_row + 7;
  log.rows[empty_row][log.column("fx_n")] = "";
  log.rows[nan_row][log.column("fy_n")] = "nan";
  const fs::path broken = write("broken.csv", log.text());
  expect_refused(learn_args(broken), 2,
                 {"broken.csv line " + std::to_string(log.line_of(empty_row)), "fx_n",
                  "broken.csv line " + std::to_string(log.line_of(nan_row)), "fy_n"});
}

// The next part's report names the version learned from the first; one not in the database is bad input,
// named by its field, and nothing is stored or written.
TEST_F(LearnCliTest, ALearnedVersionTheDatabaseDoesNotHoldIsBadInput) {
  const fs::path report_2 = dir_ / "part2.json";
  const RunResult first = run_feedplan(learn_args(log_) + " --report " + report_2.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  json edited = json::parse(read_text(report_2));
  ASSERT_EQ(edited["path_learning"]["learned_model"]["version"], 2);
  edited["path_learning"]["learned_model"]["id"] = 999;
  const fs::path report_bad = write("part2_bad.json", edited.dump(2));
  const std::string before = content();
  const fs::path program_3 = dir_ / "part3.nc";
  const RunResult r = run_feedplan("learn " + report_bad.string() + " " + log_.string() + " -o " + program_3.string() +
                                   " --db " + db_);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("path_learning.learned_model.id"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("= 999 (v2): the version learned from this program's earlier parts is not in"), std::string::npos)
      << r.output;
  EXPECT_EQ(content(), before);
  EXPECT_FALSE(fs::exists(program_3));
}

TEST_F(LearnCliTest, AMissingLogOrAMalformedPlanIsBadInput) {
  const fs::path missing = dir_ / "no_such_log.csv";
  expect_refused(learn_args(missing), 2, {missing.string()});
  // The sensor's mode: both flags, each in range.
  expect_refused(learn_args(log_) + " --sensor-hz 800", 2, {"--sensor-damping is missing"});
  expect_refused(learn_args(log_) + " --sensor-hz 800 --sensor-damping 0", 2, {"--sensor-damping = 0", "(0, 2]"});
  expect_refused(learn_args(log_) + " --sensor-hz nan --sensor-damping 0.4", 2, {"--sensor-hz"});

  const std::string report = read_text(plan_);
  // Not JSON at all: cut in the middle.
  write("c.json", report.substr(0, report.size() / 2));
  expect_refused(learn_args(log_), 2, {plan_.string(), "JSON"});
  // A field of the wrong type.
  std::string wrong = report;
  const std::string key = "\"target_force_n\": ";
  ASSERT_NE(wrong.find(key), std::string::npos) << report.substr(0, 2000);
  wrong.insert(wrong.find(key) + key.size(), "\"lots\", \"was\": ");
  write("c.json", wrong);
  expect_refused(learn_args(log_), 2, {"target_force_n"});
}

TEST_F(LoopCliTest, LearnsTheMachineAndLeavesTheDatabaseAlone) {
  const std::string before = content();
  const fs::path revolutions = dir_ / "revolutions.csv";
  const RunResult r = run_feedplan("loop " + kSamples + "/corner.yaml --cycles 2 --db " + db_ +
                                   " --machine-scale 1.5 --target-force 600 --json --revolutions " + revolutions.string() +
                                   " --plot " + (dir_ / "loop.svg").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = read_text(dir_ / "loop.svg");
  for (const char* series : {"measured cycle-1", "measured cycle-2", "feed cycle-1", "next-force", "next-feed", "target"}) {
    EXPECT_NE(svg.find(std::string("class=\"") + series + "\""), std::string::npos) << series;
  }
  const json out = json_of(r.output);
  ASSERT_EQ(out["cycles"].size(), 2u) << r.output;
  const double first = out["cycles"][0]["steady_max_abs_error_percent"].get<double>();
  const double second = out["cycles"][1]["steady_max_abs_error_percent"].get<double>();
  // The machine cuts 1.5 × harder than the model says: the first cycle's steady peaks sit near +50 %.
  EXPECT_GT(first, 30.0) << r.output;
  EXPECT_LT(second, first) << r.output;
  EXPECT_LT(second, 0.5 * first) << r.output;
  EXPECT_EQ(content(), before);

  // The per-revolution CSV holds the revolutions the table summarises: per cycle, the largest |error|
  // of its held rows is the table's, and each error is (peak − target) / target.
  std::istringstream csv(read_text(revolutions));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "cycle,s_start_mm,s_end_mm,x_mm,y_mm,peak_n,planned_force_n,target_n,error_percent,in_cut,held,steady");
  std::vector<double> held_max(2, 0.0);
  std::vector<int> held(2, 0);
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 12u) << line;
    const int cycle = static_cast<int>(v[0]);
    ASSERT_TRUE(cycle == 1 || cycle == 2) << line;
    EXPECT_NEAR(v[8], (v[5] - 600.0) / 600.0 * 100.0, 1e-9) << line;
    if (v[10] == 1.0) {
      ++held[cycle - 1];
      held_max[cycle - 1] = std::max(held_max[cycle - 1], std::abs(v[8]));
    }
  }
  for (int c = 0; c < 2; ++c) {
    EXPECT_EQ(held[c], out["cycles"][c]["held"].get<int>());
    EXPECT_NEAR(held_max[c], out["cycles"][c]["held_max_abs_error_percent"].get<double>(), 1e-9);
  }
}

TEST_F(LoopCliTest, BadFlagsNameTheFlag) {
  const std::string loop = "loop " + kSamples + "/corner.yaml --db " + db_;
  const RunResult zero = run_feedplan(loop + " --cycles 0");
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("--cycles"), std::string::npos) << zero.output;
  const RunResult negative = run_feedplan(loop + " --machine-scale -1");
  EXPECT_EQ(negative.exit_code, 2) << negative.output;
  EXPECT_NE(negative.output.find("--machine-scale"), std::string::npos) << negative.output;
  const std::string machine = kSamples + "/../data/machines/steel-mild.yaml";
  const RunResult both = run_feedplan(loop + " --machine " + machine + " --machine-scale 1.2");
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("--machine-scale conflicts with --machine " + machine), std::string::npos) << both.output;
  const RunResult nowhere = run_feedplan(loop + " --revolutions " + (dir_ / "missing" / "r.csv").string());
  EXPECT_EQ(nowhere.exit_code, 2) << nowhere.output;
  EXPECT_NE(nowhere.output.find("--revolutions"), std::string::npos) << nowhere.output;
  const RunResult no_plot = run_feedplan(loop + " --plot " + (dir_ / "missing" / "h.svg").string());
  EXPECT_EQ(no_plot.exit_code, 2) << no_plot.output;
  EXPECT_NE(no_plot.output.find("--plot"), std::string::npos) << no_plot.output;
}

TEST_F(LoopCliTest, CutsOnAMachineFile) {
  const std::string machine = kSamples + "/../data/machines/steel-mild.yaml";
  const RunResult r = run_feedplan("loop " + kSamples + "/corner.yaml --cycles 1 --db " + db_ + " --machine " + machine +
                                   " --sensor-hz 1500 --sensor-damping 0.6 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json out = json_of(r.output);
  EXPECT_EQ(out["machine"].get<std::string>(), machine);
  EXPECT_FALSE(out.contains("machine_scale"));
  ASSERT_EQ(out["cycles"].size(), 1u) << r.output;
  // Said in words: which shape the dynamometer's factor comes from, and how to get the better one.
  const RunResult text = run_feedplan("loop " + kSamples + "/corner.yaml --cycles 1 --db " + db_ + " --machine " +
                                      machine + " --sensor-hz 1500 --sensor-damping 0.6");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("dynamometer correction: the chip's shape's factor, at most 1.05 (no mechanistic model"),
            std::string::npos) << text.output;
  EXPECT_NE(text.output.find("feedplan db fit --kind mechanistic"), std::string::npos) << text.output;
  // With the tool's mechanistic model in the database, the steady cut takes the kernel's factor too.
  ASSERT_EQ(run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_mechanistic.json --db " + db_)
                .exit_code,
            0);
  const RunResult kernel = run_feedplan("loop " + kSamples + "/corner.yaml --cycles 1 --db " + db_ + " --machine " +
                                        machine + " --sensor-hz 1500 --sensor-damping 0.6");
  ASSERT_EQ(kernel.exit_code, 0) << kernel.output;
  EXPECT_NE(kernel.output.find("more where the engagement is steady and the mechanistic model's force gives more on every machine"),
            std::string::npos) << kernel.output;
}

}  // namespace
