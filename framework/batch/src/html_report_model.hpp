#pragma once
// The HTML report's model (private to the batch library): per sensor file, the JSON object that report.json
// holds for it and the figures its page shows. html_report.cpp builds it from the chain, html_report_pages.cpp
// renders the pages from it, so a number on a page is the number in report.json by construction (and each one
// names its place there: data-json, a JSON pointer, which the browser test follows).
#include "radchain/batch/html_report.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace radchain::html_detail {

using Json = nlohmann::ordered_json;

struct Figure {
  std::string key;      // its entry under "plots" in the sensor's JSON
  std::string title;    // the heading above it
  std::string caption;  // what it shows and how it was computed (HTML-escaped when rendered)
  std::string svg;      // inline SVG ("" when only the caption is shown: nothing to draw, and why)
};

struct SensorModel {
  Json data;  // report.json's sensors[i]
  std::vector<Figure> figures;
  std::vector<std::vector<std::string>> catalogue_rows;  // as `radchain catalogue` (for its summary line)
  bool bad_input = false;
  std::string error;  // the located line when bad_input
};

SensorModel evaluate_sensor(const std::string& file, const std::string& page, const HtmlReportOptions& options);

// Pages. `report` is the whole report.json; `index` the sensor's place in report["sensors"].
std::string sensor_page(const Json& report, std::size_t index, const SensorModel& model);
std::string index_page(const Json& report);

}  // namespace radchain::html_detail
