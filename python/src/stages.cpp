// Stages written in Python (radchain.register_stage, docs/python.md): a Python class becomes a plugin of the
// chain; its evaluate() is called with the light and the results it needs, with the GIL held.
#include "bindings.hpp"

#include "radchain/error.hpp"
#include "radchain/plugin.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/version.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <map>
#include <memory>

namespace radchain::python {
namespace {

// --- stages written in Python (radchain.register_stage, docs/python.md) -------------------------------------------
// A Python class with a schema, the vocabulary terms it publishes and needs, and evaluate(params, inputs) returning
// {term: value}, added to the plugin host (PluginHost::add): a sensor file's plugin = "<name>" then builds it like a
// library's stage. Its scalar phase calls Python with the GIL held, one point at a time: slow, and the same numbers.
// Its optional prepare(params, light) sees the spectral phase: the light's spectra as numpy arrays (a detector
// prototype integrates them); evaluate() then finds the light's scalars among its inputs ("light.signal.scale", ...).

// A spectrum as {"wavelength_m", "value" (numpy, copies), "unit", "extrapolation"}, or None when empty.
py::object spectrum_dict(const Spectrum& s) {
  if (s.empty()) return py::none();
  py::dict d;
  d["wavelength_m"] = py::array_t<double>(s.size(), s.wavelength_m().data());
  d["value"] = py::array_t<double>(s.size(), s.value().data());
  d["unit"] = s.unit();
  d["extrapolation"] = s.extrapolation() == Extrapolation::zero ? "zero" : "clamp";
  return d;
}

// A radiation's form by the name light.hpp gives it, and the unit of spectrum × scale that the form implies (the
// spectrum's own unit string is the target's: the optics change the form and fold their factors into the scale).
py::object radiation_dict(const Radiation& r) {
  static const std::map<RadiationForm, std::pair<const char*, const char*>> forms = {
      {RadiationForm::pupil_irradiance, {"pupil_irradiance", "W m-2 m-1"}},
      {RadiationForm::scene_radiance, {"scene_radiance", "W m-2 sr-1 m-1"}},
      {RadiationForm::focal_power, {"focal_power", "W m-1"}},
      {RadiationForm::focal_irradiance, {"focal_irradiance", "W m-2 m-1"}},
  };
  const auto form = forms.find(r.form);
  if (form == forms.end() || r.spectrum.empty()) return py::none();
  py::dict d = spectrum_dict(r.spectrum);
  d["form"] = form->second.first;
  d["unit"] = form->second.second;
  return d;
}

// What a Python prepare() sees of the light (per unit scale: the scales are evaluate()'s inputs).
py::dict light_dict(const Light& light) {
  py::dict d;
  d["signal"] = radiation_dict(light.signal);
  d["background"] = radiation_dict(light.background);
  d["illumination"] = spectrum_dict(light.illumination);
  d["up_path_transmittance"] = spectrum_dict(light.up_path_transmittance);
  d["path_radiance"] = spectrum_dict(light.path_radiance);
  d["report_band_m"] = light.has_report_band() ? py::object(py::make_tuple(light.report_band_min_m, light.report_band_max_m))
                                               : py::none();
  return d;
}

struct PythonPlugin {
  std::string name, summary, reference;
  Schema schema;
  std::vector<std::pair<Term, std::string>> publishes;  // term, equation
  std::vector<Need> needs;
  py::object cls;
};

std::mutex python_plugins_mutex;
std::map<std::string, const PythonPlugin*> python_plugins;  // the latest registration under a name

// PluginInfo::schema is a plain function pointer: each registered name gets one of a fixed set.
constexpr std::size_t python_plugin_slots = 32;
std::array<const PythonPlugin*, python_plugin_slots> slot_plugins{};
template <std::size_t I>
const Schema& slot_schema() {
  std::lock_guard lock(python_plugins_mutex);
  return slot_plugins[I]->schema;
}
template <std::size_t... I>
constexpr std::array<const Schema& (*)(), sizeof...(I)> make_slot_schemas(std::index_sequence<I...>) {
  return {&slot_schema<I>...};
}
constexpr auto slot_schemas = make_slot_schemas(std::make_index_sequence<python_plugin_slots>());

class PythonStage final : public Stage {
 public:
  PythonStage(const Params& p, const PythonPlugin& plugin) : plugin_(plugin) {
    for (const ParamSpec& spec : plugin.schema)
      if (p.has(spec.key)) params_.emplace_back(spec.key, p.handle(spec.key));
    py::gil_scoped_acquire gil;
    instance_ = plugin.cls();
  }
  ~PythonStage() override {
    py::gil_scoped_acquire gil;
    instance_ = py::object();
  }
  void prepare(Context& c) override {
    inputs_.clear();
    outputs_.clear();
    {
      py::gil_scoped_acquire gil;
      if (py::hasattr(instance_, "prepare")) instance_.attr("prepare")(param_dict(), light_dict(c.light));
    }
    for (const Need& need : plugin_.needs) {
      const std::string name(need.term.name);
      if (!need.optional) inputs_.emplace_back(name, c.require(need.term));
      else if (auto id = c.find(need.term)) inputs_.emplace_back(name, *id);
    }
    for (const auto& [term, equation] : plugin_.publishes) outputs_.emplace_back(std::string(term.name), c.declare(term, equation));
  }
  void evaluate(Context& c) override {
    py::gil_scoped_acquire gil;
    py::dict inputs;
    for (const auto& [name, id] : inputs_) inputs[py::str(name)] = c.results.value(id);
    inputs["light.signal.scale"] = c.light.signal.scale;
    inputs["light.background.scale"] = c.light.background.scale;
    inputs["light.illumination.scale"] = c.light.illumination_scale;
    inputs["light.up_path.scale"] = c.light.up_path_scale;
    const py::dict values = instance_.attr("evaluate")(param_dict(), inputs);
    for (const auto& [name, id] : outputs_) {
      if (!values.contains(name))
        throw std::runtime_error(fmt::format("{} (Python stage \"{}\"): evaluate() returned no \"{}\"", c.section,
                                             plugin_.name, name));
      c.results.set(id, values[py::str(name)].cast<double>());
    }
  }

 private:
  py::dict param_dict() const {
    py::dict params;
    for (const auto& [key, handle] : params_) params[py::str(key)] = *handle;
    return params;
  }

  const PythonPlugin& plugin_;
  py::object instance_;
  std::vector<std::pair<std::string, const double*>> params_;
  std::vector<std::pair<std::string, ResultId>> inputs_, outputs_;
};

std::unique_ptr<Stage> create_python_stage(const Params& p) {
  const PythonPlugin* plugin = nullptr;
  {
    std::lock_guard lock(python_plugins_mutex);
    plugin = python_plugins.at(p.plugin());
  }
  return std::make_unique<PythonStage>(p, *plugin);
}

const Term& vocabulary_term(const std::string& name, const std::string& plugin) {
  for (const Term& t : vocabulary::all)
    if (t.name == name) return t;
  throw py::value_error(fmt::format("register_stage(\"{}\"): \"{}\" is not a vocabulary term (framework/core/include/"
                                    "radchain/vocabulary.hpp; a criterion's: \"criteria.*.margin\")", plugin, name));
}

// One parameter: (key, type "quantity" | "number" | "integer", SI unit, example as TOML text, default or None,
// required, min, max, min exclusive, max exclusive, doc, spectral: prepare() reads it, so a change re-runs it).
using PythonParam = std::tuple<std::string, std::string, std::string, std::string, std::optional<std::string>, bool,
                               double, double, bool, bool, std::string, bool>;

void register_stage(const std::string& kind_name, const std::string& name, const std::string& summary,
                    const std::string& reference, const std::vector<PythonParam>& params,
                    const std::vector<std::pair<std::string, std::string>>& publishes,
                    const std::vector<std::pair<std::string, bool>>& needs, const py::object& cls) {
  const std::optional<Kind> kind = kind_from_name(kind_name);
  if (!kind) throw py::value_error(fmt::format("register_stage(\"{}\"): \"{}\" is not a kind of stage", name, kind_name));
  auto plugin = std::make_unique<PythonPlugin>();
  plugin->name = name, plugin->summary = summary, plugin->reference = reference, plugin->cls = cls;
  for (const auto& [key, type, si_unit, example, fallback, required, min, max, min_exclusive, max_exclusive, doc, spectral] :
       params) {
    ParamSpec spec = type == "quantity" ? quantity(key, si_unit, example)
                     : type == "integer" ? integer(key, example)
                     : type == "number"  ? number(key, example)
                                         : throw py::value_error(fmt::format(
                                               "register_stage(\"{}\"): parameter {}: type \"{}\" is not quantity, number or integer",
                                               name, key, type));
    spec.default_value = fallback, spec.required = required, spec.min = min, spec.max = max;
    spec.min_exclusive = min_exclusive, spec.max_exclusive = max_exclusive, spec.doc = doc, spec.spectral = spectral;
    plugin->schema.push_back(std::move(spec));
  }
  for (const auto& [term, equation] : publishes) plugin->publishes.emplace_back(vocabulary_term(term, name), equation);
  for (const auto& [term, optional] : needs) plugin->needs.emplace_back(vocabulary_term(term, name), optional);
  for (const auto& file : PluginHost::instance().discover())
    if (file.name == name)
      throw py::value_error(fmt::format("register_stage(\"{}\"): a plugin library has that name ({})", name, file.path));

  std::lock_guard lock(python_plugins_mutex);
  auto slot = std::find(slot_plugins.begin(), slot_plugins.end(), python_plugins.count(name) ? python_plugins[name] : nullptr);
  if (slot == slot_plugins.end())
    throw py::value_error(fmt::format("register_stage(\"{}\"): at most {} stages written in Python", name, python_plugin_slots));
  const PythonPlugin* registered = plugin.release();  // never freed: chains built from it keep pointers into it
  *slot = registered;
  python_plugins[name] = registered;
  std::vector<Term> terms;
  for (const auto& [term, equation] : registered->publishes) terms.push_back(term);
  PluginHost::instance().add(PluginInfo{plugin_abi_version, framework_version, *kind, registered->name.c_str(),
                                        registered->summary.c_str(), registered->reference.c_str(),
                                        slot_schemas[static_cast<std::size_t>(slot - slot_plugins.begin())],
                                        &create_python_stage, std::move(terms), registered->needs, InverseForm::none});
}


}  // namespace

void bind_stages(py::module_& m) {
  m.def("register_stage", &register_stage);
}

}  // namespace radchain::python
