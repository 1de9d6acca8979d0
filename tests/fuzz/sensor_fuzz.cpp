// Sensor files through everything `radchain run` does with them: parse (toml++ and the config conversion),
// validate (schemas, plugins' own rules, data files), evaluate, solve, check [expected], format the report.
// A located InputError is the expected answer to bad input; anything else is a finding (docs/fuzzing.md).
#include "fuzz_input.hpp"

#include "radchain/error.hpp"
#include "radchain/report.hpp"
#include "radchain/sensor_file.hpp"

namespace {
// Named as if it lay among the golden bad files, so that the data files they name beside them resolve (then
// RADCHAIN_DATA_PATH and spectra/, as for any sensor file). Nothing is written there.
const std::string sensor_path = RADCHAIN_SOURCE_DIR "/tests/config_errors/cases/fuzz-input.toml";
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radchain::fuzz::configure_host();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    radchain::Chain chain = radchain::load_sensor_text(std::string(radchain::fuzz::as_text(data, size)), sensor_path);
    const radchain::Report report = chain.run();
    (void)radchain::format_report_text(report);
    (void)radchain::format_report_json(report);
  } catch (const radchain::InputError&) {
  }
  return 0;
}
