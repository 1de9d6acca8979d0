#include "radchain/results.hpp"

#include "radchain/units.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace radchain {

ResultId Results::declare(const std::string& name, const std::string& si_unit, const std::string& stage,
                          const std::string& equation, const std::string& display_unit) {
  if (auto existing = find(name)) {
    if (infos_[*existing].si_unit != si_unit)
      throw std::logic_error("result \"" + name + "\" re-declared with another unit");
    infos_[*existing].equation = equation;
    return *existing;
  }
  ResultInfo info{name, si_unit, display_unit.empty() ? si_unit : display_unit, 1.0, stage, equation};
  if (info.display_unit != si_unit) info.display_factor = 1.0 / units::conversion(info.display_unit, si_unit).factor;
  index_.emplace(info.name, infos_.size());
  infos_.push_back(std::move(info));
  values_.push_back(std::numeric_limits<double>::quiet_NaN());
  return infos_.size() - 1;
}

std::optional<ResultId> Results::find(std::string_view name) const {
  if (auto it = index_.find(name); it != index_.end()) return it->second;
  return std::nullopt;
}

bool Results::is_set(ResultId id) const { return !std::isnan(values_[id]); }

void Results::clear_values() {
  for (auto& v : values_) v = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace radchain
