// The one error type (error.hpp) and schema validation (schema.hpp) in-process: how a message is assembled,
// the nearest-match rule, and each ParamType's acceptance rules on TOML text.
#include "radchain/config.hpp"
#include "radchain/error.hpp"
#include "radchain/schema.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {
using namespace radchain;

TEST(InputError, RendersOneLine) {
  const InputError e(SourceLocation{"sensors/sbv.toml", 14, 15}, "optics (plugin \"telescope\")", "aperture = \"15 kg\"",
                     "expected a length, e.g. \"15 cm\"");
  EXPECT_STREQ(e.what(),
               "sensors/sbv.toml:14:15: optics (plugin \"telescope\"): aperture = \"15 kg\": expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(e.where().line, 14);
  EXPECT_EQ(e.problem(), "expected a length, e.g. \"15 cm\"");
  // Empty parts are left out.
  EXPECT_STREQ(InputError({}, "", "", "just this").what(), "just this");
  EXPECT_STREQ(InputError(SourceLocation{"f.csv", 3, 0}, "spectrum file", "", "bad").what(), "f.csv:3: spectrum file: bad");
  EXPECT_STREQ(InputError(SourceLocation{"f.csv", 0, 0}, "", "x", "bad").what(), "f.csv: x: bad");
  EXPECT_STREQ(e.with_context("detector").what(),
               "sensors/sbv.toml:14:15: detector: aperture = \"15 kg\": expected a length, e.g. \"15 cm\"");
  EXPECT_STREQ(e.with_location(SourceLocation{"other.toml", 1, 1}).what(),
               "other.toml:1:1: optics (plugin \"telescope\"): aperture = \"15 kg\": expected a length, e.g. \"15 cm\"");
}

TEST(InputError, SourceLocationText) {
  EXPECT_EQ((SourceLocation{"a.toml", 2, 7}).str(), "a.toml:2:7");
  EXPECT_EQ((SourceLocation{"a.toml", 2, 0}).str(), "a.toml:2");
  EXPECT_EQ((SourceLocation{"a.toml", 0, 0}).str(), "a.toml");
  EXPECT_EQ((SourceLocation{"", 2, 7}).str(), "");
}

TEST(InputError, NearestMatch) {
  const std::vector<std::string> keys = {"aperture", "obscuration", "transmittance", "focal_length"};
  EXPECT_EQ(nearest_match("apperture", keys), "aperture");
  EXPECT_EQ(nearest_match("aperure", keys), "aperture");
  EXPECT_EQ(nearest_match("focal_lenght", keys), "focal_length");
  EXPECT_EQ(nearest_match("transmitance", keys), "transmittance");
  EXPECT_EQ(nearest_match("zzz", keys), "");
  EXPECT_EQ(nearest_match("anything", {}), "");
  EXPECT_EQ(join({"a", "b", "c"}), "a, b, c");
  EXPECT_EQ(join({}), "");
}

TEST(Schema, RangeAndExpectedTexts) {
  EXPECT_EQ(quantity("aperture", "m", "15 cm").above(0).at_most(100).range_text(), "in (0, 100] m");
  EXPECT_EQ(number("qe", "0.27").at_least(0).below(1).range_text(), "in [0, 1)");
  EXPECT_EQ(number("x", "1").above(0).range_text(), "> 0");
  EXPECT_EQ(quantity("t", "s", "1 s").at_least(0).range_text(), ">= 0 s");
  EXPECT_EQ(number("x", "1").range_text(), "");
  EXPECT_EQ(choice("quantisation", {"emva", "paper"}).range_text(), "one of emva, paper");
  EXPECT_EQ(quantity("aperture", "m", "15 cm").expected_text(), "expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(number("qe", "0.27").expected_text(), "expected a number, e.g. 0.27");
  EXPECT_EQ(integer("adc_bits", "12").expected_text(), "expected an integer, e.g. 12");
  EXPECT_EQ(flag("x").expected_text(), "expected true or false");
  EXPECT_EQ(spectrum_file("qe_curve", "1", "qe.csv").expected_text(),
            "expected the name of a spectrum CSV file, e.g. \"qe.csv\"");
  const ParamSpec open_above = number("x", "1").above(0);
  EXPECT_FALSE(open_above.in_range(0.0));
  EXPECT_TRUE(open_above.in_range(1e-300));
  EXPECT_FALSE(open_above.in_range(NAN));
}

const Schema& test_schema() {
  static const Schema s = {
      quantity("aperture", "m", "15 cm").needed().above(0).described("entrance pupil diameter D"),
      number("transmittance", "0.56").fallback("1").above(0).at_most(1),
      integer("adc_bits", "12").fallback("12").at_least(1).at_most(32),
      choice("mode", {"emva", "paper"}).fallback("emva"),
      flag("verbose"),
      text("label", "x"),
      quantity("dark_rate", "electron/s", "18 e-/s").fallback("0 e-/s").at_least(0),
  };
  return s;
}

Params validate(const std::string& toml) {
  const ConfigValue root = parse_toml_text(toml, "test.toml");
  return validate_section(test_schema(), *root.find("optics"), ValidationContext{"test.toml", "optics", "scope"});
}

std::string error_of(const std::string& toml) {
  try {
    validate(toml);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(Schema, ValidatesAndConvertsToSi) {
  const Params p = validate("[optics]\nplugin = \"scope\"\naperture = \"15 cm\"\ndark_rate = \"18 e-/s\"\nmode = \"paper\"\n");
  EXPECT_NEAR(p.get("aperture"), 0.15, 1e-16);
  EXPECT_TRUE(p.given("aperture"));
  EXPECT_EQ(p.get("transmittance"), 1.0);  // default
  EXPECT_FALSE(p.given("transmittance"));
  EXPECT_TRUE(p.has("transmittance"));
  EXPECT_EQ(p.integer("adc_bits"), 12);
  EXPECT_EQ(p.text("mode"), "paper");
  EXPECT_FALSE(p.has("verbose"));  // optional, no default
  EXPECT_EQ(p.get("dark_rate"), 18.0);
  EXPECT_EQ(p.context(), "optics (plugin \"scope\")");
  EXPECT_EQ(p.entry("aperture").where.line, 3);
  EXPECT_EQ(*p.handle("aperture"), p.get("aperture"));
  EXPECT_THROW(p.get("no_such_key"), std::logic_error);
}

// Params finds a key by its size and first and last 8 bytes, and compares a key longer than 16 bytes whole: keys
// alike at both ends and of one size are told apart, and a key's prefix or suffix is no match.
TEST(Schema, KeysAlikeAtBothEndsAreToldApart) {
  static const Schema schema = {
      number("detector_band_min_edge", "1").fallback("1"), number("detector_band_max_edge", "2").fallback("2"),
      number("band_min", "3").fallback("3"), number("band_max", "4").fallback("4"), number("z", "5").fallback("5"),
  };
  const ConfigValue root = parse_toml_text("[detector]\nplugin = \"x\"\n", "t.toml");
  const Params p = validate_section(schema, *root.find("detector"), ValidationContext{"t.toml", "detector", "x"});
  EXPECT_EQ(p.get("detector_band_min_edge"), 1.0);
  EXPECT_EQ(p.get("detector_band_max_edge"), 2.0);
  EXPECT_EQ(p.get("band_min"), 3.0);
  EXPECT_EQ(p.get("band_max"), 4.0);
  EXPECT_EQ(p.get("z"), 5.0);
  EXPECT_THROW(p.get("detector_band_mid_edge"), std::logic_error);
  EXPECT_THROW(p.get("band_mi"), std::logic_error);
  EXPECT_THROW(p.get(""), std::logic_error);
}

TEST(Schema, ErrorMessages) {
  const std::string head = "[optics]\nplugin = \"scope\"\n";
  EXPECT_EQ(error_of(head + "aperture = \"15 kg\"\n"),
            "test.toml:3:1: optics (plugin \"scope\"): aperture = \"15 kg\": expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(error_of(head + "aperture = 15\n"),
            "test.toml:3:1: optics (plugin \"scope\"): aperture = 15: a bare number has no unit: expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(error_of(head + "aperture = \"15\"\n"),
            "test.toml:3:1: optics (plugin \"scope\"): aperture = \"15\": no unit: expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(error_of(head + "aperture = \"cm\"\n"),
            "test.toml:3:1: optics (plugin \"scope\"): aperture = \"cm\": does not start with a number: expected a length, e.g. \"15 cm\"");
  EXPECT_EQ(error_of(head + "aperture = \"-1 cm\"\n"),
            "test.toml:3:1: optics (plugin \"scope\"): aperture = \"-1 cm\": out of range: accepted > 0 m");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nadc_bits = 12.0\n"),
            "test.toml:4:1: optics (plugin \"scope\"): adc_bits = 12.0: expected an integer, e.g. 12");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nadc_bits = 64\n"),
            "test.toml:4:1: optics (plugin \"scope\"): adc_bits = 64: out of range: accepted in [1, 32]");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nmode = \"papr\"\n"),
            "test.toml:4:1: optics (plugin \"scope\"): mode = \"papr\": expected one of emva, paper (did you mean \"paper\"?)");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nmode = \"other\"\n"),
            "test.toml:4:1: optics (plugin \"scope\"): mode = \"other\": expected one of emva, paper");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nverbose = 1\n"),
            "test.toml:4:1: optics (plugin \"scope\"): verbose = 1: expected true or false");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\nlabel = 3\n"),
            "test.toml:4:1: optics (plugin \"scope\"): label = 3: expected a string, e.g. \"x\"");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\ndark_rate = \"18 e/s\"\n"),
            "test.toml:4:1: optics (plugin \"scope\"): dark_rate = \"18 e/s\": expected an electron rate, e.g. \"18 e-/s\"");
  EXPECT_EQ(error_of(head + "transmittance = 0.5\n"),
            "test.toml:1:2: optics (plugin \"scope\"): aperture: missing required key: expected a length, e.g. \"15 cm\" "
            "(entrance pupil diameter D)");
  EXPECT_EQ(error_of(head + "aperture = \"1 cm\"\ntransmitance = 0.5\n"),
            "test.toml:4:1: optics (plugin \"scope\"): transmitance: unknown key (did you mean \"transmittance\"?); accepted keys: "
            "aperture, transmittance, adc_bits, mode, verbose, label, dark_rate");
}

}  // namespace
