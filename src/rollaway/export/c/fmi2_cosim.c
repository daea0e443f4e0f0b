/* FMI 2.0 co-simulation interface of the rollaway drum model.
 *
 * This file is the same for every exported model: it translates the FMI 2.0 calls (types, status
 * codes, logging) to the life cycle in cosim_core.c, shared with the FMI 3.0 interface, which calls
 * the model in rollaway_drum.c that rollaway generated from the Python chain with the model's values
 * baked in:
 *
 *   drum_defaults(s)        start values of the parameters
 *   drum_check(s, msg)      parameter values within their ranges (0 = fine, else msg says why)
 *   drum_setup(s)           work that depends only on parameters (e.g. a cooling table)
 *   drum_evaluate(s, t)     outputs at t = time since the lever was applied [s]
 *   drum_get_real/_boolean, drum_set_real/_boolean   access by value reference
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "cosim_core.h"

typedef struct {
    Core core;
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

/* fmi2OK where the core gives no reason, else the reason logged after the function's name */
static fmi2Status report(Instance *inst, const char *function, const char *why)
{
    if (why == NULL) return fmi2OK;
    log_message(inst, fmi2Error, "logStatusError", "%s: %s", function, why);
    return fmi2Error;
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
    core_reset(&inst->core);
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
    if (inst == NULL || inst->core.mode != MODE_INSTANTIATED) return fmi2Error;
    inst->core.time_s = startTime;     /* taken as the start by fmi2EnterInitializationMode */
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    return report(inst, "fmi2EnterInitializationMode", core_enter_initialization(&inst->core, inst->core.time_s));
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    return report(inst, "fmi2ExitInitializationMode", core_exit_initialization(&inst->core));
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    inst->core.mode = MODE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    core_reset(&inst->core);
    return fmi2OK;
}

/* ---- getting and setting variable values -------------------------------------------------- */
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    const char *why;
    size_t i;
    if (inst == NULL) return fmi2Error;
    why = core_outputs_ready(&inst->core);
    for (i = 0; why == NULL && i < nvr; i++) why = core_get_real(&inst->core, vr[i], &value[i]);
    return report(inst, "fmi2GetReal", why);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    const char *why = NULL;
    size_t i;
    if (inst == NULL) return fmi2Error;
    for (i = 0; why == NULL && i < nvr; i++) why = core_get_boolean(&inst->core, vr[i], &value[i]);
    return report(inst, "fmi2GetBoolean", why);
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    const char *why;
    size_t i;
    if (inst == NULL) return fmi2Error;
    why = core_parameters_settable(&inst->core);
    for (i = 0; why == NULL && i < nvr; i++) why = core_set_real(&inst->core, vr[i], value[i]);
    return report(inst, "fmi2SetReal", why);
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    const char *why;
    size_t i;
    if (inst == NULL) return fmi2Error;
    why = core_parameters_settable(&inst->core);
    for (i = 0; why == NULL && i < nvr; i++) why = core_set_boolean(&inst->core, vr[i], value[i]);
    return report(inst, "fmi2SetBoolean", why);
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
    if (inst == NULL) return fmi2Error;
    return report(inst, "fmi2DoStep", core_do_step(&inst->core, currentCommunicationPoint, communicationStepSize));
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL || s != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = inst->core.time_s;
    return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{ (void)c; (void)s; (void)value; return fmi2Discard; }
