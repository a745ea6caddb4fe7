#include "feedplan/force_log/force_log_file_writer.hpp"

#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "log_text.hpp"

namespace feedplan::force_log {

namespace {

// Text is handed to the file in pieces of about this size.
constexpr std::size_t kBufferBytes = 1 << 20;

}  // namespace

ForceLogFileWriter::ForceLogFileWriter(std::string path) : path_(std::move(path)) {
  namespace fs = std::filesystem;
  const fs::path target(path_);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
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
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    if (!out_) fail("write failed (disk full?)");
  }
  buffer_.clear();
}

void ForceLogFileWriter::fail(const std::string& reason) { error_ = "cannot write " + path_ + ": " + reason; }

std::string ForceLogFileWriter::finish() {
  if (finished_) return error_;
  flush_buffer();
  if (error_.empty()) {
    out_.flush();
    if (!out_) fail("write failed (disk full?)");
  }
  out_.close();
  std::error_code ec;
  if (error_.empty()) {
    std::filesystem::rename(temporary_, path_, ec);
    if (ec) fail(ec.message());
  }
  if (!error_.empty() && !temporary_.empty()) std::filesystem::remove(temporary_, ec);
  finished_ = true;
  return error_;
}

}  // namespace feedplan::force_log
