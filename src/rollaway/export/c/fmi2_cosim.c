/* FMI 2.0 co-simulation interface of the rollaway drum model.
 *
 * This file is the same for every exported model: it keeps the FMI bookkeeping (instances,
 * modes, logging, getters and setters) and calls the model in rollaway_drum.c, which rollaway
 * generated from the Python chain with the model's values baked in:
 *
 *   drum_defaults(s)        start values of the parameters
 *   drum_check(s, msg)      parameter values within their ranges (0 = fine, else msg says why)
 *   drum_setup(s)           work that depends only on parameters (e.g. a cooling table)
 *   drum_evaluate(s, t)     outputs at t = time since the lever was applied [s]
 *   drum_get_real/_boolean, drum_set_real/_boolean   access by value reference
 *
 * The outputs are closed-form functions of time (eq. 10 and the effects' own solutions), so
 * fmi2DoStep evaluates them at the end of the step: no state is integrated here, and the
 * result does not depend on the communication step size.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "rollaway_drum.h"

typedef enum { MODE_INSTANTIATED, MODE_INITIALIZATION, MODE_STEP, MODE_TERMINATED, MODE_ERROR } Mode;

typedef struct {
    DrumState state;
    Mode mode;
    double time_s;
    int logging;
    fmi2String instance_name;
    fmi2CallbackFunctions callbacks;
} Instance;

static void log_message(Instance *inst, fmi2Status status, const char *category, const char *fmt, ...)
{
    char text[512];
    va_list args;
    if (inst == NULL || inst->callbacks.logger == NULL) return;
    if (status == fmi2OK && !inst->logging) return;
    va_start(args, fmt);
    vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    inst->callbacks.logger(inst->callbacks.componentEnvironment, inst->instance_name, status, category, "%s", text);
}

static fmi2Status fail(Instance *inst, const char *fmt, const char *detail)
{
    log_message(inst, fmi2Error, "logStatusError", fmt, detail);
    return fmi2Error;
}

static fmi2Status evaluate(Instance *inst)
{
    if (drum_evaluate(&inst->state, inst->time_s) != 0) {
        inst->mode = MODE_ERROR;
        return fail(inst, "%s", "the shoe self-locks (l_f - mu*l_fr <= 0, eqs. 18-21): the model has no finite "
                    "torque; lower mu_drum");
    }
    return fmi2OK;
}

/* ---- inquire version numbers and set debug logging ---------------------------------------- */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t n, const fmi2String categories[])
{
    (void)n; (void)categories;
    if (c == NULL) return fmi2Error;
    ((Instance *)c)->logging = loggingOn;
    return fmi2OK;
}

/* ---- creation and destruction ------------------------------------------------------------- */
fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    Instance *inst;
    (void)fmuResourceLocation; (void)visible;
    if (functions == NULL || functions->allocateMemory == NULL || functions->freeMemory == NULL) return NULL;
    inst = (Instance *)functions->allocateMemory(1, sizeof(Instance));
    if (inst == NULL) return NULL;
    inst->callbacks = *functions;
    inst->logging = loggingOn;
    inst->instance_name = instanceName ? instanceName : "rollaway_drum";
    if (fmuType != fmi2CoSimulation) {
        log_message(inst, fmi2Error, "logStatusError", "%s", "this FMU supports co-simulation only");
        functions->freeMemory(inst);
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, DRUM_GUID) != 0) {
        log_message(inst, fmi2Error, "logStatusError", "GUID %s does not match the binary's %s",
                    fmuGUID ? fmuGUID : "(null)", DRUM_GUID);
        functions->freeMemory(inst);
        return NULL;
    }
    drum_defaults(&inst->state);
    inst->mode = MODE_INSTANTIATED;
    inst->time_s = 0.0;
    return inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst != NULL) inst->callbacks.freeMemory(inst);
}

/* ---- initialization, termination, reset -------------------------------------------------- */
fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    Instance *inst = (Instance *)c;
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    if (inst == NULL || inst->mode != MODE_INSTANTIATED) return fmi2Error;
    inst->time_s = startTime;          /* the FMU's time is the time since the lever was applied */
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL || inst->mode != MODE_INSTANTIATED) return fmi2Error;
    inst->mode = MODE_INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    char why[256];
    if (inst == NULL || inst->mode != MODE_INITIALIZATION) return fmi2Error;
    if (drum_check(&inst->state, why, sizeof why) != 0) {
        inst->mode = MODE_ERROR;
        return fail(inst, "%s", why);
    }
    drum_setup(&inst->state);
    inst->mode = MODE_STEP;
    return evaluate(inst);
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    inst->mode = MODE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    drum_defaults(&inst->state);
    inst->mode = MODE_INSTANTIATED;
    inst->time_s = 0.0;
    return fmi2OK;
}

/* ---- getting and setting variable values -------------------------------------------------- */
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (inst->mode == MODE_INITIALIZATION) {          /* outputs asked before the end of initialization */
        char why[256];
        if (drum_check(&inst->state, why, sizeof why) != 0) return fail(inst, "%s", why);
        drum_setup(&inst->state);
        drum_evaluate(&inst->state, inst->time_s);
    }
    for (i = 0; i < nvr; i++)
        if (drum_get_real(&inst->state, vr[i], &value[i]) != 0)
            return fail(inst, "fmi2GetReal: unknown value reference %s", "(see modelDescription.xml)");
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    for (i = 0; i < nvr; i++)
        if (drum_get_boolean(&inst->state, vr[i], &value[i]) != 0)
            return fail(inst, "fmi2GetBoolean: unknown value reference %s", "(see modelDescription.xml)");
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (inst->mode != MODE_INSTANTIATED && inst->mode != MODE_INITIALIZATION)
        return fail(inst, "%s", "fmi2SetReal: the parameters are fixed after initialization");
    for (i = 0; i < nvr; i++)
        if (drum_set_real(&inst->state, vr[i], value[i]) != 0)
            return fail(inst, "fmi2SetReal: %s", "the value reference is not a parameter (outputs and the "
                        "calibrated values are read-only)");
    return fmi2OK;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (inst->mode != MODE_INSTANTIATED && inst->mode != MODE_INITIALIZATION)
        return fail(inst, "%s", "fmi2SetBoolean: the parameters are fixed after initialization");
    for (i = 0; i < nvr; i++)
        if (drum_set_boolean(&inst->state, vr[i], value[i]) != 0)
            return fail(inst, "fmi2SetBoolean: %s", "the value reference is not a Boolean parameter");
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    (void)vr; (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "%s", "the model has no Integer variables");
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    (void)vr; (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "%s", "the model has no Integer variables");
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    (void)vr; (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "%s", "the model has no String variables");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    (void)vr; (void)value;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "%s", "the model has no String variables");
}

/* ---- FMU state and derivatives: not supported (canGetAndSetFMUstate="false") ---------------- */
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)s; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n)
{ (void)s; (void)n; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n)
{ (void)s; (void)b; (void)n; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s)
{ (void)s; (void)b; (void)n; return fail((Instance *)c, "%s", "not supported"); }
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz, const fmi2Real dv[], fmi2Real dz[])
{ (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)dz; return fail((Instance *)c, "%s", "not supported"); }

/* ---- co-simulation ------------------------------------------------------------------------ */
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{ (void)vr; (void)nvr; (void)order; (void)value; return fail((Instance *)c, "%s", "the model has no inputs"); }

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{ (void)vr; (void)nvr; (void)order; (void)value; return fail((Instance *)c, "%s", "not supported"); }

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    Instance *inst = (Instance *)c;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (inst == NULL || inst->mode != MODE_STEP) return fmi2Error;
    if (communicationStepSize < 0.0)
        return fail(inst, "%s", "fmi2DoStep: the communication step size must not be negative");
    inst->time_s = currentCommunicationPoint + communicationStepSize;
    return evaluate(inst);
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL || s != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = inst->time_s;
    return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
