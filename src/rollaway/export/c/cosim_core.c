/* The co-simulation life cycle of the rollaway drum model, shared by both FMI versions
 * (cosim_core.h says what each function does).  The outputs are closed-form functions of time
 * (eq. 10 and the effects' own solutions), so a step evaluates them at its end: no state is
 * integrated here, and the result does not depend on the communication step size. */
#include "cosim_core.h"

static const char *evaluate(Core *c)
{
    if (drum_evaluate(&c->state, c->time_s) != 0) {
        c->mode = MODE_ERROR;
        return "the shoe self-locks (l_f - mu*l_fr <= 0, eqs. 18-21): the model has no finite torque; lower mu_drum";
    }
    return 0;
}

static const char *checked(Core *c)
{
    if (drum_check(&c->state, c->why, sizeof c->why) != 0) return c->why;
    drum_setup(&c->state);
    return 0;
}

void core_reset(Core *c)
{
    drum_defaults(&c->state);
    c->mode = MODE_INSTANTIATED;
    c->time_s = 0.0;
}

const char *core_enter_initialization(Core *c, double start_time_s)
{
    if (c->mode != MODE_INSTANTIATED) return "initialization entered twice or after it ended";
    c->time_s = start_time_s;          /* the FMU's time is the time since the lever was applied */
    c->mode = MODE_INITIALIZATION;
    return 0;
}

const char *core_exit_initialization(Core *c)
{
    const char *why;
    if (c->mode != MODE_INITIALIZATION) return "initialization ended without having been entered";
    if ((why = checked(c)) != 0) {
        c->mode = MODE_ERROR;
        return why;
    }
    c->mode = MODE_STEP;
    return evaluate(c);
}

const char *core_outputs_ready(Core *c)
{
    const char *why;
    if (c->mode != MODE_INITIALIZATION) return 0;     /* outputs asked before the end of initialization */
    if ((why = checked(c)) != 0) return why;
    drum_evaluate(&c->state, c->time_s);
    return 0;
}

const char *core_parameters_settable(const Core *c)
{
    return c->mode == MODE_INSTANTIATED || c->mode == MODE_INITIALIZATION
        ? 0 : "the parameters are fixed after initialization";
}

const char *core_get_real(const Core *c, unsigned int vr, double *value)
{
    return drum_get_real(&c->state, vr, value) != 0 ? "unknown value reference (see modelDescription.xml)" : 0;
}

const char *core_get_boolean(const Core *c, unsigned int vr, int *value)
{
    return drum_get_boolean(&c->state, vr, value) != 0 ? "unknown value reference (see modelDescription.xml)" : 0;
}

const char *core_set_real(Core *c, unsigned int vr, double value)
{
    return drum_set_real(&c->state, vr, value) != 0
        ? "the value reference is not a parameter (outputs and the calibrated values are read-only)" : 0;
}

const char *core_set_boolean(Core *c, unsigned int vr, int value)
{
    return drum_set_boolean(&c->state, vr, value) != 0 ? "the value reference is not a Boolean parameter" : 0;
}

const char *core_do_step(Core *c, double current_s, double step_s)
{
    if (c->mode != MODE_STEP) return "a step outside step mode (initialization not ended, or an earlier error)";
    if (step_s < 0.0) return "the communication step size must not be negative";
    c->time_s = current_s + step_s;
    return evaluate(c);
}
