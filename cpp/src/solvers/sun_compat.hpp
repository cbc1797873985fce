// The one place that knows SUNDIALS 6.x from 7.x.
//
// Both versions share the SUNMatrix / SUNLinearSolver op signatures we use
// (SUNErrCode is int in 7.x); they differ in how a context is created and in
// how errors are reported. Errors are captured here, never printed.
#pragma once

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <idas/idas.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_types.h>

#include <stdexcept>
#include <string>

#if SUNDIALS_VERSION_MAJOR < 6
#error "lagmb needs SUNDIALS 6.0 or newer"
#endif

namespace lagmb::sun {

using real = sunrealtype;
using index = sunindextype;

/// The last error message SUNDIALS reported.
struct ErrorSink {
  std::string message;
  int code = 0;
};

/// Owns a SUNContext and routes SUNDIALS error messages into an ErrorSink.
class Context {
 public:
  Context() {
#if SUNDIALS_VERSION_MAJOR >= 7
    if (SUNContext_Create(SUN_COMM_NULL, &ctx_) != 0) throw std::runtime_error("SUNContext_Create failed");
    SUNContext_ClearErrHandlers(ctx_);  // no printing to stderr
    SUNContext_PushErrHandler(ctx_, &Context::handler7, &sink_);
#else
    if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNContext_Create failed");
#endif
  }
  ~Context() { SUNContext_Free(&ctx_); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  operator SUNContext() const { return ctx_; }
  ErrorSink& sink() { return sink_; }

  /// In 6.x errors are reported per integrator instance.
  void attach_ida(void* ida_mem) {
#if SUNDIALS_VERSION_MAJOR < 7
    IDASetErrHandlerFn(ida_mem, &Context::handler6, &sink_);
#else
    (void)ida_mem;
#endif
  }
  void attach_cvode(void* cvode_mem) {
#if SUNDIALS_VERSION_MAJOR < 7
    CVodeSetErrHandlerFn(cvode_mem, &Context::handler6, &sink_);
#else
    (void)cvode_mem;
#endif
  }
  void attach_erkstep(void* arkode_mem) {
#if SUNDIALS_VERSION_MAJOR < 7
    ERKStepSetErrHandlerFn(arkode_mem, &Context::handler6, &sink_);
#else
    (void)arkode_mem;
#endif
  }

 private:
#if SUNDIALS_VERSION_MAJOR >= 7
  static void handler7(int, const char* func, const char*, const char* msg, SUNErrCode code,
                       void* data, SUNContext) {
    auto* s = static_cast<ErrorSink*>(data);
    s->message = std::string(func ? func : "") + ": " + (msg ? msg : "");
    s->code = code;
  }
#else
  static void handler6(int code, const char* module, const char* func, char* msg, void* data) {
    auto* s = static_cast<ErrorSink*>(data);
    if (code > 0) return;  // warnings: not errors
    s->message = std::string(module ? module : "") + "::" + (func ? func : "") + ": " + (msg ? msg : "");
    s->code = code;
  }
#endif
  SUNContext ctx_ = nullptr;
  ErrorSink sink_;
};

}  // namespace lagmb::sun
