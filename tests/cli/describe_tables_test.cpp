// `radchain describe sensor|solve|expected`: the sensor file's own tables come from the same Schemas that
// validate them (radchain/sensor_file.hpp), so describe lists exactly the keys the loader accepts.
#include "cli_helpers.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

namespace {
using namespace radchain::test;

TEST(DescribeTables, EachTableListsTheKeysItsSchemaAccepts) {
  Scratch scratch;
  const std::pair<const char*, radchain::Schema> tables[] = {{"sensor", radchain::sensor_table_schema()},
                                                             {"solve", radchain::solve_entry_schema()},
                                                             {"expected", radchain::expected_entry_schema()},
                                                             {"table", radchain::table_entry_schema()}};
  for (const auto& [name, schema] : tables) {
    const CliResult r = run_cli(scratch, std::string("describe ") + name);
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    for (const auto& spec : schema) EXPECT_NE(r.out.find("  " + spec.key + " "), std::string::npos) << name << " lacks " << spec.key;
  }
}

TEST(DescribeTables, AnUnknownNameSuggestsTheNearestTable) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "describe sensr");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("did you mean \"sensor\""), std::string::npos) << r.err;
}

}  // namespace
