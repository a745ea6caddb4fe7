#pragma once
// Internal: what a Store holds — the SQLite connection, its path and schema version, and the write
// hook tests use to interrupt a transaction.

#include <filesystem>
#include <string_view>

#include "feedplan/model_db/store.hpp"
#include "sqlite_handle.hpp"

namespace feedplan::model_db {

class Store::Impl {
 public:
  Impl(const std::filesystem::path& file, int flags) : path(file), db(file.string(), flags) {}

  //! Calls the write hook, if any, after a step of a write inside its transaction.
  void after_step(std::string_view step) const {
    if (hook) hook(step);
  }

  std::filesystem::path path;
  detail::Connection db;
  int schema_version = 0;
  WriteHook hook;
};

}  // namespace feedplan::model_db
