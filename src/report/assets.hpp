// The report's embedded files, generated at build time from src/report/ and third_party/ by
// layerjkr_embed (embed_files.cpp); each holds its file's bytes exactly.
#pragma once

#include <string_view>

namespace layerjkr::detail {

extern const std::string_view kPlotlyJs;       ///< third_party/plotly.js-cartesian-dist-min/plotly-cartesian.min.js
extern const std::string_view kPlotlyLicense;  ///< its LICENSE
extern const std::string_view kPageHtml;       ///< src/report/page.html, the template
extern const std::string_view kPageCss;        ///< src/report/page.css
extern const std::string_view kPageJs;         ///< src/report/page.js

}  // namespace layerjkr::detail
