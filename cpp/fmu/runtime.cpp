// The FMU runtime (lagmb_fmu.h): CoSimulation behind plain C. No exception
// crosses this boundary: each becomes status 3 (error) and a message.
#include <exception>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lagmb/fmu/cosimulation.hpp"
#include "lagmb_fmu.h"

#define LAGMB_FMU_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

struct Slave {
  lagmb::CoSimulation cosimulation;
  lagmb_fmu_logger log;
  void* environment;
};

constexpr int kOK = 0, kError = 3;

/// Runs `body`; an exception is logged and returned as an error.
template <class Body>
int guarded(void* slave, Body&& body) {
  auto* s = static_cast<Slave*>(slave);
  if (!s) return kError;
  try {
    body(s->cosimulation);
    return kOK;
  } catch (const std::exception& e) {
    if (s->log) s->log(s->environment, kError, e.what());
  } catch (...) {
    if (s->log) s->log(s->environment, kError, "lagmb: an unknown error");
  }
  return kError;
}

}  // namespace

LAGMB_FMU_EXPORT void* lagmb_fmu_new(const char* path, lagmb_fmu_logger log, void* environment) {
  try {
    std::ifstream file(path ? path : "");
    if (!file) throw std::runtime_error(std::string("cannot read the model: ") + (path ? path : "(no path)"));
    std::ostringstream text;
    text << file.rdbuf();
    return new Slave{lagmb::CoSimulation(lagmb::CoSimulationSetup::from_text(text.str())), log, environment};
  } catch (const std::exception& e) {
    if (log) log(environment, kError, e.what());
  } catch (...) {
    if (log) log(environment, kError, "lagmb: an unknown error");
  }
  return nullptr;
}

LAGMB_FMU_EXPORT void lagmb_fmu_free(void* slave) { delete static_cast<Slave*>(slave); }

LAGMB_FMU_EXPORT int lagmb_fmu_enter_initialization(void* slave, double tolerance, double start_time) {
  return guarded(slave, [&](lagmb::CoSimulation& c) { c.enter_initialization(start_time, tolerance); });
}

LAGMB_FMU_EXPORT int lagmb_fmu_exit_initialization(void* slave) {
  return guarded(slave, [&](lagmb::CoSimulation& c) { c.exit_initialization(); });
}

LAGMB_FMU_EXPORT int lagmb_fmu_set(void* slave, const uint32_t* vr, size_t n, const double* values) {
  return guarded(slave, [&](lagmb::CoSimulation& c) {
    for (size_t k = 0; k < n; ++k) c.set(vr[k], values[k]);
  });
}

LAGMB_FMU_EXPORT int lagmb_fmu_get(void* slave, const uint32_t* vr, size_t n, double* values) {
  return guarded(slave, [&](lagmb::CoSimulation& c) {
    for (size_t k = 0; k < n; ++k) values[k] = c.get(vr[k]);
  });
}

LAGMB_FMU_EXPORT int lagmb_fmu_do_step(void* slave, double t, double h) {
  return guarded(slave, [&](lagmb::CoSimulation& c) { c.do_step(t, h); });
}

LAGMB_FMU_EXPORT int lagmb_fmu_reset(void* slave) {
  return guarded(slave, [&](lagmb::CoSimulation& c) { c.reset(); });
}

LAGMB_FMU_EXPORT void* lagmb_fmu_get_state(void* slave, void* previous) {
  void* out = nullptr;
  const int status = guarded(slave, [&](lagmb::CoSimulation& c) {
    lagmb::CoSimulationState state = c.state();
    if (previous) {
      *static_cast<lagmb::CoSimulationState*>(previous) = std::move(state);
      out = previous;
    } else {
      out = new lagmb::CoSimulationState(std::move(state));
    }
  });
  return status == kOK ? out : nullptr;
}

LAGMB_FMU_EXPORT int lagmb_fmu_set_state(void* slave, const void* state) {
  return guarded(slave, [&](lagmb::CoSimulation& c) {
    if (!state) throw std::invalid_argument("no state given");
    c.set_state(*static_cast<const lagmb::CoSimulationState*>(state));
  });
}

LAGMB_FMU_EXPORT void lagmb_fmu_free_state(void* state) { delete static_cast<lagmb::CoSimulationState*>(state); }
