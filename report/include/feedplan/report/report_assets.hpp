#pragma once
// The files every HTML report embeds, compiled in from report/web at build time (embed_assets.cmake):
// uPlot (the chart library, from npm, pinned in report/web/package-lock.json) and the report page's own
// script and style.

#include <string_view>

namespace feedplan::report::assets {

std::string_view uplot_js();   //!< uPlot.iife.min.js: defines the global uPlot
std::string_view uplot_css();  //!< uPlot.min.css
std::string_view app_js();     //!< report_app.js: draws the page from the embedded JSON
std::string_view app_css();    //!< report_app.css: the page's layout

}  // namespace feedplan::report::assets
