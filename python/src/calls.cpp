#include "calls.hpp"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "interrupt.hpp"
#include "metrology/parameters.hpp"
#include "topomill/error.hpp"

namespace topomill::python {

namespace {
// How often the waiting thread looks for a signal: far inside the 2 s a stop may take.
constexpr auto kSignalPoll = std::chrono::milliseconds(20);

py::object error_class(const char* name) {
  return py::module_::import("topomill._errors").attr(name);
}
}  // namespace

bool set_python_error(std::exception_ptr error, ErrorKind kind) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    const py::object cls = error_class(kind == ErrorKind::Scene ? "SceneError" : "InputError");
    const SourceRef& w = e.where();
    const py::object value = cls(e.what(), w.file, w.line, w.column, e.key(), e.message());
    PyErr_SetObject(cls.ptr(), value.ptr());
  } catch (const PluginError& e) {
    const py::object cls = error_class("PluginError");
    PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
  } catch (const Interrupted& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  } catch (...) {
    return false;
  }
  return true;
}

void raise_as_python(std::exception_ptr error, ErrorKind kind) {
  if (set_python_error(error, kind)) throw py::error_already_set();
  std::rethrow_exception(error);
}

// Runs `check`, whose errors name the command line's options ("--filter-s"), and names the
// keyword ("filter_s") and the call instead.
void with_python_names(const std::function<void()>& check, const std::string& call) {
  try {
    check();
  } catch (const InputError& e) {
    if (e.where().file != "command line") throw;
    std::string key = e.key();
    if (key.rfind("--", 0) == 0) key = key.substr(2);
    for (char& c : key)
      if (c == '-') c = '_';
    throw InputError(SourceRef{call}, key, e.message());
  }
}

py::list reported_parameters(const ParameterValues& v) {
  py::list out;
  for (const auto& p : v.reported) out.append(py::make_tuple(p.name, p.value, p.unit, p.method));
  return out;
}

py::list undefined_parameters(const ParameterValues& v) {
  py::list out;
  for (const auto& [name, why] : v.undefined) out.append(py::make_tuple(name, why));
  return out;
}

void interruptible(const std::function<void()>& work, ErrorKind kind) {
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    done = true;
    finished.notify_all();
  });
  bool interrupted = false;
  for (;;) {
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex);
      if (finished.wait_for(lock, kSignalPoll, [&] { return done; })) break;
    }
    if (PyErr_CheckSignals() != 0) {  // a Python exception is now set: KeyboardInterrupt
      interrupted = true;
      request_stop();
      break;
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (interrupted) {
    clear_stop();  // the process goes on: its next run starts afresh
    throw py::error_already_set();
  }
  if (error) raise_as_python(error, kind);
}

}  // namespace topomill::python
