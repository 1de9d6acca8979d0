// radchain._radchain: the C++ side of `import radchain` (python/radchain/__init__.py is the Python side).
// Everything here is a thin binding of radchain::core and radchain::batch: a Session owns one Chain built from a
// sensor file (or its text) with overrides, exactly as `radchain run --set` builds it; sweeps go through
// PointsEvaluator (radchain/batch/points.hpp) with the GIL released, on all cores. This file makes the module and
// its exception; session.cpp, jobs.cpp and stages.cpp bind the rest (bindings.hpp).
#include "bindings.hpp"

#include "radchain/error.hpp"
#include "radchain/plugin.hpp"
#include "radchain/version.hpp"

namespace radchain::python {
namespace {

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

  bind_session(m);
  bind_jobs(m);
  bind_stages(m);
}
