#pragma once
// A learned version refused because the version it was fitted from is no longer the active one: another
// learning step (another process, or an earlier run) or a rollback changed the active version since.
// Storing it anyway would file it as the child of a version it never saw — a lost update with a wrong
// parent — so the store refuses it and the database stays as it was.

#include <stdexcept>

#include "feedplan/model_db/store_records.hpp"

namespace feedplan::model_db {

//! Thrown by Store::add_learned_model (and by callers checking early) when `fitted_from` is not the active
//! version of its tool and material, `active` is. Not bad input: nothing is wrong with the logs or the
//! plan, the database moved on; what() says what happened and what can be done.
class StaleModelError : public std::runtime_error {
 public:
  StaleModelError(const ModelRecord& fitted_from, const ModelRecord& active);

  //! The version the learning step was fitted from.
  const ModelRecord& fitted_from() const { return fitted_from_; }
  //! The version active when the step was to be stored.
  const ModelRecord& active() const { return active_; }

 private:
  ModelRecord fitted_from_;
  ModelRecord active_;
};

}  // namespace feedplan::model_db
