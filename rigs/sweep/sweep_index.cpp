// The sweep's index page (sweep_index.hpp).
#include "rigs/sweep/sweep_index.hpp"

#include <cstdio>
#include <optional>
#include <sstream>

#include "common/atomic_file.hpp"
#include "rigs/report/html_page.hpp"

namespace a3::rigs::sweep {
namespace {

namespace fs = std::filesystem;

std::string number(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string with_interval(double mean, const std::optional<Interval>& ci, int digits) {
  std::string out = number(mean, digits);
  if (ci) out += " [" + number(ci->lo, digits) + ", " + number(ci->hi, digits) + "]";
  return out;
}

// The cell's report when the run wrote one, else its episode; relative to the sweep's folder.
fs::path cell_file(const fs::path& out_dir, const ResultRow& row) {
  if (row.episode.empty()) return {};
  const fs::path report = fs::path(row.episode).parent_path() / "report.html";
  std::error_code ec;
  return fs::is_regular_file(out_dir / report, ec) ? report : fs::path(row.episode);
}

// The cell's link, or "–" when it has no file or its path leaves the sweep's folder.
std::string cell_link(const fs::path& out_dir, const ResultRow& row) {
  const fs::path file = cell_file(out_dir, row);
  if (file.empty()) return "–";
  try {
    return "<a href=\"" + html_escaped(relative_href(file)) + "\">" +
           (file.filename() == "report.html" ? "report" : "episode") + "</a>";
  } catch (const std::invalid_argument&) {
    return "–";
  }
}

void plots_section(std::ostream& html, const fs::path& out_dir, const std::vector<fs::path>& pngs) {
  html << "<h2>Plots</h2>\n";
  for (const fs::path& png : pngs) {
    const fs::path rel = fs::relative(png, out_dir);
    html << "<figure><img class=\"plot\" src=\"" << html_escaped(relative_href(rel)) << "\" alt=\""
         << html_escaped(rel.generic_string()) << "\"><figcaption>" << html_escaped(rel.generic_string())
         << "</figcaption></figure>\n";
  }
}

void aggregate_section(std::ostream& html, const std::vector<AggregateRow>& aggregates) {
  html << "<h2>Aggregate (95 % intervals)</h2>\n<table id=\"aggregate\"><tr><th>scenario</th><th>agent</th>"
          "<th>think time</th><th>slice</th><th>n</th><th>α³</th><th>SP</th><th>success</th>"
          "<th title=\"failed episodes with a fault inside the agent\">agent's failures</th></tr>\n";
  for (const AggregateRow& a : aggregates) {
    html << "<tr><td>" << html_escaped(a.scenario) << "</td><td>" << html_escaped(a.agent) << "</td><td>" << html_escaped(a.think_time)
         << "</td><td>" << html_escaped(a.slice) << "</td><td>" << a.n << "</td><td>" << with_interval(a.alpha3_mean, a.alpha3_ci, 3)
         << "</td><td>" << with_interval(a.sp_mean, a.sp_ci, 3) << "</td><td>"
         << with_interval(a.success_rate, a.success_ci, 2) << "</td><td>" << a.agent_failures << "</td></tr>\n";
  }
  html << "</table>\n";
}

// "yes", "no", or "no (agent: <fault kinds>)" when the failure was the agent's own.
std::string success_text(const ResultRow& r) {
  if (r.success) return "yes";
  return r.agent_failure() ? "no (agent: " + html_escaped(r.agent_faults) + ")" : "no";
}

void cells_section(std::ostream& html, const fs::path& out_dir, const std::vector<ResultRow>& rows) {
  html << "<h2>Cells</h2>\n<table id=\"cells\"><tr><th>scenario</th><th>agent</th><th>think time</th><th>slice</th>"
          "<th>seed</th><th>status</th><th>success</th><th>α³</th><th>episode</th></tr>\n";
  for (const ResultRow& r : rows) {
    html << "<tr class=\"cell\"><td>" << html_escaped(r.scenario) << "</td><td>" << html_escaped(r.agent) << "</td><td>"
         << html_escaped(r.think_time) << "</td><td>" << html_escaped(r.slice) << "</td><td>" << r.seed << "</td><td>"
         << html_escaped(r.status) << "</td><td>" << success_text(r) << "</td><td>"
         << (r.has_episode ? number(r.alpha3, 4) : "–") << "</td><td>"
         << cell_link(out_dir, r)
         << "</td></tr>\n";
  }
  html << "</table>\n";
}

constexpr const char* kStyle =
    "body{font:13px/1.4 'DejaVu Sans',Helvetica,Arial,sans-serif;margin:0 16px 32px;color:#222}"
    "table{border-collapse:collapse}th,td{border-bottom:1px solid #e4e4e4;padding:3px 8px;text-align:left}"
    "figure{display:inline-block;margin:6px}img.plot{max-width:720px}";

// Counts the plots that loaded, for a headless browser's check.
constexpr const char* kScript =
    "window.addEventListener('load',function(){var n=0;document.querySelectorAll('img.plot').forEach(function(i){"
    "if(i.complete&&i.naturalWidth>0)++n;});document.body.setAttribute('data-plots-loaded',n);"
    "document.body.setAttribute('data-drawn','yes');});";

}  // namespace

std::string sweep_index_html(const fs::path& out_dir, const std::vector<ResultRow>& rows,
                             const std::vector<AggregateRow>& aggregates, const std::vector<fs::path>& pngs) {
  std::ostringstream html;
  // Images only from the sweep's own folder (the plots); the page's one script and style by hash.
  const std::string policy = content_security_policy({kScript}, {kStyle}, "'self'");
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">" << content_security_policy_meta(policy)
       << "<title>sweep " << html_escaped(out_dir.filename().string())
       << "</title><style>" << kStyle << "</style><script>" << kScript << "</script></head><body>\n<h1>Sweep: "
       << html_escaped(out_dir.string()) << "</h1>\n<p>" << rows.size() << " cells; results.csv and aggregate.csv beside this page.</p>\n";
  plots_section(html, out_dir, pngs);
  aggregate_section(html, aggregates);
  cells_section(html, out_dir, rows);
  html << "</body></html>\n";
  return html.str();
}

fs::path write_sweep_index(const fs::path& out_dir, const std::vector<ResultRow>& rows,
                           const std::vector<AggregateRow>& aggregates, const std::vector<fs::path>& pngs) {
  const fs::path path = out_dir / "index.html";
  common::write_file_atomically(path, sweep_index_html(out_dir, rows, aggregates, pngs));
  return path;
}

}  // namespace a3::rigs::sweep
