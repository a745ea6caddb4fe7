#include "feedplan/force_log/force_log_file_writer.hpp"

#include <cerrno>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "log_text.hpp"

namespace feedplan::force_log {

namespace {

// Text is handed to the file in pieces of about this size.
constexpr std::size_t kBufferBytes = 1 << 20;

// What the system said of the last failed write ("No space left on device"), or a general reason.
std::string system_reason() {
  return errno != 0 ? std::generic_category().message(errno) : std::string("write failed (disk full?)");
}

}  // namespace

ForceLogFileWriter::ForceLogFileWriter(std::string path) : path_(std::move(path)), target_(path_) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_symlink(fs::path(path_), ec)) target_ = fs::weakly_canonical(fs::path(path_), ec).string();
  const fs::file_status status = fs::status(fs::path(target_), ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {  // a device or pipe: no file to stage beside it
    in_place_ = true;
    out_.open(target_, std::ios::binary);
    if (!out_) error_ = "cannot write " + path_ + ": cannot open it";
    buffer_.reserve(kBufferBytes + 4096);
    return;
  }
  const fs::path target(target_);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec)) {
    error_ = "cannot write " + path_ + ": directory " + directory.string() + " does not exist";
    return;
  }
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp").append(std::to_string(::getpid()));
  temporary_ = (directory / name).string();
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) error_ = "cannot write " + path_ + ": cannot create " + temporary_;
  buffer_.reserve(kBufferBytes + 4096);
}

ForceLogFileWriter::~ForceLogFileWriter() {
  if (finished_ || temporary_.empty()) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void ForceLogFileWriter::begin(const ForceLog& header) {
  header_.metadata = header.metadata;
  header_.has_positions = header.has_positions;
  header_.has_forces = header.has_forces;
  header_.has_currents = header.has_currents;
  detail::append_force_log_header(buffer_, header_);
}

void ForceLogFileWriter::add(const ForceLogRow& row) {
  ++rows_;
  if (!error_.empty()) return;
  detail::append_force_log_row(buffer_, header_, row);
  if (buffer_.size() >= kBufferBytes) flush_buffer();
}

void ForceLogFileWriter::flush_buffer() {
  if (error_.empty()) {
    errno = 0;
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    out_.flush();
    if (!out_) fail(system_reason());
  }
  buffer_.clear();
}

void ForceLogFileWriter::fail(const std::string& reason) { error_ = "cannot write " + path_ + ": " + reason; }

std::string ForceLogFileWriter::finish() {
  if (finished_) return error_;
  flush_buffer();
  errno = 0;
  out_.close();
  if (error_.empty() && out_.fail()) fail(system_reason());
  std::error_code ec;
  if (error_.empty() && !in_place_) {
    std::filesystem::rename(temporary_, target_, ec);
    if (ec) fail(ec.message());
  }
  if (!error_.empty() && !temporary_.empty()) std::filesystem::remove(temporary_, ec);
  finished_ = true;
  return error_;
}

}  // namespace feedplan::force_log
