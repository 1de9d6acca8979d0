#pragma once
// The sensor file's own tables, validated by the same Schema machinery as a plugin's section, so that unknown
// and missing keys, units and ranges get the same located errors and `radchain describe` can show them:
//   [sensor]    name, description, reference, notes
//   [[solve]]   unknown, criterion (one name or a list), bracket (two values in the unknown's unit)
//   [expected]  "<result>" = { value, follows, tolerance, rel_tolerance, source } in the result's unit
//   [[table]]   name, vary, values (in the varied parameter's unit), results
#include "radchain/chain.hpp"
#include "radchain/schema.hpp"

#include <string>

namespace radchain {

// load_sensor() of a sensor file's text (Python's radchain.loads): `path` names it in messages and is where
// relative data files are looked for first (beside it). Throws InputError.
Chain load_sensor_text(const std::string& text, const std::string& path, const std::vector<Override>& overrides = {},
                       Solving solving = Solving::as_written);

const Schema& sensor_table_schema();
// A [[solve]] entry. The bracket's unit is the unknown's: `unknown` is that parameter's spec (nullptr: a plain
// number, as the schema `radchain describe solve` shows before any unknown is known).
Schema solve_entry_schema(const ParamSpec* unknown = nullptr);
// A [[table]] entry. The values' unit is the varied parameter's (`varied`; nullptr: plain numbers).
Schema table_entry_schema(const ParamSpec* varied = nullptr);
// An [expected] entry for a result whose SI unit is `si_unit` ("1": plain numbers).
Schema expected_entry_schema(const std::string& si_unit = "1");

}  // namespace radchain
