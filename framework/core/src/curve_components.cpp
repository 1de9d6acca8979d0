#include "radchain/curve_components.hpp"

#include "radchain/spectrum_csv.hpp"

#include <filesystem>
#include <fmt/format.h>

namespace radchain {

std::pair<double, double> passband_m(const Spectrum& curve, double fraction) {
  const double level = fraction * curve.peak_value();
  Eigen::Index first = -1, last = -1;
  for (Eigen::Index i = 0; i < curve.size(); ++i)
    if (curve.value()(i) >= level && level > 0) {
      if (first < 0) first = i;
      last = i;
    }
  if (first < 0 || last <= first) return {curve.min_wavelength_m(), curve.max_wavelength_m()};
  return {curve.wavelength_m()(first), curve.wavelength_m()(last)};
}

std::vector<ComponentMean> declare_component_means(Context& context, const Params& params, std::string_view key,
                                                   double lo_m, double hi_m) {
  std::vector<ComponentMean> out;
  if (!params.has(key)) return out;
  const Params::Entry& entry = params.entry(key);
  const std::string band = fmt::format("{:.1f}-{:.1f} nm", lo_m * 1e9, hi_m * 1e9);
  auto mean_of = [&](const Spectrum& s) { return s.integral(lo_m, hi_m) / (hi_m - lo_m); };
  const std::vector<std::string> files = entry.texts.empty() ? std::vector<std::string>{entry.text} : entry.texts;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const Spectrum& component = cached_spectrum_csv(files[k], entry.spec->si_unit).spectrum;
    const std::string name = fmt::format("{}_{}", key, k + 1);
    out.push_back({context.declare(name, entry.spec->si_unit,
                                   fmt::format("mean over {} of {}", band, std::filesystem::path(files[k]).filename().string())),
                   mean_of(component)});
  }
  if (files.size() > 1)
    out.push_back({context.declare(fmt::format("{}_product", key), entry.spec->si_unit,
                                   fmt::format("mean over {} of the product of the {} components", band, files.size())),
                   mean_of(params.spectrum(key))});
  return out;
}

}  // namespace radchain
