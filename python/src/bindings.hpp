#pragma once
// What the binding files of radchain._radchain share: module.cpp (the module, its exception and what it registers),
// session.cpp (reports, Session), jobs.cpp (describe, plugins, catalogue, sweeps, merge, budget, uncertainty,
// compare) and stages.cpp (stages written in Python). Each binds library types and converts; none decides physics.
#include "radchain/batch/session.hpp"
#include "radchain/chain.hpp"

#include <pybind11/pybind11.h>

#include <atomic>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace radchain::python {

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

inline std::vector<Override> to_overrides(const std::vector<std::pair<std::string, std::string>>& sets) {
  std::vector<Override> o;
  for (const auto& [k, v] : sets) o.push_back(Override{k, v});
  return o;
}

// The library's Session (radchain/batch/session.hpp) and what Python adds to it: one call at a time.
struct PySession {
  PySession(std::string path, std::optional<std::string> text, std::vector<Override> overrides)
      : session(std::move(path), std::move(text), std::move(overrides)) {}
  Session session;
  std::mutex mutex;  // one call at a time (the GIL is released while the chain works)
  std::atomic<std::thread::id> holder{};  // the thread inside a call: a Python stage calling back is refused
};

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

void configure(const std::vector<std::string>& explicit_dirs);  // the plugin search path (jobs.cpp)

void bind_session(py::module_& m);  // Report, Session, load, loads, check_sweep_size
void bind_jobs(py::module_& m);     // describe, plugins, configure, catalogue, sweep_table, merge, budget, uncertainty, compare, threads
void bind_stages(py::module_& m);   // register_stage

}  // namespace radchain::python
