// The page around a report's data (report/html_page.hpp): one file with everything inline, nothing that
// can end a <script> element early, the title escaped.

#include <gtest/gtest.h>

#include <string>

#include "feedplan/report/html_page.hpp"
#include "feedplan/report/report_assets.hpp"

namespace {

using feedplan::report::html_page;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

TEST(ReportHtmlPage, EmbedsUplotAndTheAppAndFetchesNothing) {
  const std::string page = html_page("t", "{}");
  EXPECT_NE(page.find("uPlot"), std::string::npos);
  EXPECT_GT(feedplan::report::assets::uplot_js().size(), 20000u);  // the minified library, not a stub
  EXPECT_GT(feedplan::report::assets::app_js().size(), 1000u);
  EXPECT_EQ(count(page, "<script src"), 0u);
  EXPECT_EQ(count(page, "<link"), 0u);
  // Three scripts (data, uPlot, the app) and two styles, each closed once.
  EXPECT_EQ(count(page, "<script"), 3u);
  EXPECT_EQ(count(page, "</script>"), 3u);
  EXPECT_EQ(count(page, "</style>"), 2u);
}

TEST(ReportHtmlPage, DataCannotEndItsScriptElement) {
  const std::string page = html_page("t", R"({"note":"</script><script>alert(1)</script>"})");
  EXPECT_EQ(count(page, "</script>"), 3u);
  EXPECT_NE(page.find(R"({"note":"<\/script><script>alert(1)<\/script>"})"), std::string::npos);
}

TEST(ReportHtmlPage, TitleIsEscaped) {
  const std::string page = html_page("a < b & \"c\"", "{}");
  EXPECT_NE(page.find("<title>a &lt; b &amp; &quot;c&quot;</title>"), std::string::npos);
  EXPECT_EQ(page.find("a < b"), std::string::npos);
}

}  // namespace
