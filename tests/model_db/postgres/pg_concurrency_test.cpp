// Learners on two processes sharing one model database on a PostgreSQL server (as two machines running
// `feedplan learn`), and a learner killed with SIGKILL in the middle of its write. Each process opens its
// own connection after the fork; the processes are synchronised with pipes, not timing.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "../store_fixtures.hpp"
#include "feedplan/model_db/stale_model_error.hpp"
#include "feedplan/model_db/store.hpp"
#include "pg_test_server.hpp"

namespace feedplan::model_db {
namespace {

const std::string kTool = "SC EM D10 Z4";
const std::string kMaterial = "S50C";
constexpr int kSamples = 20;

constexpr int kLanded = 0;
constexpr int kRefused = 4;  // StaleModelError
constexpr int kOtherError = 5;

std::string make_database() {
  const std::string url = pg_test::fresh_database();
  Store store = Store::open(url, OpenMode::kCreate);
  store.add_tool(fixtures::tool(kTool, 10, 4, 30));
  store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  store.add_model(fixtures::model(kTool, kMaterial, 1.0));
  return url;
}

// A one-byte signal between processes over a pipe; wait() is false when every sender died without sending.
struct Signal {
  Signal() { EXPECT_EQ(::pipe(fds), 0); }
  ~Signal() { close_all(); }
  void send() const { EXPECT_EQ(::write(fds[1], "x", 1), 1); }
  bool wait() const {
    char byte = 0;
    return ::read(fds[0], &byte, 1) == 1;
  }
  void close_end(int end) {
    if (fds[end] >= 0) ::close(fds[end]);
    fds[end] = -1;
  }
  void close_all() {
    close_end(0);
    close_end(1);
  }
  int fds[2] = {-1, -1};
};

// Forks a process running `work`; its exit status is kLanded, kRefused (StaleModelError) or kOtherError.
pid_t start_process(const std::function<void()>& work) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  int status = kLanded;
  try {
    work();
  } catch (const StaleModelError&) {
    status = kRefused;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "learner failed: %s\n", e.what());
    status = kOtherError;
  }
  ::_exit(status);
}

int wait_for(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return status;
}

// The pair's versions form one line of learning steps: each later version learned, its parent the version
// before it and its one learning entry fitted from that parent, the last one active, every step's samples
// stored.
void expect_true_lineage(const std::string& url, int samples) {
  const Store store = Store::open(url, OpenMode::kReadOnly);
  const std::vector<ModelRecord> versions = store.models_for(kTool, kMaterial);
  ASSERT_FALSE(versions.empty());
  std::map<RowId, RowId> fitted_from;
  for (const LearningEntry& entry : store.learning_history(kTool, kMaterial)) {
    EXPECT_TRUE(fitted_from.emplace(entry.model_id_after, entry.model_id_before).second);
  }
  EXPECT_EQ(fitted_from.size(), versions.size() - 1);
  for (std::size_t i = 1; i < versions.size(); ++i) {
    const ModelRecord& v = versions[i];
    EXPECT_EQ(v.version, static_cast<int>(i) + 1);
    ASSERT_TRUE(v.parent_id.has_value()) << "version " << v.version;
    EXPECT_EQ(*v.parent_id, versions[i - 1].id) << "version " << v.version << ": parent is not the version before it";
    EXPECT_EQ(fitted_from[v.id], *v.parent_id) << "version " << v.version;
  }
  EXPECT_TRUE(versions.back().active);
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM models WHERE active = 1"), "1");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_samples"),
            std::to_string(static_cast<int>(versions.size() - 1) * samples));
}

TEST(PgConcurrentLearning, TwoLearnerProcessesFromTheSameVersionBothLandWithTrueParents) {
  ::signal(SIGPIPE, SIG_IGN);
  const std::string url = make_database();
  Signal have_read[2], go[2];
  int refusals[2] = {0, 0};
  Signal refused[2];
  pid_t learners[2] = {0, 0};
  for (int me = 0; me < 2; ++me) {
    learners[me] = start_process([&, me] {
      Store store = Store::open(url, OpenMode::kExisting);
      bool first = true;
      for (;;) {
        try {
          fixtures::learn_step(store, kTool, kMaterial, kSamples, [&] {
            if (!first) return;
            first = false;
            have_read[me].send();  // both read v1 before either writes
            if (!go[me].wait()) ::_exit(kOtherError);
          });
          return;
        } catch (const StaleModelError&) {
          refused[me].send();  // the other one landed first: learn again from the new active version
        }
      }
    });
  }
  for (int i = 0; i < 2; ++i) {
    have_read[i].close_end(1);
    go[i].close_end(0);
    refused[i].close_end(1);
  }
  const bool both_read = have_read[0].wait() && have_read[1].wait();
  go[0].send();
  go[1].send();
  const int status_a = wait_for(learners[0]);
  const int status_b = wait_for(learners[1]);
  ASSERT_TRUE(both_read) << "a learner died before reading";
  EXPECT_TRUE(WIFEXITED(status_a) && WEXITSTATUS(status_a) == kLanded) << "status " << status_a;
  EXPECT_TRUE(WIFEXITED(status_b) && WEXITSTATUS(status_b) == kLanded) << "status " << status_b;
  for (int i = 0; i < 2; ++i) {
    while (refused[i].wait()) ++refusals[i];
  }
  // Exactly one was refused once: the race was real, and neither step was filed under v1 twice.
  EXPECT_EQ(refusals[0] + refusals[1], 1);
  const Store store = Store::open(url, OpenMode::kReadOnly);
  EXPECT_EQ(store.models_for(kTool, kMaterial).size(), 3u);
  expect_true_lineage(url, kSamples);
}

TEST(PgConcurrentLearning, ManyStepsFromTwoProcessesAllLandInOneLine) {
  const std::string url = make_database();
  constexpr int kStepsEach = 10;
  Signal start;
  std::vector<pid_t> learners;
  for (int i = 0; i < 2; ++i) {
    learners.push_back(start_process([&] {
      start.close_end(1);
      Store store = Store::open(url, OpenMode::kExisting);
      if (!start.wait()) ::_exit(kOtherError);
      for (int landed = 0; landed < kStepsEach;) {
        try {
          fixtures::learn_step(store, kTool, kMaterial, kSamples);
          ++landed;
        } catch (const StaleModelError&) {
        }
      }
    }));
  }
  start.close_end(0);
  start.send();
  start.send();
  for (const pid_t pid : learners) {
    const int status = wait_for(pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == kLanded) << "status " << status;
  }
  const Store store = Store::open(url, OpenMode::kReadOnly);
  EXPECT_EQ(store.models_for(kTool, kMaterial).size(), 1u + 2 * kStepsEach);
  expect_true_lineage(url, kSamples);
}

// The database as a text: every table's row count and the active versions.
std::string snapshot(const std::string& url) {
  std::string text;
  for (const char* table : {"models", "model_activations", "learning_history", "learning_samples", "tools", "materials"}) {
    text += std::string(table) + " " + pg_test::raw_sql(url, std::string("SELECT count(*) FROM ") + table) + "; ";
  }
  text += "active " + pg_test::raw_sql(url, "SELECT string_agg(id::text, ',' ORDER BY id) FROM models WHERE active = 1");
  return text;
}

TEST(PgCrashSafety, ALearnerKilledMidWriteLeavesTheDatabaseValidAndUnchanged) {
  const std::string url = make_database();
  {
    Store store = Store::open(url, OpenMode::kExisting);
    fixtures::learn_step(store, kTool, kMaterial, kSamples);
  }
  const std::string before = snapshot(url);
  for (const char* kill_at : {"models.insert", "models.activate", "learning_history.insert", "learning_samples.insert"}) {
    SCOPED_TRACE(kill_at);
    const pid_t child = start_process([&] {
      Store store = Store::open(url, OpenMode::kExisting);
      store.set_write_hook([kill_at](std::string_view step) {
        if (step == kill_at) ::raise(SIGKILL);
      });
      fixtures::learn_step(store, kTool, kMaterial, kSamples);
    });
    const int status = wait_for(child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the child ended otherwise: status " << status;
    EXPECT_EQ(snapshot(url), before);
    const Store store = Store::open(url, OpenMode::kReadOnly);
    EXPECT_TRUE(store.integrity_check().ok);
    EXPECT_EQ(store.active_model(kTool, kMaterial)->version, 2);
  }
  // The killed writers' lock went with their connections: the next learner lands at once, as v3 on v2.
  Store store = Store::open(url, OpenMode::kExisting, StoreOptions{.busy_timeout_ms = 5000});
  const ModelRecord v3 = fixtures::learn_step(store, kTool, kMaterial, kSamples);
  EXPECT_EQ(v3.version, 3);
  expect_true_lineage(url, kSamples);
}

}  // namespace
}  // namespace feedplan::model_db
