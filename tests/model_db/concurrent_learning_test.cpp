// Two learners on one database (two processes, each with its own Store connection, as two `feedplan
// learn` runs): a learned version is filed as the child of the version it was fitted from, so when both
// read the same active version and then write, one lands and the other is refused (StaleModelError) —
// never both on one parent, never one filed under a version it did not see. Learners that retry from the
// new active version all land, each with its true parent.
//
// The processes are synchronised with pipes, not timing: the parent lets both read before either writes.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "feedplan/model_db/stale_model_error.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::ScratchDir;

const std::string kTool = "SC EM D10 Z4";
const std::string kMaterial = "S50C";
constexpr int kSamples = 50;

// How a learner process ended (its exit status).
constexpr int kLanded = 0;
constexpr int kRefused = 4;  // StaleModelError
constexpr int kOtherError = 5;

void make_database(const std::filesystem::path& path) {
  Store store = Store::open(path, OpenMode::kCreate);
  store.add_tool(fixtures::tool(kTool, 10, 4, 30));
  store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  store.add_model(fixtures::model(kTool, kMaterial, 1.0));
}

// A pipe used as a signal between processes. Each process closes the ends it does not use, so that a
// wait returns (false) when the only process that could send has died, instead of hanging.
struct Signal {
  Signal() { EXPECT_EQ(::pipe(fds), 0); }
  ~Signal() { close_all(); }
  void send() const { EXPECT_EQ(::write(fds[1], "x", 1), 1); }
  bool wait() const {  // false when every sender is gone without sending
    char byte = 0;
    return ::read(fds[0], &byte, 1) == 1;
  }
  void close_end(int end) {
    if (fds[end] >= 0) ::close(fds[end]);
    fds[end] = -1;
  }
  void keep_sending_end() { close_end(0); }
  void keep_waiting_end() { close_end(1); }
  void close_all() {
    close_end(0);
    close_end(1);
  }
  int fds[2] = {-1, -1};
};

// Forks a learner running `work` with its own connection; returns its pid. Exit status: kLanded,
// kRefused (StaleModelError) or kOtherError.
pid_t start_learner(const std::function<void()>& work) {
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

int exit_status_of(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

TEST(ConcurrentLearning, TwoLearnersFromTheSameVersionOneLandsTheOtherIsRefused) {
  ::signal(SIGPIPE, SIG_IGN);  // a learner that died makes send() fail, not the test process
  ScratchDir dir;
  const auto path = dir / "models.db";
  make_database(path);
  constexpr int kRounds = 8;
  for (int round = 0; round < kRounds; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    Signal have_read[2], go[2];  // per learner: "I have read the active version", "write now"
    pid_t learners[2] = {0, 0};
    for (int me = 0; me < 2; ++me) {
      learners[me] = start_learner([&] {
        have_read[me].keep_sending_end();
        go[me].keep_waiting_end();
        have_read[1 - me].close_all();
        go[1 - me].close_all();
        Store store = Store::open(path, OpenMode::kExisting);
        fixtures::learn_step(store, kTool, kMaterial, kSamples, [&] {
          have_read[me].send();  // the "fitting" waits until the other learner has read the same version
          if (!go[me].wait()) ::_exit(kOtherError);
        });
      });
    }
    for (int i = 0; i < 2; ++i) {
      have_read[i].keep_waiting_end();
      go[i].keep_sending_end();
    }
    const bool both_read = have_read[0].wait() && have_read[1].wait();
    go[0].send();
    go[1].send();
    const int status_a = exit_status_of(learners[0]);
    const int status_b = exit_status_of(learners[1]);
    ASSERT_TRUE(both_read) << "a learner died before reading: exit " << status_a << ", " << status_b;
    EXPECT_TRUE((status_a == kLanded && status_b == kRefused) || (status_a == kRefused && status_b == kLanded))
        << "learner a exited " << status_a << ", learner b " << status_b << " (0 landed, 4 refused)";
    const Store store = Store::open(path, OpenMode::kReadOnly);
    EXPECT_EQ(store.models_for(kTool, kMaterial).size(), static_cast<std::size_t>(round) + 2);
  }
  fixtures::expect_true_lineage(path, kTool, kMaterial, kSamples);
}

TEST(ConcurrentLearning, LearnersThatRetryFromTheNewActiveVersionAllLandWithTrueParents) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  make_database(path);
  constexpr int kLearners = 3;
  constexpr int kStepsEach = 15;
  Signal start;
  std::vector<pid_t> learners;
  for (int i = 0; i < kLearners; ++i) {
    learners.push_back(start_learner([&] {
      Store store = Store::open(path, OpenMode::kExisting);
      if (!start.wait()) ::_exit(kOtherError);
      for (int landed = 0; landed < kStepsEach;) {
        try {
          fixtures::learn_step(store, kTool, kMaterial, kSamples);
          ++landed;
        } catch (const StaleModelError&) {
          // another learner stored a version since this one read: learn again from the new active one
        }
      }
    }));
  }
  for (int i = 0; i < kLearners; ++i) start.send();
  for (const pid_t pid : learners) EXPECT_EQ(exit_status_of(pid), kLanded);
  const Store store = Store::open(path, OpenMode::kReadOnly);
  EXPECT_EQ(store.models_for(kTool, kMaterial).size(), 1u + kLearners * kStepsEach);
  fixtures::expect_true_lineage(path, kTool, kMaterial, kSamples);
}

TEST(ConcurrentLearning, AStepFromAVersionNoLongerActiveIsRefusedAndStoresNothing) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  make_database(path);
  Store store = Store::open(path, OpenMode::kExisting);
  const ModelRecord v1 = *store.active_model(kTool, kMaterial);
  const ModelRecord v2 = fixtures::learn_step(store, kTool, kMaterial, kSamples);
  const std::string before = fixtures::raw_sql(path, "SELECT count(*) FROM models") + " models, " +
                             fixtures::raw_sql(path, "SELECT count(*) FROM learning_history") + " entries";
  ModelRecord learned = fixtures::model(kTool, kMaterial, 1.3);
  learned.source = ModelSource::kLearned;
  LearningEntry entry;
  entry.model_id_before = v1.id;  // fitted from v1, while v2 is active
  entry.part_name = "late part";
  try {
    store.add_learned_model(learned, entry, {{0.02, 4.0, 350.0, 1.0, 0.0}});
    ADD_FAILURE() << "a step fitted from v1 was stored while v2 is active";
  } catch (const StaleModelError& e) {
    EXPECT_EQ(e.fitted_from().id, v1.id);
    EXPECT_EQ(e.active().id, v2.id);
    const std::string message = e.what();
    EXPECT_NE(message.find("SC EM D10 Z4 in S50C v1"), std::string::npos) << message;
    EXPECT_NE(message.find("v2 (id " + std::to_string(v2.id)), std::string::npos) << message;
    EXPECT_NE(message.find("feedplan db rollback --tool \"SC EM D10 Z4\" --material \"S50C\" --version 1"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM models") + " models, " +
                fixtures::raw_sql(path, "SELECT count(*) FROM learning_history") + " entries",
            before);
  // After a rollback to v1, the same step is v1's true child.
  store.rollback(kTool, kMaterial, 1);
  const ModelRecord v3 = store.add_learned_model(learned, entry, {{0.02, 4.0, 350.0, 1.0, 0.0}}).first;
  EXPECT_EQ(v3.version, 3);
  ASSERT_TRUE(v3.parent_id.has_value());
  EXPECT_EQ(*v3.parent_id, v1.id);
}

}  // namespace
}  // namespace feedplan::model_db
