// The render and validate option schemas (radchain/command_options.hpp) and their validation as a sensor section.
#include "radchain/command_options.hpp"

#include "radchain/config.hpp"

#include <algorithm>

namespace radchain {
namespace {

// Where a point image falls on the detector, for point-target sensors that do not say (render and validate).
Schema frame_geometry() {
  return {
      quantity("--focal-length", "m", "45 cm").above(0).described("focal length, when the sensor has none"),
      quantity("--pixel-pitch", "m", "27 um").above(0).described("pixel pitch, when the sensor has none"),
      choice("--psf", {"pixel", "airy", "gaussian"}).described("point-spread function of a point image (default: the sensor's)"),
      quantity("--psf-wavelength", "m", "0.6 um").above(0).described("wavelength of the Airy PSF"),
      quantity("--psf-fwhm", "m", "20 um").above(0).described("FWHM of the Gaussian PSF in the focal plane"),
  };
}

// Frames and scenes are at most 16384 pixels a side (1 GiB of float pixels): larger requests are refused, not
// attempted until memory runs out.
constexpr double max_side_px = 16384;

}  // namespace

const Schema& render_option_schema() {
  static const Schema schema = [] {
    Schema s = {
        choice("--fits-type", {"auto", "float", "int16", "int32"}).fallback("auto")
            .described("FITS pixel type (auto: integers when the ADC is on)"),
        choice("--no-noise", {"shot", "dark", "read", "saturation", "adc", "all"}).as_list()
            .described("noise terms switched off (comma-separated)"),
        integer("--width", "640").fallback("512").at_least(1).at_most(max_side_px).described("frame width (pixels)"),
        integer("--height", "480").fallback("512").at_least(1).at_most(max_side_px).described("frame height (pixels)"),
        integer("--stars", "200").fallback("0").at_least(0).at_most(1e6).described("synthetic field stars"),
        text("--star-magnitudes", "8:17").described("bright:faint magnitudes of the field stars (default 8:limit+1)"),
        number("--star-slope", "0.4").fallback("0.4").described("d log10 N / dm of the star counts"),
    };
    for (ParamSpec& p : frame_geometry()) s.push_back(std::move(p));
    for (ParamSpec p : {
             number("--obscuration", "0.3").at_least(0).below(1).described("central obscuration (linear ratio) of the Airy PSF"),
             quantity("--sky", "electron", "40 e-").at_least(0).described("sky background per pixel and frame"),
             integer("--oversampling", "8").fallback("8").at_least(1).at_most(64).described("PSF phases per pixel"),
             number("--offset", "100").fallback("0").at_least(0).described("ADC pedestal (DN)"),
             quantity("--scene-sampling", "m", "1.25 m").above(0).described("ground size of one pixel of the scene map"),
             quantity("--gsd", "m", "5 m").above(0).described("output ground sampling (default: the design's ground element)"),
             choice("--optics-mtf", {"auto", "budget", "diffraction", "eq7", "none"}).fallback("auto")
                 .described("optics MTF of an Earth scene (auto: the chain's MTF budget if it has one, else diffraction)"),
             quantity("--wavelength", "m", "0.76 um").above(0).described("MTF wavelength (default: the mtf_match criterion's)"),
             flag("--no-detector-mtf").fallback("false").described("leave out the element MTF (Kolobrodov eq. 8)"),
             integer("--adc-bits", "12").at_least(1).at_most(32)
                 .described("ADC of an Earth scene (default: the detector's detector.adc_bits, else 12; ccd_line has none)"),
             choice("--stretch", {"asinh", "linear"}).described("preview stretch (default: asinh for frames, linear for scenes)"),
             integer("--upscale", "4").fallback("1").at_least(1).at_most(16).described("preview upscale (nearest neighbour)"),
         })
      s.push_back(std::move(p));
    return s;
  }();
  return schema;
}

const Schema& validate_option_schema() {
  static const Schema schema = [] {
    Schema s = {
        integer("--trials", "20000").fallback("20000").at_least(100).at_most(1e8).described("detection Monte-Carlo frames"),
        integer("--size", "512").fallback("512").at_least(64).at_most(max_side_px).described("flat-field size (pixels)"),
        number("--threshold", "2.33").fallback("2.3263478740408408").above(0)
            .described("detector threshold in noise units (default z(0.99): P_fa = 1 %)"),
        number("--max-z", "4").fallback("4").above(0).described("binomial standard errors allowed"),
        number("--offset", "100").fallback("0").at_least(0)
            .described("ADC pedestal (DN) of the rendered frames: keeps the noise of a faint frame off 0 DN"),
    };
    for (ParamSpec& p : frame_geometry()) s.push_back(std::move(p));
    return s;
  }();
  return schema;
}

Params validated_options(const Schema& schema, const OptionValues& values, const std::string& command) {
  ConfigValue table;
  table.type = ConfigValue::Type::table;
  for (const auto& [key, text] : values.given) {
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& p : schema)
      if (p.key == key) spec = &p;
    if (spec && spec->shape == ParamShape::list) {
      // --no-noise shot,dark (and repeated options) collect into one list
      ConfigValue* list = table.find(key);
      if (!list) {
        table.members.emplace_back(key, ConfigValue{});
        list = &table.members.back().second;
        list->type = ConfigValue::Type::array;
      }
      std::size_t start = 0;
      while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        list->items.push_back(parse_toml_value(text.substr(start, comma - start), command));
        start = comma + 1;
      }
      continue;
    }
    const ConfigValue value = parse_toml_value(text, command);
    if (ConfigValue* earlier = table.find(key)) *earlier = value;  // the last one given wins, as CLI11 would
    else table.members.emplace_back(key, value);
  }
  table.where = SourceLocation{command, 0, 0};
  return validate_section(schema, table, ValidationContext{});
}

}  // namespace radchain
