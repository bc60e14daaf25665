#pragma once
// urdfdom and kdl_parser log through console_bridge, whose output handler is process-wide.
// While a ConsoleCapture lives, their messages come here instead of stderr, and the first
// error is kept so that a failed parse can say why. (Callers that may run concurrently
// serialise around it: the handler is global.)
#include <string>

#include <console_bridge/console.h>

namespace achd {

class ConsoleCapture : public console_bridge::OutputHandler {
 public:
  ConsoleCapture() { console_bridge::useOutputHandler(this); }
  ~ConsoleCapture() override { console_bridge::restorePreviousOutputHandler(); }
  ConsoleCapture(const ConsoleCapture&) = delete;
  ConsoleCapture& operator=(const ConsoleCapture&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error_.empty()) first_error_ = text;
  }
  const std::string& first_error() const { return first_error_; }

 private:
  std::string first_error_;
};

}  // namespace achd
