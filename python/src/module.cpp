// topomill._topomill: the compiled half of the Python package (python/topomill/ is the other:
// the classes users hold, which call these functions).
#include "calls.hpp"
#include "log.hpp"
#include "topomill/version.hpp"

PYBIND11_MODULE(_topomill, m) {
  namespace tp = topomill::python;
  m.doc() = "topomill's core, bound for the topomill package";
  m.attr("version") = topomill::kVersion;
  m.attr("abi") = topomill::kAbiVersion;
  // Errors escaping a call outside interruptible(): bad arguments found before the work starts.
  pybind11::register_exception_translator([](std::exception_ptr error) {
    if (error && !tp::set_python_error(error, tp::ErrorKind::Input)) std::rethrow_exception(error);
  });
  // A library speaks when asked: warnings and errors only, unless the caller wants more.
  topomill::set_log_level(topomill::LogLevel::Quiet);
  m.def("set_log_level",
        [](int level) { topomill::set_log_level(static_cast<topomill::LogLevel>(level)); });
  tp::bind_scene(m);
  tp::bind_surface(m);
  tp::bind_catalog(m);
}
