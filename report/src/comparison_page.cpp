#include "feedplan/report/comparison_page.hpp"

#include <nlohmann/json.hpp>

#include <cassert>

#include "feedplan/report/html_page.hpp"

namespace feedplan::report {

std::string comparison_page_html(const ComparisonPage& page) {
  using nlohmann::json;
  assert(page.values.size() == page.strategies.size());
  json data;
  data["format"] = "feedplan-html-report";
  data["kind"] = "comparison";
  data["title"] = page.title;
  json summary = json::array();
  for (const auto& [label, value] : page.summary) summary.push_back({label, value});
  data["summary"] = std::move(summary);
  data["notes"] = page.notes;
  json figures = json::array();
  for (const ComparisonFigure& f : page.figures) figures.push_back({{"key", f.key}, {"label", f.label}});
  json rows = json::array();
  for (std::size_t k = 0; k < page.strategies.size(); ++k) {
    assert(page.values[k].size() == page.figures.size());
    json values = json::object();
    for (std::size_t j = 0; j < page.figures.size(); ++j) values[page.figures[j].key] = page.values[k][j];
    rows.push_back({{"name", page.strategies[k]}, {"figures", std::move(values)}});
  }
  data["comparison"] = {{"table", {{"columns", page.table.columns}, {"rows", page.table.rows}}},
                        {"figures", std::move(figures)},
                        {"rows", std::move(rows)}};
  return html_page(page.title, data.dump());
}

}  // namespace feedplan::report
