// radchain._radchain's jobs: describe, the plugins, catalogue, grid sweeps and merge, budget, uncertainty and
// compare — each one library call, its answer converted (typed tables as float64 columns, models as dicts).
#include "bindings.hpp"

#include "radchain/batch/budget.hpp"
#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/compare.hpp"
#include "radchain/batch/describe.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/sensor_file.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <streambuf>

using namespace pybind11::literals;

namespace radchain::python {
namespace {

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

}  // namespace

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


namespace {

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

// An output stream into a string reserved once: a 10⁶-point .npy is 32 MB, and an ostringstream growing by
// doubling copied it several times and faulted in every new page (most of radchain.grid's time over the CLI's).
class StringSink : public std::streambuf {
 public:
  explicit StringSink(std::size_t reserve) { text_.reserve(reserve); }
  std::string& text() { return text_; }

 protected:
  int overflow(int c) override {
    if (c != traits_type::eof()) text_.push_back(static_cast<char>(c));
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    text_.append(s, static_cast<std::size_t>(n));
    return n;
  }

 private:
  std::string text_;
};

// `radchain sweep path --set k=v … --set axis=from:to:steps … --results … [--no-solve] --format F [--shard k/n]`:
// the table's bytes (a shard file when sharded), the first failing point's message ("" if none), the exit code,
// how the points were solved (Sweep::method(), what --explain prints) and each column's unit. si_columns: the
// columns in SI under their bare names (radchain.grid, radchain.dask.sweep), as Session.sweep gives them.
py::tuple sweep_table(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
                      const std::vector<std::pair<std::string, std::string>>& axes, const std::vector<std::string>& results,
                      bool no_solve, const std::string& format, const std::string& shard, const std::string& order,
                      bool allow_large, bool si_columns) {
  std::unique_ptr<StringSink> sink;
  std::string failure, method;
  std::vector<std::string> units;
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
    options.si_columns = si_columns;
    Sweep sweep(options);
    units = sweep.column_units();
    const TableFormat table_format = parse_table_format(format);
    // (An .npy is its header and 8 bytes a cell; a text format's size is not known: grown as it comes.)
    const std::size_t cells = sweep.points() * sweep.columns();
    sink = std::make_unique<StringSink>(table_format == TableFormat::npy && cells < (std::size_t{1} << 32) ? 8 * cells + 65536 : 0);
    std::ostream out(sink.get());
    TableWriter writer(out, table_format, sweep.layout(), sweep.points(), options.shard, sweep.job());
    code = sweep.run(writer, &failure);
    writer.finish(code);
    method = sweep.method();
  }
  return py::make_tuple(py::bytes(sink->text()), failure, code, method, units);
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

void bind_jobs(py::module_& m) {
  m.def("describe", &describe_as_dict);
  m.def("plugins", &plugins);
  m.def("configure", &configure, py::arg("plugin_path") = std::vector<std::string>{});
  m.def("search_path", [] { return PluginHost::instance().search_path(); });
  m.def("catalogue", &catalogue, py::arg("inputs"), py::arg("sets"), py::arg("results"), py::arg("no_solve"),
        py::arg("shard") = "", py::arg("order") = "block");
  m.def("sweep_table", &sweep_table);
  m.def("merge", &merge);
  m.def("budget", &budget);
  m.def("uncertainty", &uncertainty);
  m.def("compare", static_cast<py::list (*)(const py::object&, const py::object&, const std::vector<std::pair<std::string, std::string>>&, bool, std::optional<double>)>(&radchain::python::compare));
  m.def("set_threads", [](std::size_t n) { limit_threads(n); });
  m.def("threads", [] { return thread_count(); });
}

}  // namespace radchain::python
