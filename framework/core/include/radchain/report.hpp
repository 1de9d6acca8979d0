#pragma once
// Rendering a Report for people (aligned text) and for programs (JSON).
#include "radchain/chain.hpp"

#include <string>

namespace radchain {

// Every result (value in its display unit, unit, stage, equation), then solves and [expected] checks.
std::string format_report_text(const Report& report);
// The same content as JSON (SI values plus display values).
std::string format_report_json(const Report& report);
// One [[table]]: the varied values as written, a column per result in its display unit, notes of failed rows.
std::string format_table_text(const TableOutcome& table);
// "832.1 mm" style: value in the display unit with 4-6 significant digits.
std::string format_value(double value_si, const ResultInfo& info);

}  // namespace radchain
