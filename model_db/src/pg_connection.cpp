#include "pg_connection.hpp"

#include <libpq-fe.h>

#include <stdexcept>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/database_url.hpp"
#include "pg_statement.hpp"

namespace feedplan::model_db::detail {

void PgResultDeleter::operator()(pg_result* result) const { PQclear(result); }

namespace {

// Seconds a connection attempt may take when the URL does not say (libpq's default is to wait forever
// for a host that drops packets).
constexpr const char* kConnectTimeoutS = "10";

// The first line of a libpq message, without its trailing newline.
std::string first_line(const char* message) {
  std::string text = message == nullptr ? "" : message;
  const std::size_t end = text.find('\n');
  if (end != std::string::npos) text.erase(end);
  return text;
}

// "host:port" as the URL gives them (libpq's defaults where it does not: the local socket, 5432).
std::string server_of(const std::string& url) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &error);
  if (options == nullptr) {
    PQfreemem(error);
    return "?";
  }
  std::string host;
  std::string port;
  for (const PQconninfoOption* option = options; option->keyword != nullptr; ++option) {
    if (option->val == nullptr) continue;
    if (std::string_view(option->keyword) == "host") host = option->val;
    if (std::string_view(option->keyword) == "port") port = option->val;
  }
  PQconninfoFree(options);
  if (host.empty()) host = "the local socket";
  std::string server = host;
  server += ":";
  server += port.empty() ? "5432" : port;
  return server;
}

// What may help when the server refused or could not be reached, by what libpq said.
std::string connect_advice(const std::string& message, const std::string& server) {
  if (message.find("password") != std::string::npos || message.find("authentication") != std::string::npos) {
    return "check the user and password in the URL (or ~/.pgpass) and the server's pg_hba.conf";
  }
  if (message.find("does not exist") != std::string::npos) {
    return "check the user and database name in the URL; an administrator makes the database once with "
           "`createdb`, then `feedplan db init --db URL` makes it a model database";
  }
  std::string advice = "the server is not reachable at ";
  advice += server;
  advice += ": check that it is running and that host and port in the URL are right and reachable from this machine "
            "(network, firewall); without the network, plan from a local copy made with `feedplan db sync`";
  return advice;
}

}  // namespace

PgConnection::PgConnection(const std::string& url, int lock_timeout_ms, bool read_only)
    : Connection(shown_location(url)), server_(server_of(url)) {
  char* parse_error = nullptr;
  PQconninfoOption* parsed = PQconninfoParse(url.c_str(), &parse_error);
  if (parsed == nullptr) {
    std::string message = "is not a valid PostgreSQL URL: ";
    message += first_line(parse_error);
    message += "; expected postgresql://USER@HOST:PORT/DBNAME (--db, $FEEDPLAN_DB)";
    PQfreemem(parse_error);
    throw InputError(path(), message);
  }
  PQconninfoFree(parsed);
  // Keywords in order: the URL (expanded as dbname) overrides the defaults before it.
  const char* const keywords[] = {"connect_timeout", "application_name", "dbname", nullptr};
  const char* const values[] = {kConnectTimeoutS, "feedplan", url.c_str(), nullptr};
  connection_ = PQconnectdbParams(keywords, values, 1);
  if (connection_ == nullptr || PQstatus(connection_) != CONNECTION_OK) {
    const std::string reason = connection_ == nullptr ? "out of memory" : first_line(PQerrorMessage(connection_));
    PQfinish(connection_);
    connection_ = nullptr;
    std::string message = "cannot be opened as a model database: the PostgreSQL server at ";
    message += server_;
    message += " refused or did not answer (";
    message += reason;
    message += "); ";
    message += connect_advice(reason, server_);
    message += " (--db, $FEEDPLAN_DB)";
    throw InputError(path(), message);
  }
  // Notices (e.g. "relation already exists, skipping") are not for the user's terminal.
  PQsetNoticeProcessor(connection_, [](void*, const char*) {}, nullptr);
  exec("SET lock_timeout = " + std::to_string(lock_timeout_ms > 0 ? lock_timeout_ms : 1));
  exec("SET client_min_messages = warning");
  if (read_only) exec("SET default_transaction_read_only = on");
}

PgConnection::~PgConnection() { PQfinish(connection_); }

PgResult PgConnection::run(const std::string& sql, int count, const char* const* values, const int* lengths) const {
  PgResult result(count == 0 && values == nullptr
                      ? PQexec(connection_, sql.c_str())
                      : PQexecParams(connection_, sql.c_str(), count, nullptr, values, lengths, nullptr, 0));
  const ExecStatusType status = result ? PQresultStatus(result.get()) : PGRES_FATAL_ERROR;
  if (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK || status == PGRES_EMPTY_QUERY) return result;
  const char* state = result ? PQresultErrorField(result.get(), PG_DIAG_SQLSTATE) : nullptr;
  const std::string code = state == nullptr ? "" : state;
  const std::string message = first_line(result ? PQresultErrorMessage(result.get()) : PQerrorMessage(connection_));
  std::string text = "model database ";
  text += path();
  if (code == "55P03") {
    text += " is busy: another process kept the write lock past the lock timeout (";
  } else if (PQstatus(connection_) != CONNECTION_OK) {
    text += ": lost the connection to the PostgreSQL server at ";
    text += server_;
    text += ", nothing of the unfinished write was stored: ";
    text += message;
    text += " (";
  } else {
    text += ": ";
    text += message;
    text += " (";
  }
  text += sql;
  text += ")";
  throw std::runtime_error(text);
}

void PgConnection::exec(const std::string& sql) { run(sql, 0, nullptr, nullptr); }

std::unique_ptr<StatementBackend> PgConnection::prepare(std::string_view sql) const {
  return std::make_unique<PgStatement>(*this, sql);
}

std::int64_t PgConnection::last_insert_rowid() const {
  const PgResult result = run("SELECT lastval()", 0, nullptr, nullptr);
  return std::stoll(PQgetvalue(result.get(), 0, 0));
}

void PgConnection::begin_write() {
  exec("BEGIN");
  try {
    exec("SELECT pg_advisory_xact_lock(" + std::to_string(kWriterLockKey) + ")");
  } catch (...) {
    rollback();
    throw;
  }
}

void PgConnection::commit() { exec("COMMIT"); }

void PgConnection::rollback() noexcept { PQclear(PQexec(connection_, "ROLLBACK")); }

}  // namespace feedplan::model_db::detail
