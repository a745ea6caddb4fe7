#pragma once
// Internal: what a Store holds — the connection (to a SQLite file or a PostgreSQL server), where it was
// opened from, its schema version, and the write hook tests use to interrupt a transaction.

#include <filesystem>
#include <memory>
#include <string_view>
#include <utility>

#include "feedplan/model_db/store.hpp"
#include "sql_connection.hpp"

namespace feedplan::model_db {

class Store::Impl {
 public:
  Impl(std::filesystem::path where, std::unique_ptr<detail::Connection> opened)
      : path(std::move(where)), connection(std::move(opened)), db(*connection) {}

  //! Calls the write hook, if any, after a step of a write inside its transaction.
  void after_step(std::string_view step) const {
    if (hook) hook(step);
  }

  std::filesystem::path path;
  std::unique_ptr<detail::Connection> connection;
  detail::Connection& db;
  int schema_version = 0;
  WriteHook hook;
};

}  // namespace feedplan::model_db
