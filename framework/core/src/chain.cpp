#include "radchain/chain.hpp"

#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <string_view>

namespace radchain {

bool Report::all_passed() const {
  for (const auto& s : solves)
    if (!s.converged) return false;
  for (const auto& e : expectations)
    if (!e.passed) return false;
  for (const auto& c : criteria)
    if (!c.passed && !c.informational) return false;
  return true;
}

std::optional<double> Report::value(const std::string& name) const {
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].name == name) return values[i];
  return std::nullopt;
}

namespace {
// A physics function's domain error while a stage runs — a line of sight past the horizon, a focal length a
// sweep or a solve took to zero — is bad input, not an internal error: one line naming the stage (exit 2).
// Plugins keep throwing std::domain_error / std::invalid_argument from physics/ (no InputError there: physics
// knows no sections); anything else a stage throws stays an internal error.
template <class Run>
void run_stage(const StageSlot& slot, const std::string& sensor_file, Run&& run) {
  try {
    run();
  } catch (const std::domain_error& error) {
    throw InputError(SourceLocation{sensor_file}, slot.params ? slot.params->context() : slot.section, "", error.what());
  } catch (const std::invalid_argument& error) {
    throw InputError(SourceLocation{sensor_file}, slot.params ? slot.params->context() : slot.section, "", error.what());
  }
}
}  // namespace

void Chain::invalidate_spectra() {
  spectral_from_ = 0;
  scalar_from_ = 0;
}

void Chain::prepare_from(std::size_t first) {
  light_before_.resize(stages.size());
  light_ = first == 0 ? Light{} : light_before_[first];
  // What the stages not re-run set for later spectral phases, as their spectral phase set it (run() clears values).
  for (std::size_t k = 0; k < first; ++k)
    for (const SpectralExchange::Set& s : stages[k].exchange.set) results_.set(s.id, s.value);
  for (std::size_t k = first; k < stages.size(); ++k) {
    StageSlot& slot = stages[k];
    light_before_[k] = light_;
    slot.exchange.set.clear();
    slot.exchange.read.clear();
    slot.spectral_warnings.clear();
    Context context(results_, light_, slot.section, slot.plugin, Detail::full, &slot.memo, &slot.exchange,
                    &slot.spectral_warnings);
    run_stage(slot, sensor_file, [&] { slot.stage->prepare(context); });
  }
  spectral_from_ = stages.size();
  find_spectral_reads();
}

// A result an earlier stage set in its spectral phase from scalar parameters (the platform's view zenith from its
// roll), read by a later stage's spectral phase (the atmosphere's view airmass): those parameters are spectral in
// this chain, so that Chain::set re-runs the spectral phase from the producing stage and lanes never vary them.
// Chains where no spectral phase reads such a result keep them scalar (a sweep over roll stays on the lanes).
void Chain::find_spectral_reads() {
  read_spectrally_.clear();
  for (std::size_t k = 0; k < stages.size(); ++k)
    for (const ResultId id : stages[k].exchange.read) {
      bool found = false;
      for (std::size_t j = 0; j < k; ++j)
        for (const SpectralExchange::Set& s : stages[j].exchange.set)
          if (s.id == id) {
            found = true;
            read_spectrally_.insert(read_spectrally_.end(), s.parameters.begin(), s.parameters.end());
          }
      if (!found)
        throw std::logic_error(fmt::format("[{}] (plugin \"{}\") reads \"{}\" in its spectral phase, but no earlier stage "
                                           "sets it there (Context::set_in_spectral_phase)",
                                           stages[k].section, stages[k].plugin, results_.info(id).name));
    }
}

bool Chain::read_in_spectral_phase(const double* parameter) const {
  return std::find(read_spectrally_.begin(), read_spectrally_.end(), parameter) != read_spectrally_.end();
}

void Chain::evaluate_from(std::size_t first, Detail detail) {
  scales_before_.resize(stages.size());
  const Scales start = first == 0 ? Scales{} : scales_before_[first];
  light_.illumination_scale = start.illumination;
  light_.signal.scale = start.signal;
  light_.background.scale = start.background;
  light_.up_path_scale = start.up_path;
  for (std::size_t k = first; k < stages.size(); ++k) {
    scales_before_[k] = Scales{light_.illumination_scale, light_.signal.scale, light_.background.scale, light_.up_path_scale};
    if (skips(k)) continue;
    StageSlot& slot = stages[k];
    slot.scalar_warnings.clear();
    Context context(results_, light_, slot.section, slot.plugin, detail, nullptr, nullptr, &slot.scalar_warnings);
    run_stage(slot, sensor_file, [&] { slot.stage->evaluate(context); });
  }
  for (const ResolvedSolve& r : resolved_)
    if (r.echo != SIZE_MAX) results_.set(r.echo, r.unknown.value());
  scalar_from_ = stages.size();
  ++scalar_version_;
  if (detail == Detail::essential) essential_from_ = std::min(essential_from_, first);
  else if (first <= essential_from_) essential_from_ = SIZE_MAX;
}

void Chain::set_lanes(const ParameterRef& parameter, const Lanes& values) {
  if (parameter.spectral_ || read_in_spectral_phase(parameter.value_))
    throw std::logic_error("a spectral parameter cannot differ between lanes (the spectral phase is shared)");
  for (std::size_t i = 0; i < lane_slots_.size(); ++i)
    if (lane_slots_[i].address == parameter.value_) {
      lane_parameters_[i].values = values;
      return;
    }
  lane_parameters_.push_back(LaneParameter{parameter.value_, values});
  lane_slots_.push_back(LaneSlot{parameter.value_, parameter.stage_});
}

void Chain::evaluate_lanes(Detail detail) {
  evaluate(Detail::full);  // the scalar phase up to date: the lanes start from its results
  std::size_t first = stages.size();
  for (const LaneSlot& s : lane_slots_) first = std::min(first, s.stage);
  if (lane_base_version_ != scalar_version_ || lane_results_.size() != results_.size()) {
    lane_results_.resize(results_.size());
    for (std::size_t id = 0; id < results_.size(); ++id) lane_results_[id] = constant_lanes(results_.value(id));
    lane_base_version_ = scalar_version_;
  }
  if (first < stages.size()) {
    const Scales& start = scales_before_[first];
    lane_scales_ = LaneScales{constant_lanes(start.illumination), constant_lanes(start.signal),
                              constant_lanes(start.background), constant_lanes(start.up_path)};
  }
  for (std::size_t k = first; k < stages.size(); ++k) {
    if (skips(k)) continue;
    LaneContext context(lane_results_, light_, lane_scales_, lane_parameters_, detail == Detail::full);
    bool by_lanes = false;
    run_stage(stages[k], sensor_file, [&] { by_lanes = stages[k].stage->evaluate_lanes(context); });
    if (!by_lanes) evaluate_lane_by_lane(stages[k], detail);
  }
  for (const ResolvedSolve& r : resolved_)
    if (r.echo != SIZE_MAX) {
      lane_results_[r.echo] = constant_lanes(r.unknown.value());
      for (const LaneParameter& p : lane_parameters_)
        if (p.address == r.unknown.value_) lane_results_[r.echo] = p.values;
    }
}

// The scalar evaluate() once per lane, with that lane's parameters, upstream results and scales in the scalar
// slots; everything scalar is put back afterwards, so the scalar phase stays valid.
void Chain::evaluate_lane_by_lane(StageSlot& slot, Detail detail) {
  saved_values_ = results_.values();
  const Light saved_light = light_;
  std::vector<double> saved_parameters;
  for (const LaneSlot& s : lane_slots_) saved_parameters.push_back(*s.address);
  // Put back on every way out: a caller that catches an InputError (Python, a sweep naming the point) keeps
  // a valid scalar phase.
  auto restore = [&] {
    for (std::size_t i = 0; i < lane_slots_.size(); ++i) *lane_slots_[i].address = saved_parameters[i];
    results_.restore(saved_values_);
    light_ = saved_light;
  };
  try {
    for (int lane = 0; lane < lane_count; ++lane) {
      for (std::size_t i = 0; i < lane_slots_.size(); ++i) *lane_slots_[i].address = lane_parameters_[i].values(lane);
      for (std::size_t id = 0; id < results_.size(); ++id) results_.set(id, lane_results_[id](lane));
      light_.illumination_scale = lane_scales_.illumination(lane);
      light_.signal.scale = lane_scales_.signal(lane);
      light_.background.scale = lane_scales_.background(lane);
      light_.up_path_scale = lane_scales_.up_path(lane);
      Context context(results_, light_, slot.section, slot.plugin, detail);
      run_stage(slot, sensor_file, [&] { slot.stage->evaluate(context); });
      for (const StageMemo::Declared& d : slot.memo.declarations) lane_results_[d.id](lane) = results_.value(d.id);
      lane_scales_.illumination(lane) = light_.illumination_scale;
      lane_scales_.signal(lane) = light_.signal.scale;
      lane_scales_.background(lane) = light_.background.scale;
      lane_scales_.up_path(lane) = light_.up_path_scale;
    }
  } catch (...) {
    restore();
    throw;
  }
  restore();
}

void Chain::focus(const std::vector<ResultId>& wanted) {
  std::vector<char> skip;
  if (!wanted.empty()) {
    evaluate(Detail::essential);  // every stage's declarations known (a result's stage is the one declaring it)
    std::vector<ResultId> needed = wanted;
    for (const ResolvedSolve& r : resolved_) needed.insert(needed.end(), r.margins.begin(), r.margins.end());
    std::vector<char> publishes(stages.size(), 0);
    std::size_t last = 0;
    for (ResultId id : needed) {
      // A solved unknown's echo is written by the chain itself after the stages (its value is the parameter's).
      if (std::any_of(resolved_.begin(), resolved_.end(), [&](const ResolvedSolve& r) { return r.echo == id; })) continue;
      std::size_t k = 0;
      while (k < stages.size() && std::none_of(stages[k].memo.declarations.begin(), stages[k].memo.declarations.end(),
                                               [&](const StageMemo::Declared& d) { return d.id == id; }))
        ++k;
      if (k == stages.size()) {  // echoed or unknown to every stage: nothing can be left out safely
        last = stages.size();
        break;
      }
      publishes[k] = 1;
      last = std::max(last, k);
    }
    // No criterion reads another's results (a criterion reads the chain's physics, never a verdict), so a
    // criterion nobody asked for can be left out wherever it stands.
    skip.assign(stages.size(), 0);
    for (std::size_t k = 0; k < stages.size(); ++k)
      skip[k] = last < stages.size() && (k > last || (!publishes[k] && stages[k].section.starts_with("criteria.")));
  }
  for (std::size_t k = 0; k < stages.size(); ++k)
    if (skips(k) && !(k < skip.size() && skip[k])) scalar_from_ = std::min(scalar_from_, k);
  skip_ = std::move(skip);
}

void Chain::evaluate(Detail detail) {
  std::size_t first = scalar_from_;
  if (spectral_from_ < stages.size()) {
    first = std::min(first, spectral_from_);
    prepare_from(spectral_from_);
  }
  if (detail == Detail::full) first = std::min(first, essential_from_);
  if (first < stages.size()) evaluate_from(first, detail);
}

// Name equality without a call into libc, and lookups without temporary strings (sweeps and solves resolve their
// solved unknowns by name at every evaluation.
static bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) return false;
  return true;
}

StageSlot& Chain::slot(const std::string& section) {
  for (auto& s : stages)
    if (same_name(s.section, section)) return s;
  throw std::out_of_range("no section \"" + section + "\"");
}

ParameterRef Chain::parameter(const std::string& qualified_key) {
  const auto dot = qualified_key.rfind('.');
  if (dot == std::string::npos) throw std::out_of_range("\"" + qualified_key + "\" is not <section>.<key>");
  const std::string_view section(qualified_key.data(), dot);
  const std::string_view key(qualified_key.data() + dot + 1, qualified_key.size() - dot - 1);
  StageSlot* s = nullptr;
  std::size_t index = 0;
  for (; index < stages.size(); ++index)
    if (same_name(stages[index].section, section)) {
      s = &stages[index];
      break;
    }
  if (!s) throw std::out_of_range("no section \"" + std::string(section) + "\"");
  Params::Entry* found = nullptr;
  for (auto& e : s->params->entries())
    if (same_name(e.spec->key, key)) {
      found = &e;
      break;
    }
  Params::Entry& entry = found ? *found : s->params->entry(std::string(key));  // (throws the schema's message)
  const ParamType type = entry.spec->type;
  if (type != ParamType::quantity && type != ParamType::number && type != ParamType::integer)
    throw std::out_of_range("\"" + qualified_key + "\" is not a numeric parameter");
  entry.present = true;
  ParameterRef ref;
  ref.value_ = &entry.number;
  ref.stage_ = index;
  ref.spectral_ = entry.spec->spectral || read_in_spectral_phase(&entry.number);
  ref.scaling_ = entry.spec->scaling;
  return ref;
}

void Chain::set(const ParameterRef& parameter, double value_si) {
  *parameter.value_ = value_si;
  scalar_from_ = std::min(scalar_from_, parameter.stage_);
  if (parameter.spectral_ || read_in_spectral_phase(parameter.value_))
    spectral_from_ = std::min(spectral_from_, parameter.stage_);
}

double Chain::result(const std::string& name) const {
  if (auto id = results_.find(name)) return results_.value(*id);
  throw std::out_of_range("no result \"" + name + "\"");
}


Report Chain::run() {
  skip_.clear();  // a report has every result
  results_.clear_values();
  scalar_from_ = 0;  // every result again (the spectral phase only if something spectral changed)
  evaluate();
  Report report;
  report.sensor_file = sensor_file;
  report.sensor_name = sensor_name;
  solve_all(report.solves);
  report.results.reserve(results_.size());
  for (std::size_t i = 0; i < results_.size(); ++i) {
    report.results.push_back(results_.info(i));
    report.values.push_back(results_.value(i));
  }
  for (const auto& e : expected) {
    ExpectationOutcome outcome{e, std::numeric_limits<double>::quiet_NaN(), false, false};
    if (auto id = results_.find(e.result)) {
      outcome.found = true;
      outcome.computed_si = results_.value(*id);
      const double reference = e.follows_si.value_or(e.value_si);  // an erratum is checked against what follows
      const double difference = std::abs(outcome.computed_si - reference);
      const double allowed = std::max(e.tolerance_si, e.rel_tolerance * std::abs(reference));
      outcome.passed = difference <= allowed;
    }
    report.expectations.push_back(outcome);
  }
  for (const TableSpec& table : tables) report.tables.push_back(tabulate(table));
  report.criteria = criterion_outcomes(report.solves);
  for (const StageSlot& slot : stages) {
    if (slot.params) report.warnings.insert(report.warnings.end(), slot.params->renamed().begin(), slot.params->renamed().end());
    report.warnings.insert(report.warnings.end(), slot.spectral_warnings.begin(), slot.spectral_warnings.end());
    report.warnings.insert(report.warnings.end(), slot.scalar_warnings.begin(), slot.scalar_warnings.end());
  }
  return report;
}

std::vector<CriterionOutcome> Chain::criterion_outcomes(const std::vector<SolveOutcome>& solves) const {
  std::vector<CriterionOutcome> out;
  bool saturation_judged = false;
  for (const StageSlot& slot : stages) {
    if (slot.section.rfind("criteria.", 0) != 0) continue;
    saturation_judged = saturation_judged || slot.plugin == "unsaturated";
    CriterionOutcome c;
    c.section = slot.section;
    c.informational = slot.informational;
    const std::string name = slot.section.substr(std::string_view("criteria.").size());
    const auto id = results_.find(slot.section + ".margin");
    if (!id) continue;  // a criterion without a margin judges nothing
    c.margin = results_.value(*id);
    bool solved = false;  // the binding criterion of a converged solve: its margin is the root's residual
    for (const SolveOutcome& s : solves) solved = solved || (s.converged && s.binding == name);
    // A margin of −1e-9 is rounding at a threshold (unsaturated's own `saturated` flag uses the same).
    c.passed = solved || c.margin >= -1e-9;
    if (std::isnan(c.margin)) {
      c.passed = solved;
      if (!solved) c.reason = "its margin was not computed (a failed solve before it)";
    } else if (!c.passed) {
      c.reason = fmt::format("margin {:+.4g} < 0: {}", c.margin, results_.info(*id).equation);
    }
    out.push_back(std::move(c));
  }
  // No SNR of a clipped pixel is valid: without an `unsaturated` criterion the detector's brightest pixel is
  // judged here.
  if (!saturation_judged)
    if (const auto fill = results_.find("detector.peak_pixel_fill"); fill && results_.value(*fill) > 1 + 1e-9) {
      const double f = results_.value(*fill);
      out.push_back(CriterionOutcome{
          "detector", 1 / f - 1, false, false,
          fmt::format("the brightest pixel holds {:.4g} % of its capacity (detector.peak_pixel_fill): it saturates, and "
                      "the SNR of a clipped pixel is not valid (add [criteria.unsaturated] with informational = true "
                      "to accept it)",
                      100 * f)});
    }
  return out;
}

TableOutcome Chain::tabulate(const TableSpec& table) {
  TableOutcome out;
  out.spec = table;
  std::vector<ResultId> ids;
  for (const std::string& name : table.results) {
    const auto id = results_.find(name);
    if (!id) throw std::out_of_range("[[table]] result " + name);  // sensor_file.cpp validated the names
    ids.push_back(*id);
    out.columns.push_back(results_.info(*id));
  }
  const ParameterRef varied = parameter(table.vary);
  const double original = varied.value();
  std::vector<SolveOutcome> outcomes;
  for (const double value : table.values_si) {
    set(varied, value);
    solve_all(outcomes);
    std::string note;
    for (const SolveOutcome& s : outcomes)
      if (!s.converged) note += (note.empty() ? "" : "; ") + s.spec.unknown + ": " + s.message;
    // A row whose solve failed has no values: the others were computed at the bracket end the solver left.
    std::vector<double> row;
    for (const ResultId id : ids) row.push_back(note.empty() ? results_.value(id) : std::numeric_limits<double>::quiet_NaN());
    out.rows.push_back(std::move(row));
    out.notes.push_back(std::move(note));
  }
  // Back to the file's value: the same solves again leave the chain as run() did before the table.
  set(varied, original);
  solve_all(outcomes);
  return out;
}

}  // namespace radchain
