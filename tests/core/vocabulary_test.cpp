// The vocabulary's terms and the one table of plugin kinds.
#include "radchain/plugin.hpp"
#include "radchain/vocabulary.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

namespace {
using namespace radchain;

TEST(Vocabulary, TermsNameTheirSectionAndKey) {
  static_assert(vocabulary::detector_snr.section() == "detector");
  static_assert(vocabulary::detector_snr.key() == "snr");
  static_assert(!vocabulary::detector_snr.per_criterion());
  static_assert(vocabulary::criterion_margin.per_criterion());
  EXPECT_EQ(vocabulary::criterion_margin.in_criterion("detection"), "criteria.detection.margin");
}

TEST(Vocabulary, ACriterionTermMatchesItsResultInAnyCriterion) {
  EXPECT_TRUE(vocabulary::criterion_margin.matches("criteria.energy.margin"));
  EXPECT_FALSE(vocabulary::criterion_margin.matches("criteria.energy.min_margin"));
  EXPECT_FALSE(vocabulary::criterion_margin.matches("criteria..margin"));
  EXPECT_FALSE(vocabulary::criterion_margin.matches("detector.margin"));
  EXPECT_TRUE(vocabulary::detector_snr.matches("detector.snr"));
  EXPECT_FALSE(vocabulary::detector_snr.matches("detector.snr_per_pixel"));
}

TEST(Vocabulary, EveryTermIsListedOnceWithAUnitAndAMeaning) {
  std::set<std::string_view> names;
  for (const Term& t : vocabulary::all) {
    EXPECT_TRUE(names.insert(t.name).second) << t.name << " twice";
    EXPECT_FALSE(t.unit.empty()) << t.name;
    EXPECT_FALSE(t.meaning.empty()) << t.name;
    EXPECT_TRUE(kind_of_section(t.section()) == Kind::criterion || to_string(kind_of_section(t.section())) == t.section())
        << t.name;
    EXPECT_EQ(vocabulary::term_of(t.per_criterion() ? t.in_criterion("x") : std::string(t.name)), &t);
  }
  EXPECT_EQ(vocabulary::term_of("detector.dark_noise"), nullptr);
}

TEST(Kinds, OneTableGivesNamesSectionsAndFolders) {
  EXPECT_EQ(to_string(Kind::criterion), "criterion");
  EXPECT_EQ(kind_directory(Kind::criterion), "criterion");
  EXPECT_EQ(kind_of_section("criteria.detection"), Kind::criterion);
  EXPECT_EQ(kind_of_section("optics"), Kind::optics);
  EXPECT_THROW(kind_of_section("sensor"), std::logic_error);
  EXPECT_EQ(kind_from_name("atmosphere"), Kind::atmosphere);
  EXPECT_FALSE(kind_from_name("atmospheres").has_value());
  for (const KindInfo& k : kinds) {
    EXPECT_EQ(kind_from_name(k.name), k.kind);
    EXPECT_EQ(kind_of_section(k.section), k.kind);
  }
}

TEST(Kinds, EveryPluginFolderIsAKindName) {
  // (radchain_add_plugin takes the kind from the folder: a folder that is no kind's name does not compile.)
  for (const auto& entry : std::filesystem::directory_iterator(RADCHAIN_SOURCE_DIR "/plugins"))
    if (entry.is_directory()) {
      EXPECT_TRUE(kind_from_name(entry.path().filename().string()).has_value()) << entry.path();
    }
}

}  // namespace
