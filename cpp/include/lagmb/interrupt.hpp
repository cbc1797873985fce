// Stopping a long computation when its user asks (Ctrl-C in Python).
#pragma once

#include <cmath>
#include <functional>
#include <memory>

#include "lagmb/trajectory.hpp"

namespace lagmb {

/// A user asked to stop (the installed check said so at a poll point, or a
/// user function was interrupted). Deliberately not a std::exception: no
/// handler of solver failures catches it, so it unwinds to the entry point
/// that installed the check. simulate() puts the outputs computed so far in
/// `partial`; `cause` is whatever the thrower needs to re-raise (opaque here:
/// the Python binding keeps the KeyboardInterrupt in it).
struct Interrupted {
  std::shared_ptr<void> cause;
  double t = NAN;  // time reached, where known
  Trajectory partial;
};

/// Installs `check` for the calling thread while the scope lives (scopes
/// nest; the innermost one is used). `check` throws Interrupted to stop.
class InterruptScope {
 public:
  explicit InterruptScope(std::function<void()> check);
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  std::function<void()> check_;
  InterruptScope* outer_;
};

/// Called between steps, Newton iterations and other long loops: runs the
/// installed check at most every 20 ms of wall time (it may need Python's
/// lock), so polling costs a clock read.
void poll_interrupt();

}  // namespace lagmb
