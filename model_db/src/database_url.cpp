#include "feedplan/model_db/database_url.hpp"

namespace feedplan::model_db {

bool is_server_url(std::string_view location) {
  return location.starts_with("postgresql://") || location.starts_with("postgres://");
}

std::string shown_location(std::string_view location) {
  std::string shown(location);
  if (!is_server_url(location)) return shown;
  const std::size_t authority = shown.find("://") + 3;
  const std::size_t at = shown.find('@', authority);
  const std::size_t slash = shown.find('/', authority);
  if (at != std::string::npos && (slash == std::string::npos || at < slash)) {
    const std::size_t colon = shown.find(':', authority);
    if (colon != std::string::npos && colon < at) shown.replace(colon + 1, at - colon - 1, "***");
  }
  const std::size_t query = shown.find('?');
  for (std::size_t key = shown.find("password=", query == std::string::npos ? shown.size() : query);
       key != std::string::npos; key = shown.find("password=", key + 1)) {
    const std::size_t value = key + 9;
    const std::size_t end = shown.find('&', value);
    shown.replace(value, (end == std::string::npos ? shown.size() : end) - value, "***");
  }
  return shown;
}

}  // namespace feedplan::model_db
