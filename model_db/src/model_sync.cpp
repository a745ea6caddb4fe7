#include "feedplan/model_db/model_sync.hpp"

#include "feedplan/model_db/database_url.hpp"

namespace feedplan::model_db {

ImportSummary sync_models(const Store& from, Store& to) {
  return import_json(to, export_json(from), ImportOptions{}, shown_location(from.path().string()));
}

}  // namespace feedplan::model_db
