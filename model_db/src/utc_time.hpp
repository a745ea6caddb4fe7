#pragma once
// Internal: time stamps as the store writes them — UTC, ISO 8601, milliseconds, e.g.
// "2024-05-01T12:00:00.123Z" (text that sorts in time order).

#include <string>

namespace feedplan::model_db::detail {

//! The current time as "YYYY-MM-DDTHH:MM:SS.mmmZ".
std::string utc_now_iso8601();

//! Whether `text` has that shape, or the same without milliseconds ("2024-05-01T12:00:00Z"); used to
//! check imported stamps.
bool is_utc_iso8601(const std::string& text);

}  // namespace feedplan::model_db::detail
