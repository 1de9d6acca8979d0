// Golden messages for bad input (DESIGN.md §5). Each case is cases/<name>.toml, a copy of sensors/msx-sbv.toml
// with one thing wrong (its first line says what), and cases/<name>.expected, the one line the CLI must print
// on stderr. The CLI runs with cases/ as working directory so messages carry relative paths; the few absolute
// paths it prints (plugin libraries, the plugin search path) and the version are replaced by placeholders.
#include "radchain/plugin.hpp"
#include "radchain/version.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;

const fs::path cases_dir = fs::path(RADCHAIN_SOURCE_DIR) / "tests" / "config_errors" / "cases";

struct Case {
  const char* name;
  const char* before_run = "";  // CLI options before the subcommand
  const char* after_run = "";   // options after `run <file>`
};

constexpr const char* test_plugins = "--plugin-path '" RADCHAIN_BINARY_DIR "/test_plugins'";

const Case cases[] = {
    {"toml_syntax"},
    {"unknown_plugin"},
    {"plugin_of_another_kind"},
    {"unknown_key"},
    {"missing_required_key"},
    {"missing_plugin_key"},
    {"bare_number_for_length"},
    {"wrong_dimension"},
    {"unparsable_unit"},
    {"out_of_range"},
    {"string_for_number"},
    {"float_for_integer"},
    {"bad_choice"},
    {"plugin_consistency_rule"},
    {"missing_spectrum_file"},
    {"curve_list_missing_file"},
    {"csv_no_unit_header"},
    {"csv_value_without_unit"},
    {"csv_wrong_dimension"},
    {"csv_non_monotonic"},
    {"csv_non_numeric"},
    {"plugin_bad_abi", test_plugins},
    {"plugin_no_entry", test_plugins},
    {"missing_section"},
    {"no_light_section"},
    {"reflecting_target_without_source"},
    {"unknown_section"},
    {"solve_unknown_criterion"},
    {"table_vary_is_solved"},
    {"table_value_out_of_range"},
    {"table_unknown_result"},
    {"table_value_wrong_unit"},
    {"uncertainty_unknown_key"},
    {"uncertainty_negative_sd"},
    {"uncertainty_wrong_unit"},
    {"uncertainty_not_a_string"},
    {"lamp_too_cold"},
    {"solve_bracket_out_of_range"},
    {"solve_unknown_parameter"},
    {"expected_unknown_result"},
    {"expected_wrong_unit"},
    {"expected_unknown_key"},
    {"expected_bad_kind"},
    {"curve_list_disjoint"},
    {"expected_tolerance_inf"},
    {"expected_value_nan"},
    {"expected_negative_tolerance"},
    {"sensor_unknown_key"},
    {"solve_unknown_key"},
    {"solve_bracket_with_unit"},
    {"solve_bracket_one_value"},
    {"set_bad_key", "", "--set 'optics.apperture=\"20 cm\"'"},
    {"set_unknown_section", "", "--set 'optic.aperture=\"20 cm\"'"},
    {"look_past_horizon"},
    {"swath_past_horizon"},
    {"reflectance_above_one"},
    {"band_outside_sed"},
    {"band_outside_qe_curve"},
    {"sky_given_twice"},
    {"sky_band_outside_table"},
    {"sky_table_negative"},
    {"space_zodiacal_near_sun"},
    {"space_negative_stray_light"},
    {"space_negative_stray_light_table"},
    {"space_zodiacal_latitude_only"},
    {"reference_radiance_negative"},
    {"streak_negative_rate"},
    {"streak_unknown_tracking"},
    {"streak_window_photometry"},
    {"airmass_outside_lut"},
    {"airmass_without_view"},
    {"site_extinction_and_table"},
    {"site_table_airmass_without_table"},
    {"view_airmass_given_twice"},
    {"view_airmass_outside_lut"},
    {"sun_below_horizon"},
    {"dated_scene_without_day"},
    {"csv_negative_value"},
    {"csv_transmittance_above_one"},
    {"csv_hex_number"},
    {"band_past_transmittance_curve"},
    {"band_past_atmosphere_table"},
    {"criterion_informational_not_bool"},
    {"pixel_pitch_stated_twice"},
    {"tdi_stages_stated_twice"},
    {"giqe_wavelength_outside_band"},
    {"sun_zenith_on_target_with_airmass_lut"},
    {"solve_unknown_twice"},
};

// How a case reads in test names and ctest listings (instead of a byte dump).
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

struct Outcome {
  int exit_code = -1;
  std::string stderr_text;
};

// Runs `radchain <before> run <file> <after>` in cases/ and captures stderr.
Outcome run_cli(const std::string& before, const std::string& file, const std::string& after) {
  const fs::path capture =
      fs::temp_directory_path() / ("radchain_config_errors_" + std::to_string(::getpid()) + "_" + file + ".stderr");
  const std::string command = "cd '" + cases_dir.string() + "' && '" RADCHAIN_CLI "' " + before + " run '" + file + "' " +
                              after + " >/dev/null 2>'" + capture.string() + "'";
  const int status = std::system(command.c_str());
  Outcome out;
  if (WIFEXITED(status)) out.exit_code = WEXITSTATUS(status);
  std::ifstream in(capture);
  std::ostringstream text;
  text << in.rdbuf();
  out.stderr_text = text.str();
  std::error_code ec;
  fs::remove(capture, ec);
  return out;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size()) text.replace(at, from.size(), to);
}

// Machine-specific parts of a message -> placeholders.
std::string normalised(std::string text) {
  replace_all(text, RADCHAIN_BINARY_DIR, "<build>");
  replace_all(text, std::string("this radchain ") + radchain::framework_version,
              "this radchain <version>");
  replace_all(text, "has ABI " + std::to_string(radchain::plugin_abi_version), "has ABI <abi>");
  const std::string open = "(search path: ";
  if (const auto at = text.find(open); at != std::string::npos) {
    const auto close = text.find(')', at);
    if (close != std::string::npos) text.replace(at + open.size(), close - at - open.size(), "<search path>");
  }
  return text;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The plugins of one kind the CLI will find (the first folder of the search path), sorted: "telescope, ...".
std::string plugins_of_kind(const std::string& kind_directory, bool quoted) {
  const char* env = std::getenv("RADCHAIN_PLUGIN_PATH");
  const fs::path dir = env && *env ? fs::path(std::string(env).substr(0, std::string(env).find(':')))
                                   : fs::path(RADCHAIN_BINARY_DIR) / "plugins";
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir / kind_directory, ec))
    if (entry.path().extension() == ".so") names.insert(entry.path().stem().string());
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + (quoted ? "\"" + name + "\"" : name);
  return list.empty() ? "none" : list;
}

// Expected lines may name the plugins of a kind as <optics plugins> or <quoted optics plugins>, so that adding
// a plugin does not rewrite the golden files.
std::string with_plugin_lists(std::string expected) {
  for (const radchain::KindInfo& k : radchain::kinds) {  // a kind's folder is its name
    const std::string kind(k.name);
    replace_all(expected, "<quoted " + kind + " plugins>", plugins_of_kind(kind, true));
    replace_all(expected, "<" + kind + " plugins>", plugins_of_kind(kind, false));
  }
  return expected;
}

class ConfigError : public ::testing::TestWithParam<Case> {};

TEST_P(ConfigError, PrintsTheGoldenLineAndExitsWith2) {
  const Case& c = GetParam();
  const fs::path expected_file = cases_dir / (std::string(c.name) + ".expected");
  ASSERT_TRUE(fs::exists(cases_dir / (std::string(c.name) + ".toml"))) << c.name;
  ASSERT_TRUE(fs::exists(expected_file)) << expected_file;
  std::string expected = read_file(expected_file);
  ASSERT_FALSE(expected.empty());
  ASSERT_EQ(expected.back(), '\n') << expected_file << " must end with a newline";
  expected.pop_back();
  ASSERT_EQ(expected.find('\n'), std::string::npos) << expected_file << " must hold one line";

  const Outcome out = run_cli(c.before_run, std::string(c.name) + ".toml", c.after_run);
  EXPECT_EQ(out.exit_code, 2) << out.stderr_text;
  // Exactly one line on stderr.
  ASSERT_FALSE(out.stderr_text.empty());
  EXPECT_EQ(out.stderr_text.back(), '\n');
  EXPECT_EQ(out.stderr_text.find('\n'), out.stderr_text.size() - 1) << out.stderr_text;
  std::string line = out.stderr_text;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  EXPECT_EQ(normalised(line), with_plugin_lists(expected));
}

INSTANTIATE_TEST_SUITE_P(Cases, ConfigError, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(ConfigErrors, EveryCaseFileIsRun) {
  std::set<std::string> listed;
  for (const Case& c : cases) listed.insert(c.name);
  for (const auto& entry : fs::directory_iterator(cases_dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".toml" || ext == ".expected") {
      EXPECT_TRUE(listed.count(entry.path().stem().string())) << entry.path() << " is not in the case table";
    }
  }
}

TEST(ConfigErrors, TheSetCasesFileIsValid) {
  // set_bad_key.toml is an unchanged copy: the error comes from --set alone.
  const Outcome out = run_cli("", "set_bad_key.toml", "");
  EXPECT_EQ(out.exit_code, 0) << out.stderr_text;
  EXPECT_EQ(out.stderr_text, "");
}

TEST(ConfigErrors, UnknownPluginNamesTheSearchPath) {
  const Outcome out = run_cli("", "unknown_plugin.toml", "");
  const char* env = std::getenv("RADCHAIN_PLUGIN_PATH");
  const std::string first_dir = env && *env ? std::string(env).substr(0, std::string(env).find(':'))
                                            : std::string(RADCHAIN_BINARY_DIR) + "/plugins";
  EXPECT_NE(out.stderr_text.find("(search path: " + first_dir), std::string::npos) << out.stderr_text;
}

TEST(ConfigErrors, MissingSensorFile) {
  const Outcome out = run_cli("", "no_such_sensor.toml", "");
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_EQ(out.stderr_text, "no_such_sensor.toml: sensor file: cannot be read (missing file or no permission)\n");
}

}  // namespace
