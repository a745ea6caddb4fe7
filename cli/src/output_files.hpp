#pragma once
// The files one run of a command writes, staged one by one (each written under a temporary name beside
// its target and flushed) and put in place together at the end: when one of them cannot be written, none
// is, and every existing output stays exactly as it was.

#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/atomic_file.hpp"

namespace feedplan::cli {

class OutputFiles {
 public:
  //! Stages `content` for `path`. Returns false when it cannot be written (error() then names the path
  //! and the reason; later adds do nothing), true otherwise.
  bool add(const std::string& path, std::string_view content) {
    if (!error_.empty()) return false;
    StagedFile staged(path, content);
    if (!staged.error().empty()) {
      error_ = staged.error();
      staged_.clear();  // removes what was staged before
      return false;
    }
    staged_.push_back(std::move(staged));
    return true;
  }

  //! The first staging error, or "".
  const std::string& error() const { return error_; }

  //! Puts every staged file in place: first the devices and pipes (/dev/stdout, /dev/full), whose writes
  //! can fail, then the files, renamed in the order added. With ExistingFile::kKeep a file that exists is
  //! left as it is and listed in kept(). Returns the first error, or "" (or the staging error, writing
  //! nothing); after an error nothing more is put in place. Renames do not fail once the files are staged
  //! beside their targets, short of the disk itself failing.
  std::string commit(ExistingFile existing = ExistingFile::kReplace) {
    std::string first_error = error_;
    for (const bool devices : {true, false}) {
      for (StagedFile& staged : staged_) {
        if (!first_error.empty() || staged.in_place() != devices) continue;
        bool kept = false;
        first_error = staged.commit(existing, &kept);
        if (first_error.empty()) (kept ? kept_ : written_).push_back(staged.path().string());
      }
    }
    staged_.clear();  // removes what was not put in place
    return first_error;
  }

  //! The files put in place, in order.
  const std::vector<std::string>& written() const { return written_; }
  //! The files left as they were (ExistingFile::kKeep), in order.
  const std::vector<std::string>& kept() const { return kept_; }

 private:
  std::vector<StagedFile> staged_;
  std::string error_;
  std::vector<std::string> written_;
  std::vector<std::string> kept_;
};

}  // namespace feedplan::cli
