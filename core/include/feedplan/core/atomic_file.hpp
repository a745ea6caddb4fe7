#pragma once
// Writing an output file so that it is either complete or untouched: the text goes to a temporary
// file beside the target, is flushed to the disk (fsync), and is then renamed over it (rename is atomic on
// POSIX file systems). Every write, flush, close and rename is checked: a full disk or an I/O error is an
// error naming the path and the reason, never a silent success.
//
// Staging and committing are separate steps (StagedFile), so that a command writing several files can
// write them all under temporary names first and rename them only when every one was written: a failure
// then leaves every existing output as it was.
//
// The target may be
// - a new or existing regular file: written as above; an existing file keeps its permission bits;
// - a symbolic link: the file it names is written, the link stays;
// - a device or pipe (/dev/null, /dev/stdout, a FIFO): written in place at commit (there is nothing to
//   rename onto it), with the same checks — /dev/full is "No space left on device".

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cassert>
#include <cerrno>
#include <optional>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

namespace feedplan {

//! What a commit does when the target already exists.
enum class ExistingFile {
  kReplace,  //!< replace it (atomically)
  kKeep,     //!< leave it as it is and write nothing (StagedFile::commit says so)
};

namespace atomic_file_detail {

inline std::string reason(int error_number) { return std::generic_category().message(error_number); }

// Writes all of `content` to `fd`; 0, or the errno of the write that failed.
inline int write_all(int fd, std::string_view content) {
  while (!content.empty()) {
    const ssize_t written = ::write(fd, content.data(), content.size());
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) return errno;
    if (written == 0) return EIO;
    content.remove_prefix(static_cast<std::size_t>(written));
  }
  return 0;
}

// A name beside the target that no other writer uses: the process id and a counter.
inline std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp").append(std::to_string(::getpid()));
  name.append(".").append(std::to_string(counter++));
  return target.parent_path() / name;
}

// The file a write to `path` changes: the file a symbolic link names, else `path` itself.
inline std::filesystem::path resolved_target(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_symlink(path, ec)) return path;
  std::filesystem::path target = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : target;
}

// Makes the rename durable: the directory entry flushed (best effort; some file systems refuse it).
inline void sync_directory(const std::filesystem::path& directory) {
  const int fd = ::open(directory.empty() ? "." : directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace atomic_file_detail

//! New content for one file, written under a temporary name beside it and flushed, waiting to be renamed
//! onto it by commit(). A StagedFile that is destroyed without a commit removes its temporary file, so an
//! abandoned write leaves the target as it was.
class StagedFile {
 public:
  //! Writes `content` to a temporary file beside `path` (beside the file a symbolic link names) and
  //! flushes it to the disk. On failure error() names the path and the reason and nothing is left behind.
  StagedFile(std::filesystem::path path, std::string_view content) : path_(std::move(path)) { stage(content); }

  StagedFile(StagedFile&& other) noexcept { *this = std::move(other); }
  StagedFile& operator=(StagedFile&& other) noexcept {
    discard();
    path_ = std::move(other.path_);
    target_ = std::move(other.target_);
    temporary_ = std::exchange(other.temporary_, {});
    in_place_content_ = std::move(other.in_place_content_);
    in_place_ = other.in_place_;
    committed_ = other.committed_;
    error_ = std::move(other.error_);
    return *this;
  }
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  ~StagedFile() { discard(); }

  //! "" when the content is staged, else "cannot write PATH: REASON".
  const std::string& error() const { return error_; }

  //! The path as given.
  const std::filesystem::path& path() const { return path_; }

  //! Whether the target is a device or pipe, written in place at commit (no rename: it can fail halfway).
  bool in_place() const { return in_place_; }

  //! Puts the staged content in place: renames the temporary file onto the target (or, for a device or
  //! pipe, writes the content to it). With ExistingFile::kKeep an existing target is left as it is: the
  //! temporary file is removed and `kept` (when given) set to true. Returns "" on success, otherwise a
  //! message naming the path and the reason, the target then as it was (a device may have taken part of
  //! the content). Committing a file whose staging failed returns that error. Commit once.
  std::string commit(ExistingFile existing = ExistingFile::kReplace, bool* kept = nullptr) {
    assert(!committed_);
    committed_ = true;
    if (kept) *kept = false;
    if (!error_.empty()) return error_;
    if (in_place_) return commit_in_place(existing, kept);
    const std::string result = existing == ExistingFile::kReplace ? rename_onto_target() : link_onto_new_target(kept);
    discard();
    if (result.empty()) atomic_file_detail::sync_directory(target_.parent_path());
    return result;
  }

 private:
  void fail(const std::string& reason) { error_ = "cannot write " + path_.string() + ": " + reason; }

  void stage(std::string_view content) {
    namespace fs = std::filesystem;
    target_ = atomic_file_detail::resolved_target(path_);
    std::error_code ec;
    const fs::file_status status = fs::status(target_, ec);
    if (fs::is_directory(status)) return fail("it is a directory");
    if (fs::exists(status) && !fs::is_regular_file(status)) {  // a device or a pipe: nothing to rename onto
      in_place_ = true;
      in_place_content_ = std::string(content);
      return;
    }
    const fs::path directory = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
    if (!fs::is_directory(directory, ec)) return fail("directory " + directory.string() + " does not exist");
    std::optional<mode_t> mode;  // an existing file keeps its permission bits
    if (fs::exists(status)) mode = static_cast<mode_t>(status.permissions()) & 07777;
    write_temporary(content, mode);
  }

  // The temporary file, written, flushed and closed, each step checked.
  void write_temporary(std::string_view content, std::optional<mode_t> mode) {
    const std::filesystem::path temporary = atomic_file_detail::temporary_beside(target_);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return fail("cannot create " + temporary.string() + ": " + atomic_file_detail::reason(errno));
    temporary_ = temporary;
    int error = atomic_file_detail::write_all(fd, content);
    if (error == 0 && mode && ::fchmod(fd, *mode) != 0) error = errno;
    if (error == 0 && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error != 0) {
      discard();
      fail(atomic_file_detail::reason(error));
    }
  }

  std::string rename_onto_target() {
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
      return "cannot write " + path_.string() + ": " + atomic_file_detail::reason(errno);
    }
    temporary_.clear();
    return "";
  }

  // A hard link fails with EEXIST when the target exists: no window in which another file is replaced.
  std::string link_onto_new_target(bool* kept) {
    if (::link(temporary_.c_str(), target_.c_str()) == 0) return "";
    if (errno == EEXIST) {
      if (kept) *kept = true;
      return "";
    }
    if (errno != EPERM && errno != ENOTSUP && errno != EOPNOTSUPP) {
      return "cannot write " + path_.string() + ": " + atomic_file_detail::reason(errno);
    }
    std::error_code ec;  // a file system without hard links
    if (std::filesystem::exists(target_, ec)) {
      if (kept) *kept = true;
      return "";
    }
    return rename_onto_target();
  }

  std::string commit_in_place(ExistingFile existing, bool* kept) {
    if (existing == ExistingFile::kKeep) {
      if (kept) *kept = true;
      return "";
    }
    const int fd = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return "cannot write " + path_.string() + ": " + atomic_file_detail::reason(errno);
    int error = atomic_file_detail::write_all(fd, in_place_content_);
    if (::close(fd) != 0 && error == 0) error = errno;
    in_place_content_.clear();
    return error == 0 ? "" : "cannot write " + path_.string() + ": " + atomic_file_detail::reason(error);
  }

  void discard() {
    if (temporary_.empty()) return;
    ::unlink(temporary_.c_str());
    temporary_.clear();
  }

  std::filesystem::path path_;       // as given, for messages
  std::filesystem::path target_;     // the file written: a symbolic link's target, else path_
  std::filesystem::path temporary_;  // the staged content; empty when none is waiting
  std::string in_place_content_;     // for a device or pipe: the content, written at commit
  bool in_place_ = false;            // the target is a device or pipe
  bool committed_ = false;           // commit() was called
  std::string error_;                // why staging failed, or ""
};

//! Writes `content` to `path` atomically (a StagedFile committed at once). Returns an empty string on
//! success, otherwise a message naming the path and the reason; on failure the target is left as it was.
inline std::string write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  StagedFile staged(path, content);
  return staged.commit();
}

}  // namespace feedplan
