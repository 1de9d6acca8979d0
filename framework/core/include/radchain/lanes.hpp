#pragma once
// Lanes: the scalar phase for `lane_count` points at once (a sweep evaluates eight apertures per pass). One point
// alone waits on each square root, exponential and division of its chain in turn; eight independent points fill
// the CPU's pipelines and Eigen's SIMD packets. This is what makes a million-point sweep cost milliseconds.
//
// A plugin writes its scalar phase once, as a template over an accessor, and derives from LaneStage (plugin.hpp),
// which runs it for one point (ScalarAccess) and for lane_count points (LaneContext):
//
//   class Telescope final : public LaneStage<Telescope> {
//     friend class LaneStage<Telescope>;
//     template <class Access> void compute(Access& a) {
//       using V = typename Access::Value;                     // double, or Lanes
//       const V d = a.param(aperture_);                       // a Params::handle(): per lane when swept
//       a.set(id_area_, std::numbers::pi / 4 * d * d);        // results: per lane
//       a.signal_scale() *= ...;                              // the light's scalars: per lane
//     }
//   };
//
// Use `using std::sqrt; sqrt(x)` (and exp, log1p, ...): argument-dependent lookup picks Eigen's array functions
// for Lanes. A plugin without evaluate_lanes() still works in lanes: the chain runs its scalar evaluate() once
// per lane.
#include "radchain/light.hpp"
#include "radchain/results.hpp"

#include <Eigen/Core>

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace radchain {

inline constexpr int lane_count = 8;
using Lanes = Eigen::Array<double, lane_count, 1>;

// A parameter that differs between lanes: its stable address (Params::handle()) and its values.
struct LaneParameter {
  const double* address;
  Lanes values;
};

// x in every lane. (Not Lanes::Constant(x): Eigen 3.4 assigns a constant with a scalar std::fill_n, which was a
// fifth of a sweep's time; a product takes its packet path.)
inline Lanes constant_lanes(double x) { return Lanes::Ones() * x; }

// x as a Value: a double, or x in every lane.
template <class V>
V broadcast(double x) {
  if constexpr (std::is_same_v<V, double>) return x;
  else return constant_lanes(x);
}

// The light's scalars, one per lane.
struct LaneScales {
  Lanes illumination = constant_lanes(1), signal = constant_lanes(1), background = constant_lanes(1),
        up_path = constant_lanes(1);
};

// 1 where the condition holds, else 0: a result such as "detected".
inline double indicator(bool condition) { return condition ? 1.0 : 0.0; }
template <class Derived>
Lanes indicator(const Eigen::ArrayBase<Derived>& condition) {
  return condition.template cast<double>();
}

// What a stage's scalar phase sees when it evaluates lane_count points (ScalarAccess, plugin.hpp: one point).
class LaneContext {
 public:
  using Value = Lanes;
  LaneContext(std::vector<Lanes>& results, const Light& light, LaneScales& scales,
              const std::vector<LaneParameter>& varying, bool full_detail)
      : results_(results), light_(light), scales_(scales), varying_(varying), full_detail_(full_detail) {}

  // The lane values of a swept parameter, else its one value in every lane.
  Lanes param(const double* handle) const {
    for (const LaneParameter& p : varying_)
      if (p.address == handle) return p.values;
    return constant_lanes(*handle);
  }
  // Whether a parameter differs between lanes (work on its value alone can then be done once).
  bool varies(const double* handle) const {
    for (const LaneParameter& p : varying_)
      if (p.address == handle) return true;
    return false;
  }
  const Lanes& value(ResultId id) const { return results_[id]; }
  void set(ResultId id, const Lanes& value) { results_[id] = value; }
  Lanes& illumination_scale() { return scales_.illumination; }
  Lanes& signal_scale() { return scales_.signal; }
  Lanes& background_scale() { return scales_.background; }
  Lanes& up_path_scale() { return scales_.up_path; }
  const Light& light() const { return light_; }
  bool full_detail() const { return full_detail_; }

 private:
  std::vector<Lanes>& results_;
  const Light& light_;
  LaneScales& scales_;
  const std::vector<LaneParameter>& varying_;
  bool full_detail_;
};

}  // namespace radchain
