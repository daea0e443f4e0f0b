/* The co-simulation life cycle of the rollaway drum model, shared by both FMI versions.
 *
 * fmi2_cosim.c and fmi3_cosim.c only translate their FMI calls (types, status codes, logging) to
 * these functions; the modes, the checks and the calls into the generated model (rollaway_drum.c)
 * are here once.  Every function returns NULL when all is well, else the reason to log.
 */
#ifndef ROLLAWAY_COSIM_CORE_H
#define ROLLAWAY_COSIM_CORE_H

#include "rollaway_drum.h"

typedef enum { MODE_INSTANTIATED, MODE_INITIALIZATION, MODE_STEP, MODE_TERMINATED, MODE_ERROR } Mode;

typedef struct {
    DrumState state;
    Mode mode;
    double time_s;             /* time since the lever was applied [s] */
    char why[256];             /* the last reason, when a check gives one */
} Core;

void core_reset(Core *c);                                         /* start values, instantiated, t = 0 */
const char *core_enter_initialization(Core *c, double start_time_s);
const char *core_exit_initialization(Core *c);
const char *core_outputs_ready(Core *c);                          /* before reading outputs */
const char *core_parameters_settable(const Core *c);
const char *core_get_real(const Core *c, unsigned int vr, double *value);
const char *core_get_boolean(const Core *c, unsigned int vr, int *value);
const char *core_set_real(Core *c, unsigned int vr, double value);
const char *core_set_boolean(Core *c, unsigned int vr, int value);
const char *core_do_step(Core *c, double current_s, double step_s);

#endif
