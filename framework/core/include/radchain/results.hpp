#pragma once
// The blackboard every stage writes its named results to: value (SI), unit, the stage that produced it and
// the equation it came from. Declared once per spectral configuration, then written by index, so that a
// solve or a sweep costs array stores, not string lookups.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace radchain {

using ResultId = std::size_t;

struct ResultInfo {
  std::string name;          // "detector.signal_electrons"
  std::string si_unit;       // "1", "m", "W m-2", "e-"
  std::string display_unit;  // what the report prints: "mm", "km", "deg"
  double display_factor = 1; // value_display = value_si * display_factor
  std::string stage;         // plugin name
  std::string equation;      // "Pan 2010 eq. (8)"
};

class Results {
 public:
  // Declares `name` (already qualified by the section) or returns the existing id (re-declaring with another
  // unit is a programming error: std::logic_error). display_unit defaults to si_unit.
  ResultId declare(const std::string& name, const std::string& si_unit, const std::string& stage,
                   const std::string& equation, const std::string& display_unit = {});
  void set(ResultId id, double value_si) { values_[id] = value_si; }
  double value(ResultId id) const { return values_[id]; }
  std::optional<ResultId> find(std::string_view name) const;
  const ResultInfo& info(ResultId id) const { return infos_[id]; }
  std::size_t size() const { return infos_.size(); }
  bool is_set(ResultId id) const;  // false while NaN (not evaluated)
  const std::vector<double>& values() const { return values_; }
  void restore(const std::vector<double>& values) { values_ = values; }  // (same size: saved by values())
  void clear_values();             // all NaN

 private:
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  std::vector<ResultInfo> infos_;
  std::vector<double> values_;
  std::unordered_map<std::string, ResultId, Hash, std::equal_to<>> index_;  // name → id
};

}  // namespace radchain
