#pragma once
// Output paths a command will write: checked with the other flags, before anything is written. An output
// must be a file name in an existing directory, must not be one of the command's inputs (writing it would
// destroy the input) and must not be another output (one would overwrite the other).

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/database_url.hpp"

namespace feedplan::cli {

//! A file a command reads or writes, with the flag or argument that names it (a model database may be a
//! server's URL instead: it is no file, and the checks below pass it by).
struct NamedPath {
  std::string flag;  //!< e.g. "--report", or the argument as the usage names it, e.g. "SPEC"
  std::string path;  //!< as given; "" when not given
};

//! Adds a problem for `flag` unless `path` is empty or names a file (new or existing) in an existing
//! directory.
inline void check_output_path(const std::string& flag, const std::string& path, std::vector<InputProblem>& problems) {
  namespace fs = std::filesystem;
  if (path.empty() || model_db::is_server_url(path)) return;
  const fs::path p(path);
  const fs::path directory = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    problems.push_back({flag, "= '" + path + "': directory '" + directory.string() + "' does not exist"});
  } else if (fs::is_directory(p, ec)) {
    problems.push_back({flag, "= '" + path + "': is a directory, expected a file name"});
  }
}

//! Whether `a` and `b` name the same file: the same file on disk when both exist (through symbolic
//! links, hard links, `./x` and `x`), else the same absolute path with `.`, `..` and links resolved.
inline bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  const fs::path canonical_a = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path canonical_b = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && canonical_a == canonical_b;
}

//! Whether writing `path` replaces a file's content: a new file or an existing regular one (not a device
//! such as /dev/null or /dev/stdout, which several outputs may share).
inline bool writes_a_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  return !fs::exists(status) || fs::is_regular_file(status);
}

//! The one check of a command's outputs, before anything is read from a database or written: adds a
//! problem for every output that is not a file name in an existing directory (check_output_path), that
//! is the same file as one of `inputs` ("-o = 'spec.yaml': is the same file as SPEC ('./spec.yaml'):
//! writing it would destroy that input"), or the same file as an earlier output. Empty paths are skipped.
inline void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs,
                          std::vector<InputProblem>& problems) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& output = outputs[i];
    check_output_path(output.flag, output.path, problems);
    if (output.path.empty() || model_db::is_server_url(output.path) || !writes_a_file(output.path)) continue;
    for (const NamedPath& input : inputs) {
      if (input.path.empty() || model_db::is_server_url(input.path) || !same_file(output.path, input.path)) continue;
      problems.push_back({output.flag, "= '" + output.path + "': is the same file as " + input.flag + " ('" + input.path +
                                           "'): writing it would destroy that input — give another file name"});
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (outputs[j].path.empty() || !same_file(output.path, outputs[j].path)) continue;
      problems.push_back({output.flag, "= '" + output.path + "': is the same file as " + outputs[j].flag + " ('" +
                                           outputs[j].path + "'): each output needs a file of its own"});
    }
  }
}

}  // namespace feedplan::cli
