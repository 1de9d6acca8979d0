// radchain._radchain: the C++ side of `import radchain` (python/radchain/__init__.py is the Python side).
// Everything here is a thin binding of radchain::core and radchain::batch: a Session owns one Chain built from a
// sensor file (or its text) with overrides, exactly as `radchain run --set` builds it; sweeps go through
// PointsEvaluator (radchain/batch/points.hpp) with the GIL released, on all cores.
#include "radchain/batch/budget.hpp"
#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/batch/compare.hpp"
#include "radchain/batch/describe.hpp"
#include "radchain/batch/points.hpp"
#include "radchain/batch/session.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/report.hpp"
#include "radchain/sensor_file.hpp"
#include "radchain/version.hpp"
#include "radchain/vocabulary.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace radchain::python {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// The Python exception type radchain.InputError (a ValueError), created at import.
PyObject* input_error_type = nullptr;

void raise_input_error(const InputError& e) {
  py::object type = py::reinterpret_borrow<py::object>(input_error_type);
  py::object error = type(e.what());
  const SourceLocation& w = e.where();
  auto or_none = [](const std::string& s) -> py::object { return s.empty() ? py::object(py::none()) : py::str(s); };
  error.attr("file") = or_none(w.file);
  error.attr("line") = w.line > 0 ? py::object(py::int_(w.line)) : py::object(py::none());
  error.attr("column") = w.column > 0 ? py::object(py::int_(w.column)) : py::object(py::none());
  error.attr("context") = or_none(e.context());
  error.attr("subject") = or_none(e.subject());
  error.attr("problem") = or_none(e.problem());
  PyErr_SetObject(input_error_type, error.ptr());
}

// --- reports ---------------------------------------------------------------------------------------------------

py::dict solve_dict(const SolveOutcome& s) {
  py::dict d;
  d["unknown"] = s.spec.unknown;
  d["criteria"] = s.spec.criteria;
  d["binding"] = s.binding;
  d["value_si"] = s.value_si;
  d["converged"] = s.converged;
  d["evaluations"] = s.iterations;
  d["message"] = s.message;
  py::dict roots;
  for (const auto& [name, value] : s.roots) roots[py::str(name)] = value;
  d["roots"] = roots;
  d["bracket_si"] = py::make_tuple(s.spec.lo, s.spec.hi);
  return d;
}

py::dict expectation_dict(const ExpectationOutcome& e) {
  py::dict d;
  d["result"] = e.spec.result;
  d["printed"] = e.spec.as_written;
  d["printed_si"] = e.spec.value_si;
  d["follows_si"] = e.spec.follows_si ? py::object(py::float_(*e.spec.follows_si)) : py::object(py::none());
  d["computed_si"] = e.found ? e.computed_si : nan;
  d["tolerance_si"] = e.spec.tolerance_si;
  d["rel_tolerance"] = e.spec.rel_tolerance;
  d["passed"] = e.passed;
  d["source"] = e.spec.source;
  return d;
}

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// --- Session -----------------------------------------------------------------------------------------------------

// The limits of `radchain sweep` (--allow-large) for Session.sweep: hours of work and gigabytes should be asked for.
void check_sweep_size(double points, bool allow_large) {
  if (points > SweepOptions::max_points)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", fmt::format("{:.0f} points", points),
                     fmt::format("more than {:g} points: split the job (radchain.dask.sweep shards it)", SweepOptions::max_points));
  if (points > SweepOptions::large_points && !allow_large)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", fmt::format("{:.0f} points", points),
                     fmt::format("more than {:g} points: pass allow_large=True if that is meant", SweepOptions::large_points));
}

// The library's Session (radchain/batch/session.hpp) and what Python adds to it: one call at a time.
struct PySession {
  PySession(std::string path, std::optional<std::string> text, std::vector<Override> overrides)
      : session(std::move(path), std::move(text), std::move(overrides)) {}
  Session session;
  std::mutex mutex;  // one call at a time (the GIL is released while the chain works)
  std::atomic<std::thread::id> holder{};  // the thread inside a call: a Python stage calling back is refused
};

// Points: values[p] is parameter p at every point (SI). Returns (result names, SI units, out[r][i], ok[i],
// failed count, first failure).
py::tuple sweep_points(Session& session, const std::vector<std::string>& keys,
                       const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& arrays,
                       const std::vector<std::string>& results, bool no_solve, bool allow_large) {
  if (keys.size() != arrays.size()) throw std::invalid_argument("sweep: one array per parameter");
  std::size_t count = 0;
  for (std::size_t p = 0; p < arrays.size(); ++p) {
    if (arrays[p].ndim() != 1) throw std::invalid_argument("sweep: 1-D arrays expected");
    const auto n = static_cast<std::size_t>(arrays[p].shape(0));
    if (p == 0) count = n;
    else if (n != count) throw std::invalid_argument("sweep: arrays of different lengths");
  }
  check_sweep_size(static_cast<double>(count), allow_large);
  // The values are copied (block by block, below) before they are checked: the caller's arrays may be changed by
  // another thread while the GIL is released, and a value must not change between its check and its use.
  std::vector<std::unique_ptr<double[]>> pinned;
  std::vector<const double*> values;
  for (std::size_t p = 0; p < arrays.size(); ++p) {
    pinned.emplace_back(new double[count]);  // (not zeroed: every value is copied before it is read)
    values.push_back(pinned.back().get());
  }
  PointsEvaluator* evaluator = nullptr;
  {
    py::gil_scoped_release release;
    evaluator = &session.points(keys, results, no_solve);
  }
  const std::size_t n_results = evaluator->results().size();
  py::array_t<double> out({static_cast<py::ssize_t>(n_results), static_cast<py::ssize_t>(count)});
  py::array_t<bool> ok(static_cast<py::ssize_t>(count));
  double* out_data = out.mutable_data();
  char* ok_data = reinterpret_cast<char*>(ok.mutable_data());
  std::string failure;
  std::size_t failed = 0;
  // In blocks, with Python's signal check between them: Ctrl-C (KeyboardInterrupt) stops a long sweep within a
  // block's time (2^18 points: ~0.1 s of solves on 2 cores), and the partial arrays are dropped with the exception.
  // Each block's values are copied (with the GIL held: no Python thread writes meanwhile) and checked before it runs.
  constexpr std::size_t block = std::size_t{1} << 18;
  for (std::size_t begin = 0; begin < count; begin += block) {
    const std::size_t end = std::min(count, begin + block);
    for (std::size_t p = 0; p < arrays.size(); ++p)
      std::copy(arrays[p].data() + begin, arrays[p].data() + end, pinned[p].get() + begin);
    std::string block_failure;
    {
      py::gil_scoped_release release;
      evaluator->check(values.data(), begin, end);
      failed += evaluator->run_range(values.data(), count, begin, end, out_data, ok_data, &block_failure);
    }
    if (failure.empty()) failure = block_failure;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return py::make_tuple(evaluator->results(), evaluator->result_units(), out, ok, failed, failure);
}

// One call's hold on its session. The mutex is taken with the GIL released, so that a thread waiting for it never
// holds the GIL that the thread holding it may need. A Python stage of the session's chain that calls back into the
// session (its own thread holds the mutex) would wait for ever: refused instead.
class SessionCall {
 public:
  explicit SessionCall(PySession& s) : s_(s), lock_(s.mutex, std::defer_lock) {
    if (s.holder.load() == std::this_thread::get_id())
      throw std::runtime_error("this Session is busy with a call that is still running (a Python stage called back "
                               "into its own session): use another Session (radchain.load) inside a stage");
    {
      py::gil_scoped_release release;
      lock_.lock();
    }
    s.holder = std::this_thread::get_id();
  }
  ~SessionCall() { s_.holder = std::thread::id{}; }
  SessionCall(const SessionCall&) = delete;
  SessionCall& operator=(const SessionCall&) = delete;

 private:
  PySession& s_;
  std::unique_lock<std::mutex> lock_;
};

// Calls f() with the session held (SessionCall) and the GIL held.
template <class F>
auto locked(PySession& s, F&& f) {
  const SessionCall call(s);
  return f();
}

std::vector<Override> to_overrides(const std::vector<std::pair<std::string, std::string>>& sets) {
  std::vector<Override> o;
  for (const auto& [k, v] : sets) o.push_back(Override{k, v});
  return o;
}

// --- describe: the library's model (radchain/batch/describe.hpp) as dicts ----------------------------------------

py::dict describe_as_dict(const std::string& name) {
  const Description d = radchain::describe(name);
  auto keys = [](const std::vector<KeyDescription>& list) {
    py::list out;
    for (const KeyDescription& k : list)
      out.append(py::dict("key"_a = k.key, "type"_a = k.type, "si_unit"_a = k.si_unit, "shape"_a = k.shape,
                          "required"_a = k.required, "default"_a = k.default_value, "example"_a = k.example, "doc"_a = k.doc,
                          "accepted"_a = k.accepted, "formerly"_a = k.formerly, "spectral"_a = k.spectral));
    return out;
  };
  auto terms = [](const std::vector<TermDescription>& list, bool with_optional) {
    py::list out;
    for (const TermDescription& t : list) {
      py::dict term("name"_a = t.name, "unit"_a = t.unit, "meaning"_a = t.meaning);
      if (with_optional) term["optional"] = t.optional;
      out.append(term);
    }
    return out;
  };
  py::dict out("what"_a = to_string(d.what), "name"_a = d.name, "title"_a = d.title);
  switch (d.what) {
    case Description::What::plugin:
      out["kind"] = d.kind, out["summary"] = d.summary, out["reference"] = d.reference, out["file"] = d.file;
      out["framework_version"] = d.framework_version, out["abi_version"] = d.abi_version;
      out["keys"] = keys(d.keys), out["publishes"] = terms(d.publishes, false), out["needs"] = terms(d.needs, true);
      out["example"] = d.example;
      break;
    case Description::What::kind: {
      py::list plugins;
      for (const PluginSummary& p : d.plugins) plugins.append(py::dict("name"_a = p.name, "summary"_a = p.summary, "file"_a = p.file));
      out["section"] = d.section, out["plugins"] = plugins;
      break;
    }
    case Description::What::table:
    case Description::What::command:
      out["keys"] = keys(d.keys), out["example"] = d.example;
      break;
  }
  return out;
}

py::list plugins() {
  py::list out;
  for (const auto& f : PluginHost::instance().discover()) {
    py::dict p;
    p["name"] = f.name;
    p["kind"] = std::string(to_string(f.kind));
    p["file"] = f.path;
    try {
      const PluginInfo& info = PluginHost::instance().load_file(f.path);
      p["version"] = std::string(info.framework_version);
      p["summary"] = std::string(info.summary);
      p["usable"] = true;
      p["problem"] = "";
    } catch (const InputError& error) {
      p["version"] = "";
      p["summary"] = "";
      p["usable"] = false;
      p["problem"] = error.problem();
    }
    out.append(p);
  }
  return out;
}

// The plugin search path: `explicit_dirs`, then RADCHAIN_PLUGIN_PATH, then the plugins that belong with this module:
// the build tree's when it is the build tree's module, else the prefix's it is installed in (lib/radchain/plugins
// relative to lib/python3/dist-packages/radchain), then the configured install prefix (PluginHost).
void configure(const std::vector<std::string>& explicit_dirs) {
  namespace fs = std::filesystem;
  std::vector<std::string> dirs = explicit_dirs;
  if (const char* env = std::getenv("RADCHAIN_PLUGIN_PATH")) dirs.emplace_back(env);
  std::error_code ec;
  const fs::path here = boost::dll::this_line_location(ec).parent_path();
  if (!ec) {
    std::error_code same_ec;
    if (fs::equivalent(here, RADCHAIN_PY_BUILD_MODULE_DIR, same_ec))
      dirs.emplace_back(RADCHAIN_PY_BUILD_PLUGIN_DIR);
    else
      dirs.push_back((here / RADCHAIN_PY_INSTALLED_PLUGIN_DIR).lexically_normal().string());
  }
  PluginHost::instance().configure(dirs);
}

// --- catalogue and compare ---------------------------------------------------------------------------------------

// `shard` "k/n" (with `order`, as --shard and --shard-order) makes the table a shard file of the JSON job, for
// merge() (radchain.dask runs one per task); "" is the whole job.
ShardSpec shard_of(const std::string& shard, const std::string& order) {
  return shard.empty() ? ShardSpec{} : parse_shard(shard, order);
}

py::tuple catalogue(const std::vector<std::string>& inputs, const std::vector<std::pair<std::string, std::string>>& sets,
                    const std::vector<std::string>& results, bool no_solve, const std::string& shard,
                    const std::string& order) {
  std::ostringstream out;
  std::vector<std::string> errors;
  int code = 0;
  {
    py::gil_scoped_release release;
    const std::vector<std::string> files = catalogue_files(inputs);
    CatalogueOptions options;
    options.overrides = to_overrides(sets);
    options.extra_results = results;
    options.no_solve = no_solve;
    options.shard = shard_of(shard, order);
    TableWriter writer(out, TableFormat::json, catalogue_layout(), files.size(), options.shard,
                       catalogue_job(files, options));
    code = run_catalogue(files, options, writer, &errors);
    writer.finish(code);
  }
  return py::make_tuple(out.str(), errors, code);
}

// --- grid sweeps and merge (radchain.dask): `radchain sweep` and `radchain merge` with their outputs in memory --------

// `radchain sweep path --set k=v … --set axis=from:to:steps … --results … [--no-solve] --format F [--shard k/n]`:
// the table's bytes (a shard file when sharded), the first failing point's message ("" if none), the exit code and
// how the points were solved (Sweep::method(), what --explain prints).
py::tuple sweep_table(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
                      const std::vector<std::pair<std::string, std::string>>& axes, const std::vector<std::string>& results,
                      bool no_solve, const std::string& format, const std::string& shard, const std::string& order,
                      bool allow_large) {
  std::ostringstream out;
  std::string failure, method;
  int code = 0;
  {
    py::gil_scoped_release release;
    SweepOptions options;
    options.sensor_file = path;
    options.overrides = to_overrides(sets);
    options.axes = axes;
    options.results = results;
    options.no_solve = no_solve;
    options.shard = shard_of(shard, order);
    options.allow_large = allow_large;
    Sweep sweep(options);
    TableWriter writer(out, parse_table_format(format), sweep.layout(), sweep.points(), options.shard, sweep.job());
    code = sweep.run(writer, &failure);
    writer.finish(code);
    method = sweep.method();
  }
  return py::make_tuple(py::bytes(out.str()), failure, code, method);
}

// `radchain merge files… --format F`: the unsharded job's bytes and its exit code.
py::tuple merge(const std::vector<std::string>& files, const std::string& format) {
  std::ostringstream out;
  int code = 0;
  {
    py::gil_scoped_release release;
    code = merge_shards(files, out, parse_table_format(format));
  }
  return py::make_tuple(py::bytes(out.str()), code);
}

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

// --- budget and uncertainty: the library's tables (TableData) with their numbers as they are -------------------

// {"columns": [...], "data": {column: float64 array (numeric columns) or list of str}}, for a DataFrame.
py::dict table_dict(const TableData& table) {
  py::dict data;
  for (std::size_t c = 0; c < table.layout.columns.size(); ++c) {
    if (table.layout.numeric[c]) {
      py::array_t<double> column(static_cast<py::ssize_t>(table.rows.size()));
      double* out = column.mutable_data();
      for (const auto& row : table.rows) *out++ = std::get<double>(row[c]);
      data[py::str(table.layout.columns[c])] = column;
    } else {
      py::list column;
      for (const auto& row : table.rows) column.append(std::get<std::string>(row[c]));
      data[py::str(table.layout.columns[c])] = column;
    }
  }
  return py::dict("columns"_a = table.layout.columns, "data"_a = data);
}

py::dict budget(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
                const std::vector<std::string>& results, bool no_solve) {
  TableData table;
  {
    py::gil_scoped_release release;
    Chain chain = load_sensor(path, to_overrides(sets), no_solve ? Solving::forward_only : Solving::as_written);
    BudgetOptions options;
    options.results = results;
    table = budget_table(compute_budget(chain, options));
  }
  return table_dict(table);
}

py::dict uncertainty(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
                     const std::vector<std::string>& vary, const std::vector<std::string>& results, std::size_t samples,
                     std::uint64_t seed, bool no_solve) {
  TableData table;
  {
    py::gil_scoped_release release;
    UncertaintyOptions options;
    options.sensor_file = path;
    options.overrides = to_overrides(sets);
    options.vary = vary;
    options.results = results;
    options.samples = samples;
    options.seed = seed;
    options.no_solve = no_solve;
    table = uncertainty_table(run_uncertainty(options));
  }
  return table_dict(table);
}

CompareInput compare_input(const py::object& x, const std::vector<Override>& overrides, bool solve) {
  if (py::isinstance<PySession>(x)) {
    PySession& s = x.cast<PySession&>();
    return locked(s, [&] {
      py::gil_scoped_release release;
      return s.session.compare_input(solve);
    });
  }
  const std::string path = x.cast<std::string>();
  py::gil_scoped_release release;
  return load_compare_input(path, overrides, solve);
}

py::list compare(const py::object& a, const py::object& b, const std::vector<std::pair<std::string, std::string>>& sets,
                 bool solve, std::optional<double> tolerance) {
  const std::vector<Override> overrides = to_overrides(sets);
  const CompareInput ia = compare_input(a, overrides, solve);
  const CompareInput ib = compare_input(b, overrides, solve);
  const Comparison c = radchain::compare(ia, ib);
  py::list rows;
  for (const auto& d : c.inputs) {
    py::dict r;
    r["kind"] = "input";
    r["name"] = d.name;
    r["a"] = d.a;
    r["b"] = d.b;
    r["unit"] = d.unit;
    r["a_value"] = d.a_value;
    r["b_value"] = d.b_value;
    r["a_si"] = d.a_si;
    r["b_si"] = d.b_si;
    r["si_unit"] = d.si_unit;
    r["delta"] = d.b_value - d.a_value;
    r["delta_pct"] = d.a_si != 0 ? 100 * (d.b_si - d.a_si) / std::abs(d.a_si) : nan;
    r["status"] = "differs";
    rows.append(r);
  }
  for (const auto& d : c.results) {
    py::dict r;
    r["kind"] = "result";
    r["name"] = d.name;
    r["a"] = d.in_a ? number_cell(d.a_si * d.factor) : std::string();
    r["b"] = d.in_b ? number_cell(d.b_si * d.factor) : std::string();
    r["unit"] = d.unit == "1" ? std::string() : d.unit;
    r["a_value"] = d.in_a ? d.a_si * d.factor : nan;
    r["b_value"] = d.in_b ? d.b_si * d.factor : nan;
    r["a_si"] = d.in_a ? d.a_si : nan;
    r["b_si"] = d.in_b ? d.b_si : nan;
    r["si_unit"] = "";
    r["delta"] = d.in_a && d.in_b ? d.delta() : nan;
    r["delta_pct"] = d.in_a && d.in_b ? 100 * d.relative() : nan;
    r["status"] = d.status(tolerance);
    rows.append(r);
  }
  return rows;
}

}  // namespace
}  // namespace radchain::python

PYBIND11_MODULE(_radchain, m) {
  using namespace radchain;
  using namespace radchain::python;
  m.doc() = "radchain: radiometry of electro-optical sensors (C++ core; see radchain/__init__.py)";

  input_error_type = PyErr_NewExceptionWithDoc(
      "radchain.InputError",
      "Bad input (a sensor file, an override, a parameter value): the one-line located message of the command line.\n"
      "Fields: file, line, column (None when unknown), context, subject, problem.",
      PyExc_ValueError, nullptr);
  m.attr("InputError") = py::reinterpret_borrow<py::object>(input_error_type);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      raise_input_error(e);
    }
  });

  configure({});
  m.attr("framework_version") = framework_version;
  m.attr("plugin_abi_version") = plugin_abi_version;

  py::class_<Report>(m, "Report")
      .def_property_readonly("sensor", [](const Report& r) { return r.sensor_name; })
      .def_property_readonly("file", [](const Report& r) { return r.sensor_file; })
      .def_property_readonly("names", [](const Report& r) {
        std::vector<std::string> v;
        for (const auto& i : r.results) v.push_back(i.name);
        return v;
      })
      .def_property_readonly("values_si", [](const Report& r) { return to_array(r.values); })
      .def_property_readonly("si_units", [](const Report& r) {
        std::vector<std::string> v;
        for (const auto& i : r.results) v.push_back(i.si_unit);
        return v;
      })
      .def_property_readonly("units", [](const Report& r) {
        std::vector<std::string> v;
        for (const auto& i : r.results) v.push_back(i.display_unit);
        return v;
      })
      .def_property_readonly("values", [](const Report& r) {
        std::vector<double> v;
        for (std::size_t i = 0; i < r.results.size(); ++i) v.push_back(r.values[i] * r.results[i].display_factor);
        return to_array(v);
      })
      .def_property_readonly("stages", [](const Report& r) {
        std::vector<std::string> v;
        for (const auto& i : r.results) v.push_back(i.stage);
        return v;
      })
      .def_property_readonly("equations", [](const Report& r) {
        std::vector<std::string> v;
        for (const auto& i : r.results) v.push_back(i.equation);
        return v;
      })
      .def_property_readonly("solves", [](const Report& r) {
        py::list l;
        for (const auto& s : r.solves) l.append(solve_dict(s));
        return l;
      })
      .def_property_readonly("expected", [](const Report& r) {
        py::list l;
        for (const auto& e : r.expectations) l.append(expectation_dict(e));
        return l;
      })
      .def_property_readonly("passed", &Report::all_passed)
      .def("json", &format_report_json, "the report as `radchain run --format json` prints it")
      .def("text", &format_report_text, "the report as `radchain run` prints it")
      .def("display", [](const Report& r, std::size_t i) { return format_value(r.values.at(i), r.results.at(i)); });

  py::class_<PySession>(m, "Session")
      .def_property_readonly("path", [](const PySession& s) { return s.session.path(); })
      .def_property_readonly("sensor", [](const PySession& s) { return s.session.sensor_name(); })
      .def_property_readonly("description", [](const PySession& s) { return s.session.description(); })
      .def_property_readonly("solved", [](const PySession& s) { return s.session.solved(); })
      .def_property_readonly("overrides", [](const PySession& s) {
        std::vector<std::pair<std::string, std::string>> o;
        for (const auto& x : s.session.overrides()) o.emplace_back(x.key, x.value);
        return o;
      })
      .def_property_readonly("si_values", [](const PySession& s) { return s.session.si_values(); })
      .def("set_text", [](PySession& s, const std::string& key, const std::string& value) {
        const SessionCall call(s);
        py::gil_scoped_release release;
        s.session.set_text(key, value);
      })
      .def("set_si", [](PySession& s, const std::string& key, double value) {
        locked(s, [&] { s.session.set_si(key, value); });
      })
      .def("get", [](PySession& s, const std::string& key) { return locked(s, [&] { return s.session.get(key); }); })
      .def("si_unit", [](PySession& s, const std::string& key) { return locked(s, [&] { return s.session.si_unit(key); }); })
      .def("run", [](PySession& s) {
        const SessionCall call(s);
        py::gil_scoped_release release;
        return s.session.run();
      })
      .def("evaluate", [](PySession& s) {
        const SessionCall call(s);
        py::gil_scoped_release release;
        return s.session.run(Solving::forward_only);
      })
      .def("value", [](PySession& s, const std::string& name) {
        return locked(s, [&] {
          if (!s.session.has_result(name)) throw py::key_error(name + ": " + s.session.no_such_result(name));
          return s.session.value(name);
        });
      })
      .def("sweep", [](PySession& s, const std::vector<std::string>& keys,
                       const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& arrays,
                       const std::vector<std::string>& results, bool no_solve, bool allow_large) {
        return locked(s, [&] { return sweep_points(s.session, keys, arrays, results, no_solve, allow_large); });
      });

  m.def("load", [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets) {
    py::gil_scoped_release release;
    return std::make_unique<PySession>(path, std::nullopt, to_overrides(sets));
  });
  m.def("loads", [](const std::string& text, const std::string& name, const std::vector<std::pair<std::string, std::string>>& sets) {
    py::gil_scoped_release release;
    return std::make_unique<PySession>(name, text, to_overrides(sets));
  });
  m.def("describe", &describe_as_dict);
  m.def("plugins", &plugins);
  m.def("configure", &configure, py::arg("plugin_path") = std::vector<std::string>{});
  m.def("search_path", [] { return PluginHost::instance().search_path(); });
  m.def("catalogue", &catalogue, py::arg("inputs"), py::arg("sets"), py::arg("results"), py::arg("no_solve"),
        py::arg("shard") = "", py::arg("order") = "block");
  m.def("sweep_table", &sweep_table);
  m.def("check_sweep_size", &check_sweep_size);
  m.def("register_stage", &register_stage);
  m.def("merge", &merge);
  m.def("budget", &budget);
  m.def("uncertainty", &uncertainty);
  m.def("compare", static_cast<py::list (*)(const py::object&, const py::object&, const std::vector<std::pair<std::string, std::string>>&, bool, std::optional<double>)>(&radchain::python::compare));
  m.def("set_threads", [](std::size_t n) { limit_threads(n); });
  m.def("threads", [] { return thread_count(); });
}
