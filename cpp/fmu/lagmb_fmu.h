/* The FMU runtime of lagmb (liblagmb_fmu.so, runtime.cpp): a CoSimulation
 * (lagmb/fmu/cosimulation.hpp) behind plain C, which the FMI 3.0 functions of an
 * FMU (fmi3.c, compiled by `lagmb fmu` against FMPy's FMI headers) call.
 * Status codes are fmi3Status values: 0 OK, 3 error. */
#ifndef LAGMB_FMU_H
#define LAGMB_FMU_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* message: what went wrong, for the FMU's logMessage callback */
typedef void (*lagmb_fmu_logger)(void* environment, int status, const char* message);

/* A slave from the setup file at `path` (CoSimulationSetup::to_text); NULL,
 * with a message, if it cannot be read. */
void* lagmb_fmu_new(const char* path, lagmb_fmu_logger log, void* environment);
void lagmb_fmu_free(void* slave);
/* tolerance <= 0: the setup's rtol */
int lagmb_fmu_enter_initialization(void* slave, double tolerance, double start_time);
int lagmb_fmu_exit_initialization(void* slave);
int lagmb_fmu_set(void* slave, const uint32_t* value_references, size_t n, const double* values);
int lagmb_fmu_get(void* slave, const uint32_t* value_references, size_t n, double* values);
int lagmb_fmu_do_step(void* slave, double t, double h);
int lagmb_fmu_reset(void* slave);
/* The slave's state (CoSimulation::state), in `previous` if that is not NULL
 * (FMI overwrites a state it is given), else in a new one; NULL on error. */
void* lagmb_fmu_get_state(void* slave, void* previous);
int lagmb_fmu_set_state(void* slave, const void* state);
void lagmb_fmu_free_state(void* state);

#ifdef __cplusplus
}
#endif

#endif
