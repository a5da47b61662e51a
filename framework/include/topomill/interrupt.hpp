// Stopping on request, as a model sees it: the host turns SIGINT, SIGTERM and SIGHUP into a
// request that every long loop honours within 2 s, by calling throw_if_interrupted() (or reading
// stop_requested()) every so often. A model's constructor that reads or parses a large file
// calls it too; evaluators have EvaluationRequest::stop, path models PathRequest::stop.
#pragma once

#include <stdexcept>
#include <string>

#include "topomill/export.hpp"

namespace topomill {

// Thrown at a check after a stop request; names the signal. Let it pass: the host ends the run
// with it (exit 128 + the signal), writing nothing.
class TOPOMILL_API Interrupted : public std::runtime_error {
 public:
  Interrupted();
  explicit Interrupted(const std::string& what) : std::runtime_error(what) {}
  ~Interrupted() override;
};

// Whether a stop was requested.
TOPOMILL_API bool stop_requested();

// Throws Interrupted if a stop was requested.
TOPOMILL_API void throw_if_interrupted();

}  // namespace topomill
