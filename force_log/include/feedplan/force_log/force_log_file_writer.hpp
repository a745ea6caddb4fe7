#pragma once
// A force log written to its file while it is recorded, in the text format_force_log gives (the
// same bytes), so a long recording never has to be held in memory. Like write_force_log it leaves
// the file complete or untouched: the text goes to a temporary file beside the target, renamed over
// it by finish(); a writer destroyed before finish() removes it.

#include <cstddef>
#include <fstream>
#include <string>

#include "feedplan/force_log/force_log_sink.hpp"

namespace feedplan::force_log {

//! Streams one force log to `path`.
class ForceLogFileWriter final : public ForceLogSink {
 public:
  //! Creates the temporary file beside `path` at once, so a path that cannot be written is known
  //! before the recording starts (error()).
  explicit ForceLogFileWriter(std::string path);
  ~ForceLogFileWriter() override;
  ForceLogFileWriter(const ForceLogFileWriter&) = delete;
  ForceLogFileWriter& operator=(const ForceLogFileWriter&) = delete;

  //! "" while everything written so far has reached the temporary file, else a message naming the
  //! path and the reason (later rows are then dropped).
  const std::string& error() const { return error_; }

  void begin(const ForceLog& header) override;
  void add(const ForceLogRow& row) override;

  //! Writes what is buffered, closes the file and renames it over the target. Returns "" on success,
  //! otherwise a message naming the path and the reason; the target is then left as it was.
  std::string finish();

  std::size_t rows() const { return rows_; }  //!< rows taken so far

 private:
  void flush_buffer();
  void fail(const std::string& reason);

  std::string path_;
  std::string temporary_;  // the staged file renamed onto the target at finish(); empty when in place
  std::string target_;     // where the log lands: the path, or the file a symbolic link names
  bool in_place_ = false;  // a device or pipe (/dev/stdout): written directly, nothing renamed
  std::ofstream out_;
  std::string buffer_;
  ForceLog header_;
  std::size_t rows_ = 0;
  std::string error_;
  bool finished_ = false;
};

}  // namespace feedplan::force_log
