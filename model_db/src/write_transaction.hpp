#pragma once
// Internal: the one way the store writes — a transaction that holds the database's writer lock from its
// start (SQLite: BEGIN IMMEDIATE; PostgreSQL: a transaction-scoped advisory lock), so the checks made
// inside it see what the writes will change, and that rolls back unless committed.

#include "sql_connection.hpp"

namespace feedplan::model_db::detail {

//! Begins a write transaction on construction; rolls it back on destruction unless commit() was called.
class WriteTransaction {
 public:
  explicit WriteTransaction(Connection& connection) : connection_(connection) {
    connection_.begin_write();
    open_ = true;
  }
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;
  //! Unwinding from an error or exception: undo everything.
  ~WriteTransaction() {
    if (open_) connection_.rollback();
  }

  //! Commits. On failure throws and the destructor rolls back.
  void commit() {
    connection_.commit();
    open_ = false;
  }

 private:
  Connection& connection_;
  bool open_ = false;
};

}  // namespace feedplan::model_db::detail
