#include "feedplan/report/html_page.hpp"

#include "feedplan/report/report_assets.hpp"

namespace feedplan::report {
namespace {

void append_escaped_html(std::string& out, std::string_view text) {
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
}

// Text inside <script> or <style>: "</" would end the element early (a chart library's own strings may
// hold "</div>"); "<\/" means the same in JavaScript strings and JSON, and never occurs in CSS.
void append_script_text(std::string& out, std::string_view text) {
  std::size_t start = 0;
  for (std::size_t at = text.find("</"); at != std::string_view::npos; at = text.find("</", start)) {
    out.append(text.substr(start, at - start));
    out += "<\\/";
    start = at + 2;
  }
  out.append(text.substr(start));
}

}  // namespace

std::string html_page(std::string_view title, std::string_view data_json) {
  std::string page;
  page.reserve(data_json.size() + assets::uplot_js().size() + assets::app_js().size() + 8192);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>";
  append_escaped_html(page, title);
  page += "</title>\n<style>\n";
  append_script_text(page, assets::uplot_css());
  page += "\n</style>\n<style>\n";
  append_script_text(page, assets::app_css());
  page += "\n</style>\n</head>\n<body>\n<h1 id=\"title\">";
  append_escaped_html(page, title);
  page += "</h1>\n<div id=\"report\"></div>\n<script type=\"application/json\" id=\"report-data\">\n";
  append_script_text(page, data_json);
  page += "\n</script>\n<script>\n";
  append_script_text(page, assets::uplot_js());
  page += "\n</script>\n<script>\n";
  append_script_text(page, assets::app_js());
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace feedplan::report
