// radchain._radchain's reports and sessions: Report as Python reads it, and the library's Session
// (radchain/batch/session.hpp) with one call at a time and sweeps over numpy arrays.
#include "bindings.hpp"

#include "radchain/batch/points.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/error.hpp"
#include "radchain/report.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>

namespace radchain::python {
namespace {

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



// The limits of `radchain sweep` (--allow-large) for Session.sweep: hours of work and gigabytes should be asked for.
void check_sweep_size(double points, bool allow_large) {
  if (points > SweepOptions::max_points)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", fmt::format("{:.0f} points", points),
                     fmt::format("more than {:g} points: split the job (radchain.dask.sweep shards it)", SweepOptions::max_points));
  if (points > SweepOptions::large_points && !allow_large)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", fmt::format("{:.0f} points", points),
                     fmt::format("more than {:g} points: pass allow_large=True if that is meant", SweepOptions::large_points));
}

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


}  // namespace

void bind_session(py::module_& m) {
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
  m.def("check_sweep_size", &check_sweep_size);
}

}  // namespace radchain::python
