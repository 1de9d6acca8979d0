// No atmosphere between object and sensor (space-to-space viewing): transmittance 1, no path radiance.
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {};
  return s;
}

class NoAtmosphere final : public Stage {
 public:
  void prepare(Context& c) override { id_ = c.declare("transmittance", "1", "vacuum: τ_A = 1"); }
  void evaluate(Context& c) override { c.results.set(id_, 1.0); }

 private:
  ResultId id_{};
};

const PluginInfo& info() {
  static const PluginInfo i{plugin_abi_version, framework_version, Kind::atmosphere, "none",
                            "no atmosphere (space-based viewing): τ = 1, no path radiance", "-", &schema,
                            [](const Params&) -> std::unique_ptr<Stage> { return std::make_unique<NoAtmosphere>(); }};
  return i;
}
}  // namespace

RADCHAIN_PLUGIN(info)
