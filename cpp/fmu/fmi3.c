/* The FMI 3.0 co-simulation functions of a lagmb FMU: each forwards to the
 * runtime (lagmb_fmu.h), which holds the model. `lagmb fmu` compiles this file
 * with the FMI headers FMPy ships and the model's instantiation token
 * (-DLAGMB_FMU_TOKEN="..."). Every fmi3 function is exported, as importers
 * resolve them all; those of Model Exchange, Scheduled Execution, clocks,
 * serialized states and derivatives return fmi3Error with a message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "lagmb_fmu.h"

#ifndef LAGMB_FMU_TOKEN
#error "compile with -DLAGMB_FMU_TOKEN=\"<the instantiationToken of modelDescription.xml>\""
#endif

typedef struct {
  void* slave;
  fmi3InstanceEnvironment environment;
  fmi3LogMessageCallback log;
} Instance;

static void log_message(void* instance, int status, const char* message) {
  Instance* i = (Instance*)instance;
  if (i && i->log) i->log(i->environment, (fmi3Status)status, status >= fmi3Error ? "logStatusError" : "logAll", message);
}

static fmi3Status status(int s) { return (fmi3Status)s; }

static fmi3Status unsupported(fmi3Instance instance, const char* function) {
  char message[160];
  snprintf(message, sizeof message, "%s: not supported by this co-simulation FMU", function);
  log_message(instance, fmi3Error, message);
  return fmi3Error;
}

static void* slave(fmi3Instance instance) { return instance ? ((Instance*)instance)->slave : NULL; }

/* ---- implemented --------------------------------------------------------- */

const char* fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean on, size_t n, const fmi3String categories[]) {
  (void)instance; (void)on; (void)n; (void)categories;
  return fmi3OK; /* errors are always logged; there is nothing else to log */
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String token, fmi3String resource_path,
                                         fmi3Boolean visible, fmi3Boolean logging_on, fmi3Boolean event_mode,
                                         fmi3Boolean early_return, const fmi3ValueReference required[],
                                         size_t n_required, fmi3InstanceEnvironment environment,
                                         fmi3LogMessageCallback log, fmi3IntermediateUpdateCallback update) {
  (void)name; (void)visible; (void)logging_on; (void)early_return; (void)required; (void)n_required; (void)update;
  Instance probe = {NULL, environment, log};
  if (!token || strcmp(token, LAGMB_FMU_TOKEN) != 0) {
    log_message(&probe, fmi3Error, "the instantiationToken is not this FMU's");
    return NULL;
  }
  if (event_mode) {
    log_message(&probe, fmi3Error, "this FMU has no event mode");
    return NULL;
  }
  if (!resource_path) {
    log_message(&probe, fmi3Error, "no resource path: the model is in resources/model.lagmb");
    return NULL;
  }
  const size_t length = strlen(resource_path);
  char* path = (char*)malloc(length + 16);
  Instance* i = (Instance*)malloc(sizeof(Instance));
  if (!path || !i) {
    free(path);
    free(i);
    return NULL;
  }
  /* the resource path ends with a separator (FMI 3.0, 2.3.1) */
  snprintf(path, length + 16, "%smodel.lagmb", resource_path);
  *i = probe;
  i->slave = lagmb_fmu_new(path, log_message, i);
  free(path);
  if (!i->slave) {
    free(i);
    return NULL;
  }
  return i;
}

void fmi3FreeInstance(fmi3Instance instance) {
  if (!instance) return;
  lagmb_fmu_free(slave(instance));
  free(instance);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean tolerance_defined, fmi3Float64 tolerance,
                                       fmi3Float64 start_time, fmi3Boolean stop_defined, fmi3Float64 stop_time) {
  (void)stop_defined; (void)stop_time;
  return status(lagmb_fmu_enter_initialization(slave(instance), tolerance_defined ? tolerance : 0.0, start_time));
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
  return status(lagmb_fmu_exit_initialization(slave(instance)));
}

fmi3Status fmi3Terminate(fmi3Instance instance) { return instance ? fmi3OK : fmi3Error; }

fmi3Status fmi3Reset(fmi3Instance instance) { return status(lagmb_fmu_reset(slave(instance))); }

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Float64 values[],
                          size_t n_values) {
  if (n_values != n) return unsupported(instance, "fmi3GetFloat64 of arrays");
  return status(lagmb_fmu_get(slave(instance), vr, n, values));
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                          const fmi3Float64 values[], size_t n_values) {
  if (n_values != n) return unsupported(instance, "fmi3SetFloat64 of arrays");
  return status(lagmb_fmu_set(slave(instance), vr, n, values));
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 t, fmi3Float64 h, fmi3Boolean no_set_prior,
                      fmi3Boolean* event_handling_needed, fmi3Boolean* terminate, fmi3Boolean* early_return,
                      fmi3Float64* last_successful_time) {
  (void)no_set_prior;
  const int s = lagmb_fmu_do_step(slave(instance), t, h);
  *event_handling_needed = fmi3False;
  *terminate = s != 0 ? fmi3True : fmi3False;
  *early_return = fmi3False;
  *last_successful_time = t + h;
  if (s != 0) {
    const fmi3ValueReference time = 0;
    lagmb_fmu_get(slave(instance), &time, 1, last_successful_time);
  }
  return status(s);
}

/* an FMU state: the simulator's (a restored one steps on bit for bit) */
fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* state) {
  if (!state) return unsupported(instance, "fmi3GetFMUState without a place for the state");
  void* s = lagmb_fmu_get_state(slave(instance), *state);
  if (!s) return fmi3Error;
  *state = s;
  return fmi3OK;
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState state) {
  return status(lagmb_fmu_set_state(slave(instance), state));
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* state) {
  (void)instance;
  if (state) {
    lagmb_fmu_free_state(*state);
    *state = NULL;
  }
  return fmi3OK;
}

/* ---- not supported: present because importers resolve every symbol ----- */

fmi3Instance fmi3InstantiateModelExchange(fmi3String a, fmi3String b, fmi3String c, fmi3Boolean d, fmi3Boolean e,
                                          fmi3InstanceEnvironment f, fmi3LogMessageCallback g) {
  (void)a; (void)b; (void)c; (void)d; (void)e; (void)f; (void)g;
  return NULL;
}
fmi3Instance fmi3InstantiateScheduledExecution(fmi3String a, fmi3String b, fmi3String c, fmi3Boolean d,
                                               fmi3Boolean e, fmi3InstanceEnvironment f, fmi3LogMessageCallback g,
                                               fmi3ClockUpdateCallback h, fmi3LockPreemptionCallback i,
                                               fmi3UnlockPreemptionCallback j) {
  (void)a; (void)b; (void)c; (void)d; (void)e; (void)f; (void)g; (void)h; (void)i; (void)j;
  return NULL;
}
#define UNSUPPORTED_1(F) \
  fmi3Status F(fmi3Instance i) { return unsupported(i, #F); }
UNSUPPORTED_1(fmi3EnterEventMode)
UNSUPPORTED_1(fmi3EnterConfigurationMode)
UNSUPPORTED_1(fmi3ExitConfigurationMode)
UNSUPPORTED_1(fmi3EvaluateDiscreteStates)
UNSUPPORTED_1(fmi3EnterContinuousTimeMode)
UNSUPPORTED_1(fmi3EnterStepMode)
#define UNSUPPORTED_GET_SET(T)                                                                              \
  fmi3Status fmi3Get##T(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3##T v[], size_t m) {       \
    (void)r; (void)n; (void)v; (void)m;                                                                     \
    return unsupported(i, "fmi3Get" #T);                                                                    \
  }                                                                                                         \
  fmi3Status fmi3Set##T(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3##T v[], size_t m) { \
    (void)r; (void)n; (void)v; (void)m;                                                                     \
    return unsupported(i, "fmi3Set" #T);                                                                    \
  }
UNSUPPORTED_GET_SET(Float32)
UNSUPPORTED_GET_SET(Int8)
UNSUPPORTED_GET_SET(UInt8)
UNSUPPORTED_GET_SET(Int16)
UNSUPPORTED_GET_SET(UInt16)
UNSUPPORTED_GET_SET(Int32)
UNSUPPORTED_GET_SET(UInt32)
UNSUPPORTED_GET_SET(Int64)
UNSUPPORTED_GET_SET(UInt64)
UNSUPPORTED_GET_SET(Boolean)
UNSUPPORTED_GET_SET(String)
fmi3Status fmi3GetBinary(fmi3Instance i, const fmi3ValueReference r[], size_t n, size_t s[], fmi3Binary v[],
                         size_t m) {
  (void)r; (void)n; (void)s; (void)v; (void)m;
  return unsupported(i, "fmi3GetBinary");
}
fmi3Status fmi3SetBinary(fmi3Instance i, const fmi3ValueReference r[], size_t n, const size_t s[],
                         const fmi3Binary v[], size_t m) {
  (void)r; (void)n; (void)s; (void)v; (void)m;
  return unsupported(i, "fmi3SetBinary");
}
fmi3Status fmi3GetClock(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3Clock v[]) {
  (void)r; (void)n; (void)v;
  return unsupported(i, "fmi3GetClock");
}
fmi3Status fmi3SetClock(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3Clock v[]) {
  (void)r; (void)n; (void)v;
  return unsupported(i, "fmi3SetClock");
}
fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance i, fmi3ValueReference r, size_t* n) {
  (void)r; (void)n;
  return unsupported(i, "fmi3GetNumberOfVariableDependencies");
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance i, fmi3ValueReference d, size_t a[], fmi3ValueReference b[],
                                       size_t c[], fmi3DependencyKind k[], size_t n) {
  (void)d; (void)a; (void)b; (void)c; (void)k; (void)n;
  return unsupported(i, "fmi3GetVariableDependencies");
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance i, fmi3FMUState s, size_t* n) {
  (void)s; (void)n;
  return unsupported(i, "fmi3SerializedFMUStateSize");
}
fmi3Status fmi3SerializeFMUState(fmi3Instance i, fmi3FMUState s, fmi3Byte b[], size_t n) {
  (void)s; (void)b; (void)n;
  return unsupported(i, "fmi3SerializeFMUState");
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance i, const fmi3Byte b[], size_t n, fmi3FMUState* s) {
  (void)b; (void)n; (void)s;
  return unsupported(i, "fmi3DeserializeFMUState");
}
#define UNSUPPORTED_DERIVATIVE(F)                                                                         \
  fmi3Status F(fmi3Instance i, const fmi3ValueReference u[], size_t nu, const fmi3ValueReference k[],      \
               size_t nk, const fmi3Float64 s[], size_t ns, fmi3Float64 o[], size_t no) {                  \
    (void)u; (void)nu; (void)k; (void)nk; (void)s; (void)ns; (void)o; (void)no;                           \
    return unsupported(i, #F);                                                                            \
  }
UNSUPPORTED_DERIVATIVE(fmi3GetDirectionalDerivative)
UNSUPPORTED_DERIVATIVE(fmi3GetAdjointDerivative)
fmi3Status fmi3GetIntervalDecimal(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3Float64 v[],
                                  fmi3IntervalQualifier q[]) {
  (void)r; (void)n; (void)v; (void)q;
  return unsupported(i, "fmi3GetIntervalDecimal");
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3UInt64 c[],
                                   fmi3UInt64 s[], fmi3IntervalQualifier q[]) {
  (void)r; (void)n; (void)c; (void)s; (void)q;
  return unsupported(i, "fmi3GetIntervalFraction");
}
fmi3Status fmi3GetShiftDecimal(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3Float64 v[]) {
  (void)r; (void)n; (void)v;
  return unsupported(i, "fmi3GetShiftDecimal");
}
fmi3Status fmi3GetShiftFraction(fmi3Instance i, const fmi3ValueReference r[], size_t n, fmi3UInt64 c[],
                                fmi3UInt64 s[]) {
  (void)r; (void)n; (void)c; (void)s;
  return unsupported(i, "fmi3GetShiftFraction");
}
fmi3Status fmi3SetIntervalDecimal(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3Float64 v[]) {
  (void)r; (void)n; (void)v;
  return unsupported(i, "fmi3SetIntervalDecimal");
}
fmi3Status fmi3SetIntervalFraction(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3UInt64 c[],
                                   const fmi3UInt64 s[]) {
  (void)r; (void)n; (void)c; (void)s;
  return unsupported(i, "fmi3SetIntervalFraction");
}
fmi3Status fmi3SetShiftDecimal(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3Float64 v[]) {
  (void)r; (void)n; (void)v;
  return unsupported(i, "fmi3SetShiftDecimal");
}
fmi3Status fmi3SetShiftFraction(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3UInt64 c[],
                                const fmi3UInt64 s[]) {
  (void)r; (void)n; (void)c; (void)s;
  return unsupported(i, "fmi3SetShiftFraction");
}
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance i, fmi3Boolean* a, fmi3Boolean* b, fmi3Boolean* c, fmi3Boolean* d,
                                    fmi3Boolean* e, fmi3Float64* f) {
  (void)a; (void)b; (void)c; (void)d; (void)e; (void)f;
  return unsupported(i, "fmi3UpdateDiscreteStates");
}
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance i, fmi3Boolean a, fmi3Boolean* b, fmi3Boolean* c) {
  (void)a; (void)b; (void)c;
  return unsupported(i, "fmi3CompletedIntegratorStep");
}
fmi3Status fmi3SetTime(fmi3Instance i, fmi3Float64 t) {
  (void)t;
  return unsupported(i, "fmi3SetTime");
}
#define UNSUPPORTED_STATES(F, CONST)                          \
  fmi3Status F(fmi3Instance i, CONST fmi3Float64 v[], size_t n) { \
    (void)v; (void)n;                                         \
    return unsupported(i, #F);                                \
  }
UNSUPPORTED_STATES(fmi3SetContinuousStates, const)
UNSUPPORTED_STATES(fmi3GetContinuousStateDerivatives, )
UNSUPPORTED_STATES(fmi3GetEventIndicators, )
UNSUPPORTED_STATES(fmi3GetContinuousStates, )
UNSUPPORTED_STATES(fmi3GetNominalsOfContinuousStates, )
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance i, size_t* n) {
  (void)n;
  return unsupported(i, "fmi3GetNumberOfEventIndicators");
}
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance i, size_t* n) {
  (void)n;
  return unsupported(i, "fmi3GetNumberOfContinuousStates");
}
fmi3Status fmi3GetOutputDerivatives(fmi3Instance i, const fmi3ValueReference r[], size_t n, const fmi3Int32 o[],
                                    fmi3Float64 v[], size_t m) {
  (void)r; (void)n; (void)o; (void)v; (void)m;
  return unsupported(i, "fmi3GetOutputDerivatives");
}
fmi3Status fmi3ActivateModelPartition(fmi3Instance i, fmi3ValueReference c, fmi3Float64 t) {
  (void)c; (void)t;
  return unsupported(i, "fmi3ActivateModelPartition");
}
