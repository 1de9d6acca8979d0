#include "radchain/plugin.hpp"

#include "radchain/error.hpp"

#include "radchain/plugin_host.hpp"

#include <fmt/format.h>

#include <link.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace radchain {

Stage::~Stage() = default;  // the key function lives in the framework, so every plugin shares one vtable type
void Stage::prepare(Context&) {}
bool Stage::evaluate_lanes(LaneContext&) { return false; }

namespace {
const KindInfo& info_of(Kind kind) {
  for (const KindInfo& k : kinds)
    if (k.kind == kind) return k;
  throw std::logic_error(fmt::format("no Kind {} in radchain::kinds", static_cast<int>(kind)));
}
}  // namespace

std::string to_string(Kind kind) { return std::string(info_of(kind).name); }
std::string kind_directory(Kind kind) { return std::string(info_of(kind).name); }

std::optional<Kind> kind_from_name(std::string_view name) {
  for (const KindInfo& k : kinds)
    if (k.name == name) return k.kind;
  return std::nullopt;
}

Kind kind_of_section(std::string_view section) {
  const std::string_view head = section.substr(0, section.find('.'));  // "criteria.detection" -> "criteria"
  for (const KindInfo& k : kinds)
    if (k.section == head) return k.kind;
  throw std::logic_error(fmt::format("\"{}\" is no plugin kind's section", section));
}

bool PluginInfo::publishes_term(const Term& term) const {
  return std::find(publishes.begin(), publishes.end(), term) != publishes.end();
}

const Need* PluginInfo::need_of(const Term& term) const {
  for (const Need& n : needs)
    if (n.term == term) return &n;
  return nullptr;
}

std::string to_string(RadiationForm form) {
  switch (form) {
    case RadiationForm::none: return "no radiation";
    case RadiationForm::pupil_irradiance: return "a point object's irradiance at the pupil";
    case RadiationForm::scene_radiance: return "an extended scene's radiance";
    case RadiationForm::focal_power: return "a point image's power";
    case RadiationForm::focal_irradiance: return "a focal-plane irradiance";
  }
  return "?";
}

namespace {
// Whether the text lies in a segment a loaded object maps without write permission (a string literal's .rodata):
// such text cannot change while the object stays loaded, and a plugin's object stays loaded while its stages live.
// The read-only segments are listed again whenever objects were loaded or unloaded since (dl_iterate_phdr's
// counters); this runs when a stage's declaration is first remembered, not in the repeated spectral phases.
bool in_read_only_segment(std::string_view text) {
  if (text.empty()) return false;
  struct Segments {
    unsigned long long adds = ~0ULL, subs = ~0ULL;
    std::vector<std::pair<std::uintptr_t, std::uintptr_t>> read_only;  // [begin, end)
  };
  static std::mutex mutex;
  static Segments segments;
  const std::lock_guard lock(mutex);
  Segments now;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t size, void* data) {
        auto* s = static_cast<Segments*>(data);
        if (size < offsetof(dl_phdr_info, dlpi_subs) + sizeof info->dlpi_subs) return 1;  // no counters: list anew
        s->adds = info->dlpi_adds, s->subs = info->dlpi_subs;
        return 1;
      },
      &now);
  if (now.adds != segments.adds || now.subs != segments.subs || now.adds == ~0ULL) {
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* data) {
          auto* s = static_cast<Segments*>(data);
          for (int i = 0; i < info->dlpi_phnum; ++i) {
            const ElfW(Phdr)& ph = info->dlpi_phdr[i];
            if (ph.p_type == PT_LOAD && !(ph.p_flags & PF_W))
              s->read_only.emplace_back(info->dlpi_addr + ph.p_vaddr, info->dlpi_addr + ph.p_vaddr + ph.p_memsz);
          }
          return 0;
        },
        &now);
    std::sort(now.read_only.begin(), now.read_only.end());  // segments do not overlap
    segments = std::move(now);
  }
  const auto begin = reinterpret_cast<std::uintptr_t>(text.data()), end = begin + text.size();
  const auto after = std::upper_bound(segments.read_only.begin(), segments.read_only.end(),
                                      std::pair(begin, UINTPTR_MAX));  // the first segment starting after `begin`
  return after != segments.read_only.begin() && end <= std::prev(after)->second;
}

// The contract a plugin states (PluginInfo::publishes, needs), or nothing for a stage the host did not load
// (a test's hand-built stage).
const PluginInfo* contract_of(const std::string& plugin) { return PluginHost::instance().loaded(plugin); }
}  // namespace

ResultId Context::declare(std::string_view name, std::string_view si_unit, std::string_view equation,
                          std::string_view display_unit) {
  return declare_result(nullptr, name, si_unit, equation, display_unit);
}

ResultId Context::declare(const Term& term, std::string_view equation, std::string_view display_unit) {
  return declare_result(&term, {}, term.unit, equation, display_unit);
}

// `name` is empty for a term: its key, read only when the memo does not answer (the term's text is one more cache
// miss in a cold spectral phase).
ResultId Context::declare_result(const Term* term, std::string_view name, std::string_view si_unit,
                                 std::string_view equation, std::string_view display_unit) {
  if (memo_ && next_declaration_ < memo_->declarations.size()) {
    // The same declaration as at the last spectral phase (checked against the contract when it was first made)?
    const StageMemo::Declared& last = memo_->declarations[next_declaration_];
    const std::string_view text = std::string_view(memo_->text).substr(last.text_begin);
    auto same = [&](int k, std::string_view now, std::size_t begin, std::size_t size) {
      return now.size() == size && (now.data() == last.literal[k] || text.substr(begin, size) == now);
    };
    const bool same_name_and_unit = term ? last.term == term
                                         : !last.term && same(0, name, 0, last.name_size) &&
                                               same(1, si_unit, last.name_size, last.unit_size);
    if (same_name_and_unit) {
      const ResultId id = last.id;
      if (!same(2, equation, last.name_size + last.unit_size, last.equation_size)) {
        results.declare(results.info(id).name, results.info(id).si_unit, plugin, std::string(equation));  // relabel
        memo_->text.resize(last.text_begin);  // and remember it anew (`last` goes with the resize below)
        memo_->declarations.resize(next_declaration_);
        remember_declaration(id, term, name, si_unit, equation);
      }
      ++next_declaration_;
      return id;
    }
  }
  if (term) name = term->key();
  std::string qualified = section + "." + std::string(name);
  if (!term) {
    if (const Term* known = vocabulary::term_of(qualified))
      throw std::logic_error(fmt::format("plugin \"{}\" declares \"{}\" as a plain name: it is the vocabulary's \"{}\" "
                                         "(declare it with Context::declare(term, ...))",
                                         plugin, qualified, known->name));
  } else {
    if (!term->matches(qualified))
      throw std::logic_error(fmt::format("plugin \"{}\" in [{}] declares \"{}\", a result of another section", plugin,
                                         section, term->name));
    if (const PluginInfo* info = contract_of(plugin); info && !info->publishes_term(*term))
      throw std::logic_error(fmt::format("plugin \"{}\" declares \"{}\" but does not list it in `publishes` "
                                         "(RADCHAIN_PLUGIN(..., .publishes = {{...}}))",
                                         plugin, term->name));
  }
  const ResultId id = results.declare(std::move(qualified), std::string(si_unit), plugin, std::string(equation),
                                      std::string(display_unit));
  if (memo_) {  // a stage that declares differently from now on: forget the rest
    if (next_declaration_ < memo_->declarations.size()) {
      memo_->text.resize(memo_->declarations[next_declaration_].text_begin);
      memo_->declarations.resize(next_declaration_);
    }
    remember_declaration(id, term, name, si_unit, equation);
    ++next_declaration_;
  }
  return id;
}

void Context::remember_declaration(ResultId id, const Term* term, std::string_view name, std::string_view si_unit,
                                   std::string_view equation) {
  StageMemo::Declared d{id, term, static_cast<std::uint32_t>(memo_->text.size()), 0, 0,
                        static_cast<std::uint32_t>(equation.size())};
  if (!term) {
    d.name_size = static_cast<std::uint32_t>(name.size()), d.unit_size = static_cast<std::uint32_t>(si_unit.size());
    memo_->text.append(name).append(si_unit);
    if (in_read_only_segment(name)) d.literal[0] = name.data();
    if (in_read_only_segment(si_unit)) d.literal[1] = si_unit.data();
  }
  memo_->text.append(equation);
  if (in_read_only_segment(equation)) d.literal[2] = equation.data();
  memo_->declarations.push_back(d);
}

std::optional<ResultId> Context::find(const Term& term) { return look_up(term, false); }

ResultId Context::require(const Term& term) {
  if (auto id = look_up(term, true)) return *id;
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("needs the result \"{}\", which no earlier stage provides: the chain's plugins do not fit together",
                               term.name));
}

std::optional<ResultId> Context::look_up(const Term& term, bool required) {
  if (memo_ && next_lookup_ < memo_->lookups.size()) {
    const StageMemo::LookUp& last = memo_->lookups[next_lookup_];
    if (last.term == &term && (last.id != SIZE_MAX || last.results_then == results.size())) {
      ++next_lookup_;
      return last.id == SIZE_MAX ? std::nullopt : std::optional<ResultId>(last.id);
    }
  }
  // Not a repeat of the last spectral phase: the look-up must be one the plugin states.
  if (term.per_criterion())
    throw std::logic_error(fmt::format("plugin \"{}\" looks up \"{}\": a criterion's result is no stage's input",
                                       plugin, term.name));
  if (const PluginInfo* info = contract_of(plugin)) {
    const Need* need = info->need_of(term);
    if (!need)
      throw std::logic_error(fmt::format("plugin \"{}\" reads the result \"{}\" but does not list it in `needs` "
                                         "(RADCHAIN_PLUGIN(..., .needs = {{...}}))",
                                         plugin, term.name));
    if (required && need->optional)
      throw std::logic_error(fmt::format("plugin \"{}\" requires the result \"{}\" but lists it as if_present() in "
                                         "`needs`",
                                         plugin, term.name));
  }
  const std::optional<ResultId> id = results.find(term.name);
  if (memo_) {  // (a miss is looked up again once a result has been declared: it may be the one)
    memo_->lookups.resize(next_lookup_);
    memo_->lookups.push_back(StageMemo::LookUp{id.value_or(SIZE_MAX), &term, results.size()});
    ++next_lookup_;
  }
  return id;
}

void Context::set_in_spectral_phase(ResultId id, double value, std::initializer_list<const double*> scalar_parameters) {
  if (!exchange_)
    throw std::logic_error(fmt::format("plugin \"{}\" sets \"{}\" for the spectral phase outside its spectral phase "
                                       "(prepare)",
                                       plugin, results.info(id).name));
  results.set(id, value);
  exchange_->set.push_back(SpectralExchange::Set{id, value, std::vector<const double*>(scalar_parameters)});
}

double Context::read_in_spectral_phase(ResultId id) {
  if (!exchange_)
    throw std::logic_error(fmt::format("plugin \"{}\" reads \"{}\" for its spectral phase outside it (prepare)", plugin,
                                       results.info(id).name));
  exchange_->read.push_back(id);
  return results.value(id);
}

void Context::warn(const InputError& warning) {
  if (!warnings_) return;
  const std::string line = warning.what();
  if (std::find(warnings_->begin(), warnings_->end(), line) == warnings_->end()) warnings_->push_back(line);
}

void Context::refuse_form(const std::string& what, RadiationForm form) const {
  // No light: the file has no [source] (a geometry-only file, or a self-luminous target's that needs none).
  if (form == RadiationForm::none)
    throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                     fmt::format("needs light ({}), but the sensor file has no [source] section to give it: add one "
                                 "(e.g. [source] plugin = \"sun\"), or use a stage that needs no light",
                                 what));
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("expected {} but the earlier stages deliver {}", what, to_string(form)));
}

}  // namespace radchain
