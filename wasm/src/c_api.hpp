#pragma once
// The C ABI between the wasm module and its JS wrapper (wasm/js/*.mjs). Functions that
// can fail return a status (0 = ok) or a null pointer and leave the message of the
// exception in last_error(); the wrapper turns it into a JS Error. Try blocks cost
// nothing here: the module is built with native wasm exceptions.
#include <exception>
#include <memory>
#include <string>

#include <emscripten/emscripten.h>
#include <nlohmann/json_fwd.hpp>

#include "achd/data.hpp"
#include "achd/model.hpp"

#define ACHD_EXPORT extern "C" EMSCRIPTEN_KEEPALIVE

namespace achd::wasm {

// A loaded robot: solvers share its model and simulators copy it, so deleting the robot
// first leaves them valid.
struct Robot {
  std::shared_ptr<const Model> model;
  std::string info;  // JSON description read once by the wrapper (names, limits, ...)
  // robot.solve (case_api.cpp): its outputs, made on first use, and its last result text.
  std::unique_ptr<Data> data;
  std::string result;
};

void set_last_error(const char* message);

// The JSON text of a case-shaped input written by the JS bridge (wasm/js/json_text.mjs),
// parsed, the values JSON cannot hold marked (foreign_values.hpp), for the case parser.
nlohmann::json json_from_bridge(const char* text);

// Runs f(); on an exception stores its message and returns 1.
template <typename F>
int guarded(F&& f) {
  try {
    f();
    return 0;
  } catch (const std::exception& e) {
    set_last_error(e.what());
  } catch (...) {
    set_last_error("unknown C++ exception");
  }
  return 1;
}

}  // namespace achd::wasm
