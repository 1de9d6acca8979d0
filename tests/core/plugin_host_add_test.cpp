// PluginHost::add: a plugin defined in the process (how radchain.register_stage brings a Python stage in) is found
// by load() under its kind and name, its contract is checked like a library's, and a chain runs it. The stage here
// is the threshold form of snr_threshold (margin = SNR/T − 1, Pan 2010 eq. 10) without a closed-form inverse, so
// msx-sbv's limiting magnitude is bracketed instead of inverted: both must give the same root.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/sensor_file.hpp"
#include "radchain/vocabulary.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace {
using namespace radchain;

const Schema& added_schema() {
  static const Schema s = {number("threshold", "5").above(0).described("SNR threshold T")};
  return s;
}

class AddedThreshold final : public Stage {
 public:
  explicit AddedThreshold(const Params& p) : threshold_(p.handle("threshold")) {}
  void prepare(Context& c) override {
    snr_ = c.require(vocabulary::detector_snr);
    margin_ = c.declare(vocabulary::criterion_margin, "SNR/T − 1");
  }
  void evaluate(Context& c) override { c.results.set(margin_, c.results.value(snr_) / *threshold_ - 1.0); }

 private:
  const double* threshold_;
  ResultId snr_{}, margin_{};
};

const PluginInfo& added() {
  static const PluginInfo& info = PluginHost::instance().add(PluginInfo{
      plugin_abi_version, framework_version, Kind::criterion, "added_threshold", "SNR ≥ T (test)", "Pan 2010 eq. 10",
      &added_schema, [](const Params& p) -> std::unique_ptr<Stage> { return std::make_unique<AddedThreshold>(p); },
      {vocabulary::criterion_margin}, {vocabulary::detector_snr}, InverseForm::none});
  return info;
}

std::string sbv_text() {
  std::ifstream in(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(PluginHostAdd, LoadFindsTheAddedPluginUnderItsKindOnly) {
  const PluginInfo& info = added();
  EXPECT_EQ(&PluginHost::instance().load(Kind::criterion, "added_threshold"), &info);
  EXPECT_EQ(PluginHost::instance().loaded("added_threshold"), &info);
  EXPECT_THROW(PluginHost::instance().load(Kind::detector, "added_threshold"), InputError);
}

TEST(PluginHostAdd, AChainRunsItAndSolvesToTheLibraryStagesRoot) {
  added();
  const std::string path = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml";
  std::string text = sbv_text();
  const auto at = text.find("plugin = \"snr_threshold\"");
  ASSERT_NE(at, std::string::npos);
  Chain library = load_sensor_text(text, path);
  Chain in_process = load_sensor_text(text.replace(at, 24, "plugin = \"added_threshold\""), path);
  const Report a = library.run(), b = in_process.run();
  ASSERT_TRUE(b.all_passed());
  // snr_threshold inverts in closed form, the added stage is bracketed (TOMS 748): the same root to 1e-12.
  EXPECT_NEAR(*b.value("target.magnitude"), *a.value("target.magnitude"), 1e-12 * *a.value("target.magnitude"));
  EXPECT_NEAR(*b.value("criteria.detection.margin"), 0.0, 1e-12);
  // A file's value outside the schema's range is refused with the plugin named, as for a library.
  try {
    load_sensor_text(text, path, {Override{"criteria.detection.threshold", "-1"}});
    ADD_FAILURE() << "threshold = -1 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plugin \"added_threshold\""), std::string::npos) << e.what();
  }
}

}  // namespace
