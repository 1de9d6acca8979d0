// The plugin contract (PluginInfo::publishes, needs): every bundled sensor and example runs with the contract
// enforced (Context::require/find/declare throw std::logic_error on a result a plugin did not list), the
// bundled plugins' lists fit together, and the checks themselves fire.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/vocabulary.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace {
using namespace radchain;
namespace fs = std::filesystem;

std::vector<std::string> sensor_files() {
  std::vector<std::string> files;
  for (const char* dir : {"/sensors", "/examples"})
    for (const auto& f : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + dir))
      if (f.path().extension() == ".toml") files.push_back(f.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<const PluginInfo*> bundled_plugins() {
  std::vector<const PluginInfo*> plugins;
  for (const auto& f : PluginHost::instance().discover()) plugins.push_back(&PluginHost::instance().load_file(f.path));
  return plugins;
}

bool is_vocabulary(const Term& term) {
  return std::find(vocabulary::all.begin(), vocabulary::all.end(), term) != vocabulary::all.end();
}

TEST(PluginContract, EverySensorAndExampleRunsWithinItsPluginsContracts) {
  const auto files = sensor_files();
  ASSERT_GE(files.size(), 6u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    try {
      Chain chain = load_sensor(file);
      const Report report = chain.run();
      EXPECT_FALSE(report.results.empty());
      // Each vocabulary result a stage declared is one its plugin lists in `publishes`.
      for (const auto& slot : chain.stages) {
        for (const StageMemo::Declared& d : slot.memo.declarations) {
          if (const Term* term = vocabulary::term_of(chain.results().info(d.id).name)) {
            EXPECT_TRUE(slot.info->publishes_term(*term)) << slot.plugin << " declares " << term->name;
            EXPECT_TRUE(d.term && *d.term == *term) << slot.plugin << " declares " << term->name << " as a plain name";
          }
        }
      }
    } catch (const std::logic_error& e) {
      ADD_FAILURE() << "contract broken: " << e.what();
    }
  }
}

TEST(PluginContract, BundledPluginsListOnlyVocabularyTermsOfTheRightSections) {
  const auto plugins = bundled_plugins();
  ASSERT_GE(plugins.size(), 16u);
  for (const PluginInfo* info : plugins) {
    SCOPED_TRACE(info->name);
    for (const Term& t : info->publishes) {
      EXPECT_TRUE(is_vocabulary(t)) << t.name;
      const bool own_section = info->kind == Kind::criterion ? t.per_criterion() : t.section() == to_string(info->kind);
      EXPECT_TRUE(own_section) << info->name << " publishes " << t.name << ", another section's result";
    }
    for (const Need& n : info->needs) {
      EXPECT_TRUE(is_vocabulary(n.term)) << n.term.name;
      EXPECT_FALSE(n.term.per_criterion()) << "no stage reads a criterion's result: " << n.term.name;
    }
  }
}

TEST(PluginContract, EveryNeedIsPublishedByABundledPluginAndEveryTermByOne) {
  const auto plugins = bundled_plugins();
  std::set<std::string_view> published;
  for (const PluginInfo* info : plugins)
    for (const Term& t : info->publishes) published.insert(t.name);
  for (const PluginInfo* info : plugins)
    for (const Need& n : info->needs)
      EXPECT_TRUE(published.contains(n.term.name)) << info->name << " needs " << n.term.name << ", which no plugin publishes";
  for (const Term& t : vocabulary::all) EXPECT_TRUE(published.contains(t.name)) << t.name << " is published by no plugin";
}

// A stage of a loaded plugin, run by hand.
struct HandRun {
  Results results;
  Light light;
  std::string section, plugin;
  HandRun(std::string section, std::string plugin) : section(std::move(section)), plugin(std::move(plugin)) {
    PluginHost::instance().load(kind_of_section(this->section), this->plugin);
  }
  Context context() { return Context(results, light, section, plugin); }
};

TEST(PluginContract, RequiringAResultNotListedInNeedsIsAProgrammingError) {
  HandRun run("criteria.detection", "snr_threshold");
  Context c = run.context();
  try {
    c.require(vocabulary::optics_aperture);
    FAIL() << "no logic_error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("snr_threshold"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("optics.aperture"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("needs"), std::string::npos) << e.what();
  }
  EXPECT_THROW(c.find(vocabulary::optics_aperture), std::logic_error);
  // A listed need that no earlier stage declared is the user's chain that does not fit: an InputError.
  EXPECT_THROW(c.require(vocabulary::detector_snr), InputError);
}

TEST(PluginContract, RequiringAnOptionalNeedIsAProgrammingError) {
  HandRun run("detector", "ccd_frame");  // lists the optics' f-number as if_present()
  Context c = run.context();
  EXPECT_THROW(c.require(vocabulary::optics_f_number), std::logic_error);
  EXPECT_FALSE(c.find(vocabulary::optics_f_number).has_value());
}

// A look-up is remembered between spectral phases, a miss too: the next phase's same look-up is a comparison, and the
// contract is not checked again (the cold spectral phase's cost). A miss is looked up afresh once a result has been
// declared, since it may be the one looked for; an unlisted need is still a programming error at its first look-up.
TEST(PluginContract, AMissIsRememberedUntilAResultIsDeclared) {
  HandRun run("detector", "ccd_frame");  // lists the optics' f-number as if_present()
  StageMemo memo;
  const auto& lookups = memo.lookups;
  auto phase = [&] { return Context(run.results, run.light, run.section, run.plugin, Detail::full, &memo); };
  {
    Context c = phase();
    EXPECT_FALSE(c.find(vocabulary::optics_f_number).has_value());
  }
  ASSERT_EQ(lookups.size(), 1u);
  EXPECT_EQ(lookups[0].id, SIZE_MAX);
  EXPECT_EQ(lookups[0].term, &vocabulary::optics_f_number);
  {
    Context c = phase();
    EXPECT_FALSE(c.find(vocabulary::optics_f_number).has_value());  // remembered
    EXPECT_THROW(c.find(vocabulary::optics_aperture), std::logic_error);  // not the remembered one: checked
  }
  const ResultId f_number = run.results.declare("optics.f_number", "1", "telescope", "N = f'/D");
  {
    Context c = phase();
    EXPECT_EQ(c.find(vocabulary::optics_f_number), std::optional<ResultId>(f_number));  // declared since: found
  }
  EXPECT_EQ(lookups[0].id, f_number);
}

// A stage's declarations are remembered between spectral phases: the same ones again keep their ids (a term by
// identity, a plain name by its text), and a changed equation is taken, never left stale; a declaration out of the
// remembered order, or another term in its place, is checked against the contract afresh.
TEST(PluginContract, ARepeatedDeclarationKeepsItsIdAndTakesANewEquation) {
  HandRun run("criteria.detection", "snr_threshold");
  StageMemo memo;
  const auto& declarations = memo.declarations;
  auto phase = [&] { return Context(run.results, run.light, run.section, run.plugin, Detail::full, &memo); };
  std::string equation = "m = SNR − T";  // a label the plugin builds: the same buffer, new text
  ResultId margin{}, detected{};
  {
    Context c = phase();
    margin = c.declare(vocabulary::criterion_margin, equation);
    detected = c.declare("detected", "1", "m ≥ 0");
  }
  ASSERT_EQ(declarations.size(), 2u);
  EXPECT_EQ(declarations[0].term, &vocabulary::criterion_margin);
  EXPECT_EQ(declarations[1].term, nullptr);
  // String literals are recognised as such (read-only segments), a std::string's buffer is not.
  EXPECT_EQ(declarations[0].literal[2], nullptr);
  EXPECT_NE(declarations[1].literal[0], nullptr);
  EXPECT_NE(declarations[1].literal[2], nullptr);
  equation.replace(equation.find('T'), 1, "5");
  {
    Context c = phase();
    EXPECT_EQ(c.declare(vocabulary::criterion_margin, equation), margin);
    EXPECT_EQ(c.declare("detected", "1", "m ≥ 0 (pinned)"), detected);
  }
  EXPECT_EQ(run.results.info(margin).equation, "m = SNR − 5");
  EXPECT_EQ(run.results.info(detected).equation, "m ≥ 0 (pinned)");
  EXPECT_EQ(run.results.size(), 2u);
  {
    Context c = phase();
    EXPECT_THROW(c.declare(vocabulary::detector_snr, "x"), std::logic_error);  // another term in the first place
  }
  {
    Context c = phase();
    EXPECT_THROW(c.declare("margin", "1", "x"), std::logic_error);  // the term's name as a plain one: not the memo's
  }
}

TEST(PluginContract, DeclaringAnUnlistedOrMisspelledTermIsAProgrammingError) {
  HandRun run("criteria.detection", "snr_threshold");
  Context c = run.context();
  EXPECT_THROW(c.declare(vocabulary::criterion_required_quality, "x"), std::logic_error);  // not in publishes
  EXPECT_THROW(c.declare(vocabulary::detector_snr, "x"), std::logic_error);               // another section's
  EXPECT_THROW(c.declare("margin", "1", "x"), std::logic_error);  // a vocabulary name as a plain string
  const ResultId margin = c.declare(vocabulary::criterion_margin, "x");
  EXPECT_EQ(run.results.info(margin).name, "criteria.detection.margin");
  EXPECT_EQ(run.results.info(margin).si_unit, "1");
  EXPECT_NO_THROW(c.declare("detected", "1", "x"));  // a result only the report shows
}

// `radchain describe ...` (the test environment's plugin path), stdout.
std::string describe(const std::string& what) {
  std::string out;
  if (FILE* pipe = ::popen(("'" RADCHAIN_CLI "' describe " + what + " 2>&1").c_str(), "r")) {
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

TEST(DescribeContract, APluginShowsWhatItPublishesAndNeedsWithUnitsAndMeanings) {
  const std::string out = describe("snr_threshold");
  const auto publishes = out.find("\npublishes:\n"), needs = out.find("\nneeds:\n"), example = out.find("\nexample:\n");
  ASSERT_NE(publishes, std::string::npos) << out;
  ASSERT_NE(needs, std::string::npos) << out;
  ASSERT_LT(publishes, needs);
  ASSERT_LT(needs, example);
  const std::string published = out.substr(publishes, needs - publishes), needed = out.substr(needs, example - needs);
  EXPECT_NE(published.find("criteria.<name>.margin"), std::string::npos) << published;
  EXPECT_NE(published.find(std::string(vocabulary::criterion_margin.meaning)), std::string::npos) << published;
  EXPECT_NE(needed.find("detector.snr  [1]  " + std::string(vocabulary::detector_snr.meaning)), std::string::npos) << needed;
}

TEST(DescribeContract, AKindListsItsPluginsWithTheirSummaries) {
  for (const char* kind : {"criterion", "criteria"}) {
    const std::string out = describe(kind);
    SCOPED_TRACE(out);
    EXPECT_EQ(out.rfind("criterion plugins", 0), 0u);
    for (const PluginInfo* info : bundled_plugins())
      EXPECT_EQ(out.find(info->summary) != std::string::npos, info->kind == Kind::criterion) << info->name;
  }
}

TEST(PluginHostDiscovery, ScansOncePerSearchPath) {
  const fs::path dir = fs::temp_directory_path() / ("radchain-discovery-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "optics");
  std::string telescope_path;
  for (const auto& f : PluginHost::instance().discover())
    if (f.name == "telescope") telescope_path = f.path;
  ASSERT_FALSE(telescope_path.empty());

  PluginHost& host = PluginHost::instance();
  host.configure({dir.string()});
  const std::size_t before = host.discover().size();
  fs::copy_file(telescope_path, dir / "optics" / "zz_late_arrival.so");
  EXPECT_EQ(host.discover().size(), before);  // the scan is cached
  host.configure({dir.string()});
  EXPECT_EQ(host.discover().size(), before + 1);  // a new search path is scanned again
  host.configure({});
  fs::remove_all(dir);
}

}  // namespace
