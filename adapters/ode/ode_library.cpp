#include "adapters/ode/ode_library.h"

#include <ode/ode.h>

#include <cstdarg>
#include <cstdio>
#include <stdexcept>

namespace ib::ode {
namespace {

thread_local MessageLog* current_log = nullptr;

std::string format(const char* format_text, va_list args) {
  char text[1024];
  std::vsnprintf(text, sizeof text, format_text, args);
  return text;
}

// dError and dDebug: ODE aborts when the handler returns; say what happened first, where the suite's
// job log (stderr) keeps it.
void report_fatal(const char* kind, int number, const char* message, va_list args) {
  std::fprintf(stderr, "ODE %s %d: %s\n", kind, number, format(message, args).c_str());
  std::fflush(stderr);
}
void on_error(int number, const char* message, va_list args) { report_fatal("error", number, message, args); }
void on_debug(int number, const char* message, va_list args) { report_fatal("internal error", number, message, args); }

// dMessage: a warning (e.g. the LCP solver's "s <= 0"); ODE goes on. Echoed to stderr (the job's log)
// as long as the run's log keeps them, so that a warning every step cannot flood it.
void on_message(int number, const char* message, va_list args) {
  std::string text = "ODE message " + std::to_string(number) + ": " + format(message, args);
  if (!current_log || current_log->add(text)) std::fprintf(stderr, "%s\n", text.c_str());
}

// Initialisation and, at normal process exit, dCloseODE (a function-local static: constructed on first
// use, by one thread only).
struct Library {
  Library() {
    dSetErrorHandler(on_error);
    dSetDebugHandler(on_debug);
    dSetMessageHandler(on_message);
    if (!dCheckConfiguration("ODE_double_precision"))
      throw std::runtime_error(std::string("ODE is not the double-precision build: ") + dGetConfiguration());
    if (!dInitODE2(0)) throw std::runtime_error("ODE: dInitODE2 failed");
  }
  ~Library() { dCloseODE(); }
};

}  // namespace

void ensure_initialised() {
  static const Library library;
  // ODE wants its per-thread data on every thread that steps a world; a no-op when already there.
  if (!dAllocateODEDataForThread(dAllocateMaskAll)) throw std::runtime_error("ODE: dAllocateODEDataForThread failed");
}

std::string version_text() {
  return std::string("ODE ") + dODE_VERSION +
         (dCheckConfiguration("ODE_double_precision") ? " (double precision)" : " (single precision)");
}

const void* library_function() { return reinterpret_cast<const void*>(&dGetConfiguration); }

std::string header_version_text() { return std::string("dODE_VERSION ") + dODE_VERSION; }

MessageLog::MessageLog() : outer_(current_log) { current_log = this; }

bool MessageLog::add(std::string message) {
  ++count_;
  if (messages_.size() >= kKept) return false;
  messages_.push_back(std::move(message));
  return true;
}
MessageLog::~MessageLog() { current_log = outer_; }

}  // namespace ib::ode
