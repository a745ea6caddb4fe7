#pragma once
// Which model a learning step changes. A plan made with the model of its own tool and material (an exact
// match) learns into that model: the next version of the same pair. A plan that borrowed another tool's
// or material's model (model_db/model_borrowing.hpp) must not change it — a Ø8 cut would otherwise
// rewrite the Ø10's model — so it learns into the spec's own tool and material: the first version of
// that pair, fitted from the borrowed model as its prior, with the borrowed version recorded as the
// step's "before" in the history. The spec's tool must be registered with the spec's geometry and its
// material registered; otherwise learning is refused with the command that registers them.

#include <string>

#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model_db/store.hpp"

namespace feedplan::cli {

//! The tool and material a learned version is filed under.
struct LearningPair {
  std::string tool_name;      //!< a registered tool
  std::string material_name;  //!< a registered material
  bool borrowed = false;      //!< the plan borrowed the model: the pair is the spec's, not the model's
};

//! The pair for a plan whose model was `planned` with match status `match_status` ("exact", "borrowed",
//! or "" in reports written before it was recorded: taken as exact when `planned` is the spec's own
//! tool and material). Throws InputError naming tool.name or material when a borrowed plan's spec tool
//! is not registered (or registered with another geometry) or its material is not registered, with the
//! `feedplan db` command that registers it in `db_path`.
LearningPair learning_pair(const model_db::Store& store, const std::string& db_path, const cycles::CycleSpec& spec,
                           const model_db::ModelRecord& planned, const std::string& match_status);

}  // namespace feedplan::cli
