// Writing outputs atomically (core/atomic_file.hpp): a write is complete or leaves the target as it was;
// write errors — a full device, a file-size limit, a missing directory — are errors naming the path and
// the reason, never a silent success; no temporary file is left behind; a symbolic link is written
// through; an existing file keeps its permission bits; ExistingFile::kKeep never replaces a file.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/core/atomic_file.hpp"

namespace feedplan {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("feedplan_atomic_file_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  //! The names in the scratch directory, sorted: what a write left behind.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesANewFileAndReplacesAnOldOne) {
  const fs::path path = dir_ / "out.txt";
  EXPECT_EQ(write_file_atomically(path, "first\n"), "");
  EXPECT_EQ(read_text(path), "first\n");
  EXPECT_EQ(write_file_atomically(path, "second, longer\n"), "");
  EXPECT_EQ(read_text(path), "second, longer\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, AFullDeviceIsAnErrorNamingThePathAndTheReason) {
  if (!fs::is_character_file("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const std::string error = write_file_atomically("/dev/full", "a program\n");
  EXPECT_EQ(error, "cannot write /dev/full: No space left on device");
  EXPECT_TRUE(fs::is_character_file("/dev/full")) << "the device node was replaced";
}

TEST_F(AtomicFileTest, ADeviceThatTakesTheTextIsWrittenInPlace) {
  if (!fs::is_character_file("/dev/null")) GTEST_SKIP() << "no /dev/null here";
  EXPECT_EQ(write_file_atomically("/dev/null", "discarded\n"), "");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// A regular file on a file system that refuses the write: the file-size limit (RLIMIT_FSIZE) makes
// write() fail with EFBIG after the first bytes, as a full disk does with ENOSPC. Run in a child so the
// limit stays there.
TEST_F(AtomicFileTest, AWriteThatFailsHalfwayLeavesTheOldFileAndNoTemporary) {
  const fs::path path = dir_ / "report.json";
  write_text(path, "the old report\n");
  const fs::path message_path = dir_ / "message.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const std::string error = write_file_atomically(path, std::string(100000, 'x'));
    std::ofstream(message_path) << error;  // shorter than the limit
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(read_text(message_path), "cannot write " + path.string() + ": File too large");
  EXPECT_EQ(read_text(path), "the old report\n");
  fs::remove(message_path);
  EXPECT_EQ(entries(), std::vector<std::string>{"report.json"});
}

TEST_F(AtomicFileTest, AMissingDirectoryOrADirectoryTargetIsAnError) {
  EXPECT_EQ(write_file_atomically(dir_ / "nowhere" / "out.txt", "x"),
            "cannot write " + (dir_ / "nowhere" / "out.txt").string() + ": directory " + (dir_ / "nowhere").string() +
                " does not exist");
  fs::create_directory(dir_ / "sub");
  EXPECT_EQ(write_file_atomically(dir_ / "sub", "x"), "cannot write " + (dir_ / "sub").string() + ": it is a directory");
  EXPECT_EQ(entries(), std::vector<std::string>{"sub"});
  EXPECT_TRUE(fs::is_empty(dir_ / "sub"));
}

TEST_F(AtomicFileTest, ASymbolicLinkIsWrittenThroughAndStaysALink) {
  fs::create_directory(dir_ / "real");
  const fs::path real = dir_ / "real" / "program.nc";
  write_text(real, "old\n");
  const fs::path link = dir_ / "program.nc";
  fs::create_symlink(real, link);
  EXPECT_EQ(write_file_atomically(link, "new\n"), "");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_text(real), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "real"), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, AnExistingFileKeepsItsPermissions) {
  const fs::path path = dir_ / "script.sh";
  write_text(path, "old\n");
  fs::permissions(path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
  EXPECT_EQ(write_file_atomically(path, "new\n"), "");
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::mask,
            fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
}

TEST_F(AtomicFileTest, AStagedFileNotCommittedLeavesNothing) {
  const fs::path path = dir_ / "out.csv";
  write_text(path, "old\n");
  {
    StagedFile staged(path, "new\n");
    EXPECT_EQ(staged.error(), "");
    EXPECT_EQ(entries().size(), 2u);  // the target and the staged temporary
    EXPECT_EQ(read_text(path), "old\n");
  }
  EXPECT_EQ(read_text(path), "old\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.csv"});
}

TEST_F(AtomicFileTest, KeepingAnExistingFileWritesOnlyNewOnes) {
  const fs::path existing = dir_ / "plot.svg";
  write_text(existing, "old\n");
  bool kept = false;
  StagedFile onto_existing(existing, "new\n");
  EXPECT_EQ(onto_existing.commit(ExistingFile::kKeep, &kept), "");
  EXPECT_TRUE(kept);
  EXPECT_EQ(read_text(existing), "old\n");
  StagedFile onto_new(dir_ / "new.svg", "new\n");
  EXPECT_EQ(onto_new.commit(ExistingFile::kKeep, &kept), "");
  EXPECT_FALSE(kept);
  EXPECT_EQ(read_text(dir_ / "new.svg"), "new\n");
  EXPECT_EQ(entries(), (std::vector<std::string>{"new.svg", "plot.svg"}));
}

// A child rewrites one file over and over, alternating two large contents, and is killed with SIGKILL at
// random points: the file is always one of the two, whole. A killed writer may leave its temporary
// (".name.tmp<pid>.<n>") behind — never a half-written target.
TEST_F(AtomicFileTest, AWriterKilledAtRandomPointsLeavesTheOldOrTheNewContent) {
  const fs::path path = dir_ / "program.nc";
  const std::string a(3'000'000, 'a');
  const std::string b = std::string(2'000'000, 'b') + "\n";
  ASSERT_EQ(write_file_atomically(path, a), "");
  const unsigned seed = 424242u;
  std::mt19937 random(seed);
  for (int trial = 0; trial < 20; ++trial) {
    const int writes_first = std::uniform_int_distribution<int>(0, 2)(random);
    const int delay_us = std::uniform_int_distribution<int>(0, 20000)(random);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t child = ::fork();
    if (child == 0) {
      ::close(fds[0]);
      for (int i = 0;; ++i) {
        if (!write_file_atomically(path, i % 2 == 0 ? b : a).empty()) ::_exit(3);
        if (::write(fds[1], "x", 1) != 1) ::_exit(3);
      }
    }
    ::close(fds[1]);
    char byte = 0;
    for (int i = 0; i < writes_first && ::read(fds[0], &byte, 1) == 1; ++i) {
    }
    ::usleep(static_cast<useconds_t>(delay_us));
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ::close(fds[0]);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the writer ended otherwise: status " << status;
    const std::string content = read_text(path);
    EXPECT_TRUE(content == a || content == b) << "a half-written file of " << content.size() << " bytes";
  }
  for (const std::string& name : entries()) {
    EXPECT_TRUE(name == "program.nc" || name.rfind(".program.nc.tmp", 0) == 0) << name;
  }
}

}  // namespace
}  // namespace feedplan
