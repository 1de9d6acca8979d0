// `radchain report`: the HTML pages, rendered from report.json's model (html_report_model.hpp). Static HTML5, one
// inline style sheet and one inline script (sortable tables) per page; nothing is fetched.
#include "html_report_model.hpp"

#include "radchain/batch/svg_plot.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

namespace radchain::html_detail {
namespace {

using svg::xml_escape;

std::string esc(const std::string& s) { return xml_escape(s); }
std::string esc(const Json& j) { return j.is_string() ? xml_escape(j.get<std::string>()) : std::string(); }

// A dotted name or a path, escaped, that may break after its dots, underscores, slashes and hyphens only.
std::string breakable(const std::string& name) {
  std::string out;
  for (char c : name) {
    out += xml_escape(std::string(1, c));
    if (c == '.' || c == '_' || c == '/' || c == '-') out += "<wbr>";
  }
  return out;
}

const char* const style = R"css(
:root{--fg:#1b1f24;--muted:#57606a;--line:#d0d7de;--ok:#1a7f37;--fail:#cf222e;--info:#9a6700;--alt:#f6f8fa}
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 "DejaVu Sans","Liberation Sans",Arial,sans-serif;color:var(--fg);background:#fff}
header.top{background:#24292f;color:#fff;padding:9px 24px;font-size:13px}
header.top a{color:#d0d7de;text-decoration:none} header.top a:hover{text-decoration:underline}
main{max-width:1200px;margin:0 auto;padding:6px 24px 40px}
h1{font-size:23px;margin:18px 0 4px}
h2{font-size:18px;margin:30px 0 8px;border-bottom:1px solid var(--line);padding-bottom:4px}
h3{font-size:15px;margin:18px 0 6px}
a{color:#0550ae}
table{border-collapse:collapse;width:100%;margin:6px 0 14px;font-size:13px}
th,td{border-bottom:1px solid var(--line);padding:4px 8px;text-align:left;vertical-align:top}
th{background:var(--alt);font-weight:600;white-space:nowrap}
table.sortable th{cursor:pointer;user-select:none}
table.sortable th::after{content:" \2195";color:#8c959f;font-weight:400}
table.sortable th[aria-sort=ascending]::after{content:" \25B2";color:var(--fg)}
table.sortable th[aria-sort=descending]::after{content:" \25BC";color:var(--fg)}
tbody tr:hover{background:#f3f6fa}
td.num,th.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
td.text{overflow-wrap:anywhere}
td.name{white-space:nowrap}
td.breakable{overflow-wrap:normal}
.status{font-weight:700;white-space:nowrap}
.status.ok{color:var(--ok)} .status.FAIL,.status.ERROR{color:var(--fail)} .status.info,.status.warning{color:var(--info)}
.badge{display:inline-block;border-radius:10px;padding:1px 10px;font-size:12px;font-weight:700;color:#fff;vertical-align:middle}
.badge.ok{background:var(--ok)} .badge.FAIL,.badge.ERROR{background:var(--fail)}
.muted,figcaption{color:var(--muted)}
code,.mono{font-family:"DejaVu Sans Mono","Liberation Mono",monospace;font-size:12.5px}
figure{margin:10px 0 26px}
figure svg{max-width:100%;height:auto;display:block}
figcaption{font-size:13px;max-width:920px;margin-top:4px}
dl.meta{display:grid;grid-template-columns:max-content 1fr;gap:3px 16px;margin:10px 0}
dl.meta dt{color:var(--muted)} dl.meta dd{margin:0;overflow-wrap:anywhere}
.error{background:#ffebe9;border:1px solid #ff8182;padding:8px 12px;white-space:pre-wrap;overflow-wrap:anywhere}
.keys{display:flex;flex-wrap:wrap;gap:10px;margin:12px 0}
.key{border:1px solid var(--line);border-radius:6px;padding:6px 12px;background:var(--alt)}
.key .v{font-size:18px;font-weight:700}
nav.toc{margin:10px 0;font-size:13px} nav.toc a{margin-right:14px}
.default{color:var(--muted);font-style:italic}
ul.warnings li{color:#7d4e00;overflow-wrap:anywhere}
ol.chain li{margin:3px 0}
.scroll{overflow-x:auto}
footer{color:var(--muted);font-size:12px;border-top:1px solid var(--line);margin-top:30px;padding-top:8px}
)css";

// Click (or Enter on) a header to sort by that column; again to reverse. Cells sort by data-sort when they have one
// (the full-precision number), else by their text; numbers before text.
const char* const sort_script = R"js(
document.querySelectorAll('table.sortable').forEach(function (table) {
  var heads = table.tHead.rows[0].cells;
  Array.prototype.forEach.call(heads, function (th, column) {
    th.tabIndex = 0;
    function key(row) {
      var cell = row.cells[column];
      if (!cell) return '';
      var v = cell.hasAttribute('data-sort') ? cell.getAttribute('data-sort') : cell.textContent.trim();
      return v !== '' && isFinite(Number(v)) ? Number(v) : v.toLowerCase();
    }
    function sort() {
      var ascending = th.getAttribute('aria-sort') !== 'ascending';
      Array.prototype.forEach.call(heads, function (h) { h.removeAttribute('aria-sort'); });
      th.setAttribute('aria-sort', ascending ? 'ascending' : 'descending');
      var body = table.tBodies[0], rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a), y = key(b), r;
        if (typeof x === 'number' && typeof y === 'number') r = x - y;
        else if (typeof x === 'number') r = -1;
        else if (typeof y === 'number') r = 1;
        else r = x < y ? -1 : x > y ? 1 : 0;
        return ascending ? r : -r;
      });
      rows.forEach(function (r) { body.appendChild(r); });
    }
    th.addEventListener('click', sort);
    th.addEventListener('keydown', function (e) { if (e.key === 'Enter') sort(); });
  });
});
)js";

std::string page(const std::string& title, const std::string& nav, const std::string& body, const std::string& generator) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n"
      "<link rel=\"icon\" href=\"data:,\">\n<style>{}</style>\n</head>\n<body>\n<header class=\"top\">{}</header>\n<main>\n{}"
      "<footer>Generated by {}. Every number is the chain's own result; report.json beside index.html holds them all.</footer>\n"
      "</main>\n<script>{}</script>\n</body>\n</html>\n",
      esc(title), style, nav, body, esc(generator), sort_script);
}

// A number cell: the value shown to 6 significant digits (as `radchain run` prints), its place in report.json, and
// the full value to sort by.
std::string number_text(const Json& v, const char* format = "{:.6g}") {
  if (!v.is_number()) return "";
  return fmt::format(fmt::runtime(format), v.get<double>());
}

std::string num_cell(const Json& v, const std::string& pointer, const char* format = "{:.6g}") {
  if (!v.is_number()) return "<td class=\"num\"></td>";
  return fmt::format("<td class=\"num\" data-json=\"{}\" data-sort=\"{}\">{}</td>", esc(pointer), v.get<double>(), number_text(v, format));
}

std::string num_span(const Json& v, const std::string& pointer, const char* format = "{:.6g}") {
  if (!v.is_number()) return "<span class=\"muted\">—</span>";
  return fmt::format("<span class=\"num\" data-json=\"{}\">{}</span>", esc(pointer), number_text(v, format));
}

std::string status_cell(const std::string& status) {
  return fmt::format("<td class=\"status {0}\" data-sort=\"{0}\">{0}</td>", esc(status));
}

std::string text_cell(const std::string& text, const std::string& cls = "text") {
  return fmt::format("<td class=\"{}\">{}</td>", cls, esc(text));
}

std::string head(std::initializer_list<std::pair<const char*, bool>> columns) {
  std::string h = "<thead><tr>";
  for (const auto& [name, numeric] : columns) h += fmt::format("<th{}>{}</th>", numeric ? " class=\"num\"" : "", name);
  return h + "</tr></thead>\n";
}

std::string sensor_base(std::size_t index) { return fmt::format("/sensors/{}", index); }

// ---- the sensor page's sections ----------------------------------------------------------------------------------

std::string key_results_html(const Json& s, const std::string& base) {
  if (s["key_results"].empty()) return "";
  std::string out = "<div class=\"keys\">";
  for (const auto& k : s["key_results"]) {
    const std::size_t i = k["result"].get<std::size_t>();
    const Json& r = s["results"][i];
    out += fmt::format("<div class=\"key\"><div class=\"muted mono\">{}</div><div><span class=\"v\">{}</span> {}</div>"
                       "<div class=\"muted\">{}</div></div>",
                       esc(r["name"]), num_span(r["value"], fmt::format("{}/results/{}/value", base, i)), esc(r["unit"]),
                       esc(r["equation"]));
  }
  return out + "</div>\n";
}

std::string checks_html(const Json& s, const std::string& base) {
  std::string out = "<h2 id=\"checks\">Checks</h2>\n";
  if (s["checks"].empty())
    return out + "<p class=\"muted\">No [expected] reference, no [[solve]] and no criterion to check.</p>\n";
  out += "<p class=\"muted\">[expected] references (kind: published = the instrument's figure, peer = another tool from the "
         "same inputs, paper = a paper's worked example, internal = radchain against itself), failed solves and failed "
         "criteria. Tolerance and Δ are in the reference's unit.</p>\n";
  out += "<div class=\"scroll\"><table class=\"sortable\" id=\"checks-table\">" +
         head({{"Result", false}, {"Kind", false}, {"Computed", true}, {"Reference", true}, {"Tolerance", true}, {"Unit", false},
               {"Δ", true}, {"Δ %", true}, {"Status", false}, {"Source and notes", false}}) +
         "<tbody>\n";
  for (std::size_t i = 0; i < s["checks"].size(); ++i) {
    const Json& c = s["checks"][i];
    const std::string p = fmt::format("{}/checks/{}/", base, i);
    std::string note = c["note"].get<std::string>();
    if (c.contains("line") && c["line"].get<int>() > 0) note += fmt::format(" (line {})", c["line"].get<int>());
    out += "<tr>" + text_cell(c["result"].get<std::string>(), "name mono") + text_cell(c["kind"].get<std::string>(), "name") +
           num_cell(c["computed"], p + "computed") + num_cell(c["reference"], p + "reference") +
           num_cell(c["tolerance"], p + "tolerance") + text_cell(c["unit"].get<std::string>(), "name") +
           num_cell(c["delta"], p + "delta", "{:+.4g}") + num_cell(c["delta_pct"], p + "delta_pct", "{:+.3g}") +
           status_cell(c["status"].get<std::string>()) + text_cell(note) + "</tr>\n";
  }
  return out + "</tbody></table></div>\n";
}

std::string solves_html(const Json& s, const std::string& base) {
  if (s["solves"].empty()) return "";
  std::string out = "<h2 id=\"solves\">Solves</h2>\n<p class=\"muted\">Each [[solve]] drives its criteria's margins to zero; "
                    "with several criteria the value at which every margin holds is kept, and that criterion binds.</p>\n";
  out += "<div class=\"scroll\"><table id=\"solves-table\">" +
         head({{"Unknown", false}, {"Criteria", false}, {"Value", true}, {"Unit", false}, {"Binds", false},
               {"Each criterion's own root", false}, {"Method", false}, {"Evaluations", true}, {"Status", false}}) +
         "<tbody>\n";
  for (std::size_t i = 0; i < s["solves"].size(); ++i) {
    const Json& v = s["solves"][i];
    const std::string p = fmt::format("{}/solves/{}/", base, i);
    std::string roots;
    for (std::size_t r = 0; r < v["roots"].size(); ++r)
      roots += fmt::format("{}{}: {}", r ? "<br>" : "", esc(v["roots"][r]["criterion"]),
                           num_span(v["roots"][r]["value"], fmt::format("{}roots/{}/value", p, r)));
    std::string criteria;
    for (const auto& c : v["criteria"]) criteria += (criteria.empty() ? "" : ", ") + c.get<std::string>();
    std::string method = v["method"].get<std::string>();
    if (!v["fallback"].get<std::string>().empty()) method += " (not in closed form: " + v["fallback"].get<std::string>() + ")";
    const bool ok = v["converged"].get<bool>();
    out += "<tr>" + text_cell(v["unknown"].get<std::string>(), "name mono") + text_cell(criteria) + num_cell(v["value"], p + "value") +
           text_cell(v["unit"].get<std::string>(), "name") + text_cell(v["binding"].get<std::string>(), "name") +
           "<td class=\"text\">" + roots + "</td>" + text_cell(ok ? method : "FAILED: " + v["message"].get<std::string>()) +
           fmt::format("<td class=\"num\">{}</td>", v["iterations"].get<int>()) + status_cell(ok ? "ok" : "FAIL") + "</tr>\n";
  }
  return out + "</tbody></table></div>\n";
}

std::string criteria_html(const Json& s, const std::string& base) {
  if (s["criteria"].empty()) return "";
  std::string out = "<h2 id=\"criteria\">Criteria</h2>\n<p class=\"muted\">Margin = achieved / required − 1: ≥ 0 holds. An "
                    "informational criterion is reported and does not fail the run.</p>\n";
  out += "<table id=\"criteria-table\">" + head({{"Criterion", false}, {"Margin", true}, {"Status", false}, {"Why it fails", false}}) +
         "<tbody>\n";
  for (std::size_t i = 0; i < s["criteria"].size(); ++i) {
    const Json& c = s["criteria"][i];
    out += "<tr>" + text_cell(c["section"].get<std::string>(), "name mono") +
           num_cell(c["margin"], fmt::format("{}/criteria/{}/margin", base, i), "{:+.4g}") +
           status_cell(c["status"].get<std::string>()) +
           text_cell(c["reason"].get<std::string>() + (c["informational"].get<bool>() ? " (informational)" : "")) + "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string warnings_html(const Json& s) {
  std::string out = "<h2 id=\"warnings\">Warnings</h2>\n";
  if (s["warnings"].empty()) return out + "<p class=\"muted\">None: no result is physically suspect.</p>\n";
  out += "<ul class=\"warnings\">";
  for (const auto& w : s["warnings"]) out += "<li>" + esc(w) + "</li>";
  return out + "</ul>\n";
}

std::string figures_html(const SensorModel& model) {
  std::string out = "<h2 id=\"plots\">Plots</h2>\n";
  if (model.figures.empty())
    return out + "<p class=\"muted\">Nothing to plot: this chain computes no SNR, solves no magnitude, has no MTF budget "
                 "and no result to differentiate.</p>\n";
  for (const auto& f : model.figures)
    out += fmt::format("<figure class=\"figure-{}\">\n<h3>{}</h3>\n{}<figcaption>{}</figcaption>\n</figure>\n", esc(f.key),
                       esc(f.title), f.svg, esc(f.caption));
  return out;
}

std::string chain_html(const Json& s) {
  std::string out = "<h2 id=\"chain\">Chain</h2>\n<p class=\"muted\">The plugins in the order they act; each publishes "
                    "results that the later ones read.</p>\n<ol class=\"chain\">";
  for (const auto& st : s["chain"])
    out += fmt::format("<li><code>[{}]</code> <b>{}</b>{} — {} <span class=\"muted\">({})</span></li>", esc(st["section"]),
                       esc(st["plugin"]), st["informational"].get<bool>() ? " <i>(informational)</i>" : "", esc(st["summary"]),
                       esc(st["reference"]));
  return out + "</ol>\n";
}

std::string inputs_html(const Json& s, const std::string& base) {
  std::string out = "<h2 id=\"inputs\">Inputs</h2>\n<p class=\"muted\">Every value the chain uses: as the file writes it "
                    "(<span class=\"default\">italic: the plugin's default</span>), its unit, where it comes from, and the "
                    "value in use in SI (a solved unknown's is its root).</p>\n";
  out += "<div class=\"scroll\"><table class=\"sortable\" id=\"inputs-table\">" +
         head({{"Input", false}, {"As written", false}, {"Unit (SI)", false}, {"In use (SI)", true}, {"From", false}, {"Meaning", false}}) +
         "<tbody>\n";
  for (std::size_t i = 0; i < s["inputs"].size(); ++i) {
    const Json& in = s["inputs"][i];
    const bool by_default = in["default"].get<bool>();
    std::string value_cell = "<td class=\"num\"></td>";
    const Json& v = in["value_si"];
    if (v.is_number()) value_cell = num_cell(v, fmt::format("{}/inputs/{}/value_si", base, i));
    else if (v.is_boolean()) value_cell = fmt::format("<td class=\"num\">{}</td>", v.get<bool>() ? "true" : "false");
    else if (v.is_array()) {
      std::string list;
      for (std::size_t k = 0; k < v.size(); ++k)
        list += (k ? ", " : "") + num_span(v[k], fmt::format("{}/inputs/{}/value_si/{}", base, i, k));
      value_cell = "<td class=\"num\">" + list + "</td>";
    }
    out += fmt::format("<tr{}>", by_default ? " class=\"default\"" : "") +
           text_cell(in["section"].get<std::string>() + "." + in["key"].get<std::string>(), "name mono") +
           text_cell(in["written"].get<std::string>(), "text mono") + text_cell(in["unit"].get<std::string>(), "name") + value_cell +
           text_cell(in["provenance"].get<std::string>()) + text_cell(in["doc"].get<std::string>()) + "</tr>\n";
  }
  return out + "</tbody></table></div>\n";
}

std::string results_html(const Json& s, const std::string& base) {
  std::string out = "<h2 id=\"results\">Results</h2>\n<p class=\"muted\">Every result of the chain in the order the stages "
                    "declare them, in its display unit, with the stage and the equation that produced it.</p>\n";
  out += "<div class=\"scroll\"><table class=\"sortable\" id=\"results-table\">" +
         head({{"Result", false}, {"Value", true}, {"Unit", false}, {"Stage", false}, {"Equation", false}}) + "<tbody>\n";
  for (std::size_t i = 0; i < s["results"].size(); ++i) {
    const Json& r = s["results"][i];
    out += fmt::format("<tr id=\"r-{}\">", esc(r["name"])) + text_cell(r["name"].get<std::string>(), "name mono") +
           num_cell(r["value"], fmt::format("{}/results/{}/value", base, i)) + text_cell(r["unit"].get<std::string>(), "name") +
           text_cell(r["stage"].get<std::string>(), "name") + text_cell(r["equation"].get<std::string>()) + "</tr>\n";
  }
  return out + "</tbody></table></div>\n";
}

std::string tables_html(const Json& s, const std::string& base) {
  if (s["tables"].empty()) return "";
  std::string out = "<h2 id=\"tables\">Tables</h2>\n<p class=\"muted\">The file's [[table]] entries: its solves again at each "
                    "value of one input.</p>\n";
  for (std::size_t t = 0; t < s["tables"].size(); ++t) {
    const Json& tab = s["tables"][t];
    out += fmt::format("<h3>{}</h3>\n<div class=\"scroll\"><table class=\"sortable\"><thead><tr><th>{}</th>", esc(tab["name"]), esc(tab["vary"]));
    for (const auto& c : tab["columns"])
      out += fmt::format("<th class=\"num\">{}{}</th>", esc(c["name"]), c["unit"].get<std::string>().empty() ? "" : " (" + esc(c["unit"]) + ")");
    out += "<th>Note</th></tr></thead><tbody>\n";
    for (std::size_t r = 0; r < tab["rows"].size(); ++r) {
      out += fmt::format("<tr><td class=\"name\" data-sort=\"{}\">{}</td>", tab["values_si"][r].get<double>(), esc(tab["values"][r]));
      for (std::size_t c = 0; c < tab["rows"][r].size(); ++c)
        out += num_cell(tab["rows"][r][c], fmt::format("{}/tables/{}/rows/{}/{}", base, t, r, c));
      out += text_cell(tab["notes"][r].get<std::string>()) + "</tr>\n";
    }
    out += "</tbody></table></div>\n";
  }
  return out;
}

std::string top_nav(const std::string& to_index, const std::string& here) {
  return fmt::format("<a href=\"{}\">radchain report</a> › {}", to_index, esc(here));
}

}  // namespace

std::string sensor_page(const Json& report, std::size_t index, const SensorModel& model) {
  const Json& s = report["sensors"][index];
  const std::string base = sensor_base(index);
  const std::string status = s["status"].get<std::string>();
  const std::string name = s["name"].get<std::string>().empty() ? s["stem"].get<std::string>() : s["name"].get<std::string>();
  std::string body = fmt::format("<h1>{} <span class=\"badge {}\" id=\"status\">{}</span></h1>\n<p class=\"muted mono\">{}</p>\n",
                                 esc(name), esc(status), esc(status), esc(s["file"]));
  if (status == "ERROR") {
    body += "<h2>Bad input</h2>\n<p>The file could not be evaluated:</p>\n<div class=\"error\" id=\"error\">" + esc(s["error"]) + "</div>\n";
    return page(name + " — radchain report", top_nav("../index.html", name), body, report["generator"].get<std::string>());
  }
  body += "<dl class=\"meta\">";
  for (const char* key : {"description", "reference", "notes"})
    if (!s[key].get<std::string>().empty())
      body += fmt::format("<dt>{}</dt><dd>{}</dd>", std::string(1, static_cast<char>(std::toupper(key[0]))) + (key + 1), esc(s[key]));
  body += "</dl>\n";
  body += key_results_html(s, base);
  body += "<nav class=\"toc\">";
  for (const auto& [id, title, shown] : std::initializer_list<std::tuple<const char*, const char*, bool>>{
           {"checks", "Checks", true}, {"solves", "Solves", !s["solves"].empty()}, {"criteria", "Criteria", !s["criteria"].empty()},
           {"warnings", "Warnings", true}, {"plots", "Plots", true}, {"chain", "Chain", true}, {"inputs", "Inputs", true},
           {"results", "Results", true}, {"tables", "Tables", !s["tables"].empty()}})
    if (shown) body += fmt::format("<a href=\"#{}\">{}</a>", id, title);
  body += "</nav>\n";
  body += checks_html(s, base) + solves_html(s, base) + criteria_html(s, base) + warnings_html(s) + figures_html(model) +
          chain_html(s) + inputs_html(s, base) + results_html(s, base) + tables_html(s, base);
  if (!s["uncertainty"].empty()) {
    body += "<h2 id=\"uncertainty\">Tolerances</h2>\n<p class=\"muted\">The file's [uncertainty] (sampled by `radchain "
            "uncertainty` and `radchain catalogue --uncertainty`).</p>\n<ul>";
    for (const auto& u : s["uncertainty"]) body += fmt::format("<li><code>{}</code> = {}</li>", esc(u["key"]), esc(u["distribution"]));
    body += "</ul>\n";
  }
  return page(name + " — radchain report", top_nav("../index.html", name), body, report["generator"].get<std::string>());
}

std::string index_page(const Json& report) {
  const int code = report["exit_code"].get<int>();
  const char* overall = code == 0 ? "ok" : code == 1 ? "FAIL" : "ERROR";
  std::string body = fmt::format("<h1>Instruments <span class=\"badge {0}\" id=\"status\">{0}</span></h1>\n<p id=\"summary\">{1}</p>\n",
                                 overall, esc(report["summary"]));
  std::string inputs;
  for (const auto& i : report["inputs"]) inputs += (inputs.empty() ? "" : ", ") + i.get<std::string>();
  body += fmt::format("<p class=\"muted\">{} sensor file{}{}. Click a column header to sort.</p>\n", report["sensors"].size(),
                      report["sensors"].size() == 1 ? "" : "s",
                      report["overrides"].empty() ? "" : "; every file with --set " + esc(report["overrides"].dump()));

  body += "<div class=\"scroll\"><table class=\"sortable\" id=\"instruments\">" +
          head({{"Instrument", false}, {"File", false}, {"Kinds of check", false}, {"Key results", false}, {"Checks ok", true},
                {"Warnings", true}, {"Status", false}}) +
          "<tbody>\n";
  for (std::size_t i = 0; i < report["sensors"].size(); ++i) {
    const Json& s = report["sensors"][i];
    const std::string base = sensor_base(i);
    const std::string status = s["status"].get<std::string>();
    const std::string name = s["name"].get<std::string>().empty() ? s["stem"].get<std::string>() : s["name"].get<std::string>();
    std::string kinds, keys;
    std::size_t ok = 0, total = 0, informational = 0;
    if (status != "ERROR") {
      // Checks are the rows that pass or fail; a failing informational criterion is counted apart.
      std::map<std::string, int> by_kind;
      for (const auto& c : s["checks"]) {
        if (c["status"] == "info") {
          ++informational;
          continue;
        }
        ++by_kind[c["kind"].get<std::string>()];
        ++total;
        ok += c["status"] == "ok";
      }
      for (const auto& [k, n] : by_kind) kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", k, n);
      if (informational) kinds += fmt::format("{}{} informational criterion{} not met", kinds.empty() ? "" : "; ", informational,
                                              informational == 1 ? "" : "s");
      for (const auto& k : s["key_results"]) {
        const std::size_t r = k["result"].get<std::size_t>();
        const Json& res = s["results"][r];
        keys += fmt::format("{}<span class=\"mono\">{}</span> = {} {}", keys.empty() ? "" : "<br>", breakable(res["name"].get<std::string>()),
                            num_span(res["value"], fmt::format("{}/results/{}/value", base, r)), esc(res["unit"]));
      }
    } else {
      keys = "<span class=\"status ERROR\">" + esc(s["error"]) + "</span>";
    }
    body += fmt::format("<tr><td class=\"text\"><a href=\"{}\">{}</a></td>", esc(s["page"]), esc(name)) +
            "<td class=\"breakable mono\">" + breakable(s["file"].get<std::string>()) + "</td>" + text_cell(kinds) +
            "<td class=\"breakable\">" + keys + "</td>" +
            (total ? fmt::format("<td class=\"num\" data-sort=\"{}\">{} / {}</td>", static_cast<double>(ok) / total, ok, total)
                   : std::string("<td class=\"num muted\" data-sort=\"2\">none</td>")) +
            fmt::format("<td class=\"num\">{}</td>", status == "ERROR" ? 0 : s["warnings"].size()) + status_cell(status) + "</tr>\n";
  }
  body += "</tbody></table></div>\n";

  body += "<h2 id=\"all-checks\">Checks</h2>\n<p class=\"muted\">Every [expected] reference, failed solve and failed criterion "
          "of every file, as <code>radchain catalogue</code> states them; tolerance and Δ in the reference's unit.</p>\n";
  body += "<div class=\"scroll\"><table class=\"sortable\" id=\"checks\">" +
          head({{"Instrument", false}, {"Result", false}, {"Kind", false}, {"Computed", true}, {"Reference", true},
                {"Tolerance", true}, {"Unit", false}, {"Δ %", true}, {"Status", false}, {"Source and notes", false}}) +
          "<tbody>\n";
  for (std::size_t i = 0; i < report["sensors"].size(); ++i) {
    const Json& s = report["sensors"][i];
    const std::string name = s["name"].get<std::string>().empty() ? s["stem"].get<std::string>() : s["name"].get<std::string>();
    const std::string link = fmt::format("<td class=\"text\"><a href=\"{}\">{}</a></td>", esc(s["page"]), esc(name));
    if (s["status"] == "ERROR") {
      body += "<tr>" + link + "<td></td><td></td><td class=\"num\"></td><td class=\"num\"></td><td class=\"num\"></td><td></td>"
              "<td class=\"num\"></td>" + status_cell("ERROR") + text_cell(s["error"].get<std::string>()) + "</tr>\n";
      continue;
    }
    for (std::size_t k = 0; k < s["checks"].size(); ++k) {
      const Json& c = s["checks"][k];
      const std::string p = fmt::format("/sensors/{}/checks/{}/", i, k);
      body += "<tr>" + link + text_cell(c["result"].get<std::string>(), "name mono") + text_cell(c["kind"].get<std::string>(), "name") +
              num_cell(c["computed"], p + "computed") + num_cell(c["reference"], p + "reference") +
              num_cell(c["tolerance"], p + "tolerance") + text_cell(c["unit"].get<std::string>(), "name") +
              num_cell(c["delta_pct"], p + "delta_pct", "{:+.3g}") + status_cell(c["status"].get<std::string>()) +
              text_cell(c["note"].get<std::string>()) + "</tr>\n";
    }
  }
  body += "</tbody></table></div>\n";
  return page("radchain report", "<a href=\"index.html\">radchain report</a>", body, report["generator"].get<std::string>());
}

}  // namespace radchain::html_detail
