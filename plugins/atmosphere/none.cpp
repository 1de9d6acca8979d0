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

}  // namespace

RADCHAIN_PLUGIN(NoAtmosphere, {
    .summary = "no atmosphere (space-based viewing): τ = 1, no path radiance",
    .reference = "-",
    .schema = schema,
})
