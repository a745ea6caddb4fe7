#pragma once
// Copying the content of one model database into another — a local file and a shared server, either way
// — so that a machine without the network keeps planning from its own copy and what it learned reaches
// the others later.

#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"

namespace feedplan::model_db {

//! Copies into `to` what `from` holds: tools, materials, every model version of both kinds with its number,
//! parent version, source, time stamp and which one is active, the cutting tests and the learning history —
//! the content export_json writes, imported by import_json's rules (model_exchange.hpp) in one transaction.
//! What `to` already holds identically is skipped, so a second sync changes nothing. `from`'s active
//! versions become `to`'s. A tool or material of the same name but other content, or a version number that
//! both hold with different content (two machines learned apart), is an InputError naming it, and `to`
//! stays as it was. Returns what was copied and skipped.
ImportSummary sync_models(const Store& from, Store& to);

}  // namespace feedplan::model_db
