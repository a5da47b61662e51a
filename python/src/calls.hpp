// What every binding shares: a call made without the GIL on a worker thread while the caller's
// thread watches for Ctrl-C, and topomill's errors raised as the package's Python exceptions.
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <functional>
#include <string>

namespace topomill {
struct ParameterValues;
}

namespace topomill::python {

namespace py = pybind11;

// The Python exception class an InputError becomes: "SceneError" for errors in a scene (its
// file, a set() or a model's parameter), "InputError" for the other inputs (files, options).
enum class ErrorKind { Scene, Input };

// Runs `work` on a worker thread with the GIL released. The calling thread wakes every few
// milliseconds to let Python handle signals: when Ctrl-C raises KeyboardInterrupt there, the
// work is asked to stop (as SIGINT asks the command line), waited for (within the 2 s every
// loop promises) and the KeyboardInterrupt propagates. An exception from the work is raised as
// its Python counterpart (raise_as_python).
void interruptible(const std::function<void()>& work, ErrorKind kind);

// Sets the Python error for a C++ exception (GIL held): InputError as topomill.SceneError or
// topomill.InputError (with file, line, column, key and message), PluginError as
// topomill.PluginError, Interrupted as KeyboardInterrupt. False for any other exception, which
// pybind11 then raises as its own (RuntimeError for std::exception).
bool set_python_error(std::exception_ptr error, ErrorKind kind);
// The same, thrown as py::error_already_set; any other exception rethrown unchanged.
[[noreturn]] void raise_as_python(std::exception_ptr error, ErrorKind kind);

// Runs `check`, code shared with the command line whose errors name its options
// ("--filter-s"), and names the Python keyword ("filter_s") and the call instead.
void with_python_names(const std::function<void()>& check, const std::string& call);

// A run's or a measurement's parameters as (name, value, unit, method) tuples, and the
// undefined ones as (name, why).
py::list reported_parameters(const ParameterValues& v);
py::list undefined_parameters(const ParameterValues& v);

void bind_scene(py::module_& m);
void bind_surface(py::module_& m);
void bind_catalog(py::module_& m);

}  // namespace topomill::python
