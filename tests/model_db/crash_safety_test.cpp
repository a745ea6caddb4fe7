// Crash safety of the model store: a child process starts a large import or a model write and is
// killed with SIGKILL in the middle of its transaction (through the store's write hook); the parent then
// opens the database and finds the content exactly as before (a full export compared byte for byte) and
// PRAGMA integrity_check "ok". A child learning step after step is killed at random points (from
// outside, or at a random step of a write) over many trials: the database opens, passes integrity_check
// and holds every acknowledged step and at most the one in flight, each whole, with true parents. An
// exception thrown in the middle of a write rolls it back in-process.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::ScratchDir;

//! Runs `work` in a forked child that gets its own connection (SQLite connections must not cross a
//! fork, so the parent holds none while forking). Returns the child's wait status.
int run_in_child(const std::function<void()>& work) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      work();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);  // the work finished: the kill never came
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

//! A large document: the fixture content of a second store plus 300 cutting tests of 200 peaks each.
std::string large_document(const ScratchDir& dir) {
  Store source = Store::open(dir / "large_source.db", OpenMode::kCreate);
  fixtures::populate(source);
  source.add_tool(fixtures::tool("SC EM D16 Z4", 16, 4, 45));
  for (int i = 0; i < 30; ++i) source.add_model(fixtures::model("SC EM D12 Z4", "S50C", 1.0 + 0.01 * i));
  for (int i = 0; i < 300; ++i) {
    source.add_cutting_test(fixtures::cutting_test(i % 2 == 0 ? "SC EM D12 Z4" : "SC EM D16 Z4", "Ti6Al4V", i, 200));
  }
  return export_json(source);
}

//! A target store with content of its own, so "unchanged" means more than "empty".
void fill_target(const std::filesystem::path& path) {
  Store target = Store::open(path, OpenMode::kCreate);
  target.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
  target.add_tool(fixtures::tool("target's own", 8, 3, 30));
  target.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
  target.add_model(fixtures::model("target's own", "S50C", 1.5));
  target.add_cutting_test(fixtures::cutting_test("target's own", "S50C", 7));
}

std::string full_export(const std::filesystem::path& path) {
  return export_json(Store::open(path, OpenMode::kReadOnly));
}

TEST(CrashSafety, ImportKilledHalfwayLeavesTheDatabaseAsItWas) {
  ScratchDir dir;
  const auto path = dir / "target.db";
  const std::string document = large_document(dir);
  fill_target(path);
  const std::string before = full_export(path);

  // Count the rows a complete import writes, on a copy.
  int total_rows = 0;
  {
    std::filesystem::copy_file(path, dir / "count.db");
    Store counter = Store::open(dir / "count.db", OpenMode::kExisting);
    counter.set_write_hook([&](std::string_view) { ++total_rows; });
    import_json(counter, document);
  }
  ASSERT_GT(total_rows, 300);

  int rows_before_kill = 0;
  const int status = run_in_child([&] {
    StoreOptions small_cache;
    small_cache.cache_size_kib = 64;  // so the half-written transaction spills into the WAL file
    Store store = Store::open(path, OpenMode::kExisting, small_cache);
    store.set_write_hook([&](std::string_view) {
      if (++rows_before_kill == total_rows / 2) ::raise(SIGKILL);
    });
    import_json(store, document);
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child was not killed (exit status " << WEXITSTATUS(status) << ")";
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  // The half-written transaction did reach the disk (more than SQLite's page cache holds), so the
  // rollback below is SQLite's recovery at work, not merely nothing having been written.
  std::error_code ec;
  EXPECT_GT(std::filesystem::file_size(path.string() + "-wal", ec), 256u * 1024u);

  Store after = Store::open(path, OpenMode::kExisting);
  const IntegrityReport report = after.integrity_check();
  EXPECT_TRUE(report.ok) << (report.messages.empty() ? "" : report.messages.front());
  EXPECT_EQ(export_json(after), before);
  // The lock died with the child: the same import now goes through.
  import_json(after, document);
  EXPECT_EQ(after.all_cutting_tests().size(), 1u + 5u + 300u);  // the target's own, the fixture's, the large batch
}

TEST(CrashSafety, ModelWriteKilledBetweenInsertAndActivationLeavesTheOldVersionActive) {
  ScratchDir dir;
  const auto path = dir / "target.db";
  fill_target(path);
  const std::string before = full_export(path);

  for (const char* step : {"models.insert", "models.activate"}) {
    const int status = run_in_child([&] {
      Store store = Store::open(path, OpenMode::kExisting);
      store.set_write_hook([&](std::string_view at) {
        if (at == step) ::raise(SIGKILL);
      });
      store.add_model(fixtures::model("target's own", "S50C", 1.6));
    });
    ASSERT_TRUE(WIFSIGNALED(status)) << step;

    Store after = Store::open(path, OpenMode::kExisting);
    EXPECT_TRUE(after.integrity_check().ok) << step;
    EXPECT_EQ(export_json(after), before) << step;
    const auto versions = after.models_for("target's own", "S50C");
    ASSERT_EQ(versions.size(), 1u) << step;
    EXPECT_TRUE(versions[0].active) << step;
    EXPECT_EQ(after.activation_history("target's own", "S50C").size(), 1u) << step;
  }
}

TEST(CrashSafety, RollbackKilledMidwayChangesNothing) {
  ScratchDir dir;
  const auto path = dir / "target.db";
  fill_target(path);
  {
    Store store = Store::open(path, OpenMode::kExisting);
    store.add_model(fixtures::model("target's own", "S50C", 1.6));
  }
  const std::string before = full_export(path);
  const int status = run_in_child([&] {
    Store store = Store::open(path, OpenMode::kExisting);
    store.set_write_hook([](std::string_view) { ::raise(SIGKILL); });
    store.rollback("target's own", "S50C", 1);
  });
  ASSERT_TRUE(WIFSIGNALED(status));
  Store after = Store::open(path, OpenMode::kExisting);
  EXPECT_TRUE(after.integrity_check().ok);
  EXPECT_EQ(export_json(after), before);
  EXPECT_EQ(after.active_model("target's own", "S50C")->version, 2);
}

// How one trial of the learning kill test stops its child: from outside, after it acknowledged some
// commits (wherever the child then is: inside a transaction, between two, in SQLite's commit), or from
// inside, at a chosen step of a chosen learning step's transaction (through the write hook).
struct KillPlan {
  bool from_outside = true;  // SIGKILL from the parent, else raised by the child's write hook
  int commits_first = 0;     // outside: commits the child acknowledges before the parent kills it
  int delay_us = 0;          // outside: then a pause, so the kill lands anywhere in the next write
  int at_write = 0;          // inside: the write (1, 2, …) to interrupt
  int at_step = 0;           // inside: its step (1 … 4: models.insert, .activate, learning_history, samples)
};

KillPlan random_kill_plan(std::mt19937& random) {
  KillPlan plan;
  plan.from_outside = std::uniform_int_distribution<int>(0, 1)(random) == 1;
  plan.commits_first = std::uniform_int_distribution<int>(0, 3)(random);
  plan.delay_us = std::uniform_int_distribution<int>(0, 4000)(random);
  plan.at_write = std::uniform_int_distribution<int>(1, 3)(random);
  plan.at_step = std::uniform_int_distribution<int>(1, 4)(random);
  return plan;
}

// A child that runs learning steps on `path` one after another until it is killed, writing one byte to
// `acknowledge` after each commit. Returns its pid.
pid_t start_learning_child(const std::filesystem::path& path, const KillPlan& plan, int acknowledge) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  try {
    StoreOptions small_cache;
    small_cache.cache_size_kib = 64;  // so a step's pages spill into the WAL before it commits
    Store store = Store::open(path, OpenMode::kExisting, small_cache);
    int write = 1;
    int step = 0;
    if (!plan.from_outside) {
      store.set_write_hook([&](std::string_view) {
        if (write == plan.at_write && ++step == plan.at_step) ::raise(SIGKILL);
      });
    }
    for (;; ++write) {
      fixtures::learn_step(store, "SC EM D10 Z4", "S50C", 400);
      if (::write(acknowledge, "x", 1) != 1) ::_exit(3);
    }
  } catch (...) {
    ::_exit(3);
  }
}

// Reads acknowledgements until `count` arrived (or the child closed the pipe); returns how many came.
int read_acknowledgements(int fd, int count) {
  int received = 0;
  char byte = 0;
  while ((count < 0 || received < count) && ::read(fd, &byte, 1) == 1) ++received;
  return received;
}

TEST(CrashSafety, LearningKilledAtRandomPointsLeavesTheOldOrTheNewState) {
  const unsigned seed = 20240611u;
  constexpr int kTrials = 40;
  std::mt19937 random(seed);
  ScratchDir dir;
  const auto path = dir / "learning.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    store.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
    store.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
    store.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  }
  int versions_before = 1;
  for (int trial = 0; trial < kTrials; ++trial) {
    const KillPlan plan = random_kill_plan(random);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial) + ": " +
                 (plan.from_outside ? "killed from outside after " + std::to_string(plan.commits_first) + " commits + " +
                                          std::to_string(plan.delay_us) + " us"
                                    : "killed at step " + std::to_string(plan.at_step) + " of write " +
                                          std::to_string(plan.at_write)));
    int pipe_fds[2];
    ASSERT_EQ(::pipe(pipe_fds), 0);
    const pid_t child = start_learning_child(path, plan, pipe_fds[1]);
    ::close(pipe_fds[1]);
    int acknowledged = 0;
    if (plan.from_outside) {
      acknowledged = read_acknowledgements(pipe_fds[0], plan.commits_first);
      ::usleep(static_cast<useconds_t>(plan.delay_us));
      ::kill(child, SIGKILL);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    acknowledged += read_acknowledgements(pipe_fds[0], -1);
    ::close(pipe_fds[0]);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the child ended otherwise: status " << status;

    Store after = Store::open(path, OpenMode::kExisting);  // quick_check on open
    const IntegrityReport report = after.integrity_check();
    ASSERT_TRUE(report.ok) << (report.messages.empty() ? "" : report.messages.front());
    const int versions = static_cast<int>(after.models_for("SC EM D10 Z4", "S50C").size());
    // Every acknowledged commit is there; at most one more (committed, killed before acknowledging it).
    EXPECT_GE(versions, versions_before + acknowledged);
    EXPECT_LE(versions, versions_before + acknowledged + 1);
    if (!plan.from_outside) {
      EXPECT_EQ(versions, versions_before + plan.at_write - 1);
    }
    fixtures::expect_true_lineage(path, "SC EM D10 Z4", "S50C", 400);
    if (HasFailure()) return;
    versions_before = versions;
  }
}

TEST(CrashSafety, AnExceptionHalfwayThroughAnImportRollsItBack) {
  ScratchDir dir;
  const auto path = dir / "target.db";
  const std::string document = large_document(dir);
  fill_target(path);
  Store store = Store::open(path, OpenMode::kExisting);
  const std::string before = export_json(store);
  int rows = 0;
  store.set_write_hook([&](std::string_view step) {
    if (++rows == 150) throw std::runtime_error("injected at row 150 (" + std::string(step) + ")");
  });
  EXPECT_THROW(import_json(store, document), std::runtime_error);
  EXPECT_EQ(rows, 150);
  EXPECT_EQ(export_json(store), before);
  EXPECT_TRUE(store.integrity_check().ok);
  // The store is usable afterwards, and the same import then succeeds.
  store.set_write_hook(nullptr);
  import_json(store, document);
  EXPECT_EQ(store.all_cutting_tests().size(), 1u + 5u + 300u);  // the target's own, the fixture's, the large batch
}

TEST(CrashSafety, AnExceptionInEachStepOfEachWriteRollsItBack) {
  ScratchDir dir;
  const auto base = dir / "base.db";
  fill_target(base);
  Store(Store::open(base, OpenMode::kExisting)).add_model(fixtures::model("target's own", "S50C", 1.6));
  const std::string before = full_export(base);  // every connection closed: the WAL is in the file
  const std::vector<std::function<void(Store&)>> writes{
      [](Store& store) { store.add_tool(fixtures::tool("new tool", 6, 3, 35)); },
      [](Store& store) { store.add_material(fixtures::material("new material", IsoGroup::kM, 180)); },
      [](Store& store) { store.add_model(fixtures::model("target's own", "S50C", 1.7)); },
      [](Store& store) { store.rollback("target's own", "S50C", 1); },
      [](Store& store) { store.add_cutting_test(fixtures::cutting_test("SC EM D10 Z4", "S50C", 3)); },
      [](Store& store) {
        LearningEntry entry;
        entry.model_id_before = store.active_model("target's own", "S50C")->id;
        entry.part_name = "pocket";
        store.add_learning_entry(entry);
      },
  };
  for (std::size_t i = 0; i < writes.size(); ++i) {
    const auto path = dir / ("write" + std::to_string(i) + ".db");
    std::filesystem::copy_file(base, path);
    Store store = Store::open(path, OpenMode::kExisting);
    // Throw at the first step of the write, then at the second, … until it runs through without
    // reaching the step: every interrupted attempt must leave the content as it was.
    int interrupted = 0;
    for (int throw_at = 1;; ++throw_at) {
      int steps = 0;
      store.set_write_hook([&](std::string_view) {
        if (++steps == throw_at) throw std::runtime_error("injected");
      });
      try {
        writes[i](store);
      } catch (const std::runtime_error&) {
        ++interrupted;
        EXPECT_EQ(export_json(store), before) << "write " << i << ", step " << throw_at;
        continue;
      }
      break;
    }
    EXPECT_GE(interrupted, 1) << "write " << i << " has no step to interrupt";
    EXPECT_NE(export_json(store), before) << "write " << i << " changed nothing even when not interrupted";
    EXPECT_TRUE(store.integrity_check().ok);
  }
}

}  // namespace
}  // namespace feedplan::model_db
