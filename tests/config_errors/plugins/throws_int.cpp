// A plugin whose scalar phase throws an int, not a std::exception: radchain must report it (exit 3), not abort.
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {};
  return s;
}

class ThrowsInt final : public Stage {
 public:
  void prepare(Context& c) override { id_ = c.declare("transmittance", "1", "never computed"); }
  void evaluate(Context&) override { throw 42; }

 private:
  ResultId id_{};
};

}  // namespace

RADCHAIN_PLUGIN(ThrowsInt, {
    .summary = "test plugin: throws an int from evaluate",
    .reference = "-",
    .schema = schema,
})
