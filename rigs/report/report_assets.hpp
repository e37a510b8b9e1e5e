// The episode report's own page template, style sheet and script (rigs/report/, compiled in).
// The template's placeholders @A3_TITLE@, @A3_CSS@, @A3_DATA@, @A3_D3@ and @A3_JS@ are filled
// by episode_report.cpp.
#pragma once

#include <string_view>

namespace a3::rigs {

std::string_view report_page_template();
std::string_view report_style();
std::string_view report_script();

}  // namespace a3::rigs
