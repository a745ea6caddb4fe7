#pragma once
// One self-contained HTML page: the title, the report's data as JSON, and everything that draws it —
// uPlot and the page's script and style (report_assets.hpp) — inline, so the file opens offline from
// any folder, with no server and nothing fetched.

#include <string>
#include <string_view>

namespace feedplan::report {

//! The page titled `title` (escaped for HTML) carrying `data_json` (a JSON document, as the page's
//! script reads it: see report_app.js) in a <script type="application/json"> element, with "</" written
//! as "<\/" so no text inside it can end the element.
std::string html_page(std::string_view title, std::string_view data_json);

}  // namespace feedplan::report
