/* FMI 3.0 co-simulation interface of the rollaway drum model.
 *
 * The same model as fmi2_cosim.c (see there): this file translates the FMI 3.0 calls to the life
 * cycle in cosim_core.c, which calls rollaway_drum.c, generated from the Python chain.  Co-simulation without event mode: after initialization
 * the instance is in step mode, and fmi3DoStep evaluates the closed-form outputs at the end of
 * the step.  Functions of other interfaces and types (model exchange, clocks, Int8 ... Binary,
 * FMU state, derivatives) log an error and return fmi3Error; the model has no such variables.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "cosim_core.h"

typedef struct {
    Core core;
    int logging;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log;
} Instance;

static void log_error(Instance *inst, const char *fmt, const char *detail)
{
    char text[512];
    if (inst == NULL || inst->log == NULL) return;
    snprintf(text, sizeof text, fmt, detail);
    inst->log(inst->environment, fmi3Error, "logStatusError", text);
}

static fmi3Status unsupported(fmi3Instance instance, const char *function)
{
    log_error((Instance *)instance, "%s is not supported by this FMU (co-simulation, Float64 and Boolean only)",
              function);
    return fmi3Error;
}

/* fmi3OK where the core gives no reason, else the reason logged after the function's name */
static fmi3Status report(Instance *inst, const char *function, const char *why)
{
    char text[320];
    if (why == NULL) return fmi3OK;
    snprintf(text, sizeof text, "%s: %s", function, why);
    log_error(inst, "%s", text);
    return fmi3Error;
}

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    (void)nCategories; (void)categories;
    if (instance == NULL) return fmi3Error;
    ((Instance *)instance)->logging = loggingOn;
    return fmi3OK;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    if (logMessage) logMessage(instanceEnvironment, fmi3Error, "logStatusError", "this FMU is co-simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                               fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    (void)clockUpdate; (void)lockPreemption; (void)unlockPreemption;
    if (logMessage) logMessage(instanceEnvironment, fmi3Error, "logStatusError", "this FMU is co-simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    Instance *inst;
    (void)instanceName; (void)resourcePath; (void)visible; (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables; (void)nRequiredIntermediateVariables; (void)intermediateUpdate;
    if (instantiationToken == NULL || strcmp(instantiationToken, DRUM_GUID) != 0) {
        if (logMessage) logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                                   "the instantiation token does not match the binary's");
        return NULL;
    }
    if (eventModeUsed) {
        if (logMessage) logMessage(instanceEnvironment, fmi3Error, "logStatusError", "this FMU has no event mode");
        return NULL;
    }
    inst = (Instance *)calloc(1, sizeof(Instance));
    if (inst == NULL) return NULL;
    inst->environment = instanceEnvironment;
    inst->log = logMessage;
    inst->logging = loggingOn;
    core_reset(&inst->core);
    return inst;
}

void fmi3FreeInstance(fmi3Instance instance) { free(instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    Instance *inst = (Instance *)instance;
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    if (inst == NULL) return fmi3Error;
    return report(inst, "fmi3EnterInitializationMode", core_enter_initialization(&inst->core, startTime));
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    Instance *inst = (Instance *)instance;
    if (inst == NULL) return fmi3Error;
    return report(inst, "fmi3ExitInitializationMode", core_exit_initialization(&inst->core));
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    if (instance == NULL) return fmi3Error;
    ((Instance *)instance)->core.mode = MODE_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    Instance *inst = (Instance *)instance;
    if (inst == NULL) return fmi3Error;
    core_reset(&inst->core);
    return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Float64 values[], size_t nValues)
{
    Instance *inst = (Instance *)instance;
    const char *why;
    size_t i;
    if (inst == NULL || nValues < nValueReferences) return fmi3Error;
    why = core_outputs_ready(&inst->core);
    for (i = 0; why == NULL && i < nValueReferences; i++) why = core_get_real(&inst->core, valueReferences[i], &values[i]);
    return report(inst, "fmi3GetFloat64", why);
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          const fmi3Float64 values[], size_t nValues)
{
    Instance *inst = (Instance *)instance;
    const char *why;
    size_t i;
    if (inst == NULL || nValues < nValueReferences) return fmi3Error;
    why = core_parameters_settable(&inst->core);
    for (i = 0; why == NULL && i < nValueReferences; i++) why = core_set_real(&inst->core, valueReferences[i], values[i]);
    return report(inst, "fmi3SetFloat64", why);
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          fmi3Boolean values[], size_t nValues)
{
    Instance *inst = (Instance *)instance;
    const char *why = NULL;
    size_t i;
    int v = 0;
    if (inst == NULL || nValues < nValueReferences) return fmi3Error;
    for (i = 0; why == NULL && i < nValueReferences; i++) {
        why = core_get_boolean(&inst->core, valueReferences[i], &v);
        values[i] = v != 0;
    }
    return report(inst, "fmi3GetBoolean", why);
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,
                          const fmi3Boolean values[], size_t nValues)
{
    Instance *inst = (Instance *)instance;
    const char *why;
    size_t i;
    if (inst == NULL || nValues < nValueReferences) return fmi3Error;
    why = core_parameters_settable(&inst->core);
    for (i = 0; why == NULL && i < nValueReferences; i++)
        why = core_set_boolean(&inst->core, valueReferences[i], values[i] ? 1 : 0);
    return report(inst, "fmi3SetBoolean", why);
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean *eventHandlingNeeded,
                      fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    Instance *inst = (Instance *)instance;
    fmi3Status status;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (inst == NULL) return fmi3Error;
    status = report(inst, "fmi3DoStep", core_do_step(&inst->core, currentCommunicationPoint, communicationStepSize));
    if (eventHandlingNeeded) *eventHandlingNeeded = fmi3False;
    if (terminateSimulation) *terminateSimulation = fmi3False;
    if (earlyReturn) *earlyReturn = fmi3False;
    if (lastSuccessfulTime) *lastSuccessfulTime = inst->core.time_s;
    return status;
}

/* ---- not supported: other interfaces, other variable types, FMU state, derivatives, clocks ---- */
fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{  return unsupported(instance, "fmi3EnterEventMode"); }
fmi3Status fmi3GetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Float32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetFloat32"); }
fmi3Status fmi3GetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Int8 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetInt8"); }
fmi3Status fmi3GetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt8 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetUInt8"); }
fmi3Status fmi3GetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Int16 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetInt16"); }
fmi3Status fmi3GetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt16 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetUInt16"); }
fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Int32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetInt32"); }
fmi3Status fmi3GetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetUInt32"); }
fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Int64 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetInt64"); }
fmi3Status fmi3GetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt64 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetUInt64"); }
fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3String values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3GetString"); }
fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, size_t valueSizes[], fmi3Binary values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)valueSizes; (void)values; (void)nValues; return unsupported(instance, "fmi3GetBinary"); }
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Clock values[])
{ (void)valueReferences; (void)nValueReferences; (void)values; return unsupported(instance, "fmi3GetClock"); }
fmi3Status fmi3SetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Float32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetFloat32"); }
fmi3Status fmi3SetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Int8 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetInt8"); }
fmi3Status fmi3SetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt8 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetUInt8"); }
fmi3Status fmi3SetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Int16 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetInt16"); }
fmi3Status fmi3SetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt16 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetUInt16"); }
fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Int32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetInt32"); }
fmi3Status fmi3SetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt32 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetUInt32"); }
fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Int64 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetInt64"); }
fmi3Status fmi3SetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt64 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetUInt64"); }
fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3String values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)values; (void)nValues; return unsupported(instance, "fmi3SetString"); }
fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const size_t valueSizes[], const fmi3Binary values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)valueSizes; (void)values; (void)nValues; return unsupported(instance, "fmi3SetBinary"); }
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Clock values[])
{ (void)valueReferences; (void)nValueReferences; (void)values; return unsupported(instance, "fmi3SetClock"); }
fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference valueReference, size_t* nDependencies)
{ (void)valueReference; (void)nDependencies; return unsupported(instance, "fmi3GetNumberOfVariableDependencies"); }
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent, size_t elementIndicesOfDependent[], fmi3ValueReference independents[], size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[], size_t nDependencies)
{ (void)dependent; (void)elementIndicesOfDependent; (void)independents; (void)elementIndicesOfIndependents; (void)dependencyKinds; (void)nDependencies; return unsupported(instance, "fmi3GetVariableDependencies"); }
fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* FMUState)
{ (void)FMUState; return unsupported(instance, "fmi3GetFMUState"); }
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{ (void)FMUState; return unsupported(instance, "fmi3SetFMUState"); }
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* FMUState)
{ (void)FMUState; return unsupported(instance, "fmi3FreeFMUState"); }
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t* size)
{ (void)FMUState; (void)size; return unsupported(instance, "fmi3SerializedFMUStateSize"); }
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState, fmi3Byte serializedState[], size_t size)
{ (void)FMUState; (void)serializedState; (void)size; return unsupported(instance, "fmi3SerializeFMUState"); }
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[], size_t size, fmi3FMUState* FMUState)
{ (void)serializedState; (void)size; (void)FMUState; return unsupported(instance, "fmi3DeserializeFMUState"); }
fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns, const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{ (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed; (void)sensitivity; (void)nSensitivity; return unsupported(instance, "fmi3GetDirectionalDerivative"); }
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns, const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{ (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed; (void)sensitivity; (void)nSensitivity; return unsupported(instance, "fmi3GetAdjointDerivative"); }
fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{  return unsupported(instance, "fmi3EnterConfigurationMode"); }
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{  return unsupported(instance, "fmi3ExitConfigurationMode"); }
fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[])
{ (void)valueReferences; (void)nValueReferences; (void)intervals; (void)qualifiers; return unsupported(instance, "fmi3GetIntervalDecimal"); }
fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt64 counters[], fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{ (void)valueReferences; (void)nValueReferences; (void)counters; (void)resolutions; (void)qualifiers; return unsupported(instance, "fmi3GetIntervalFraction"); }
fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3Float64 shifts[])
{ (void)valueReferences; (void)nValueReferences; (void)shifts; return unsupported(instance, "fmi3GetShiftDecimal"); }
fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, fmi3UInt64 counters[], fmi3UInt64 resolutions[])
{ (void)valueReferences; (void)nValueReferences; (void)counters; (void)resolutions; return unsupported(instance, "fmi3GetShiftFraction"); }
fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Float64 intervals[])
{ (void)valueReferences; (void)nValueReferences; (void)intervals; return unsupported(instance, "fmi3SetIntervalDecimal"); }
fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{ (void)valueReferences; (void)nValueReferences; (void)counters; (void)resolutions; return unsupported(instance, "fmi3SetIntervalFraction"); }
fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Float64 shifts[])
{ (void)valueReferences; (void)nValueReferences; (void)shifts; return unsupported(instance, "fmi3SetShiftDecimal"); }
fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{ (void)valueReferences; (void)nValueReferences; (void)counters; (void)resolutions; return unsupported(instance, "fmi3SetShiftFraction"); }
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{  return unsupported(instance, "fmi3EvaluateDiscreteStates"); }
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean* discreteStatesNeedUpdate, fmi3Boolean* terminateSimulation, fmi3Boolean* nominalsOfContinuousStatesChanged, fmi3Boolean* valuesOfContinuousStatesChanged, fmi3Boolean* nextEventTimeDefined, fmi3Float64* nextEventTime)
{ (void)discreteStatesNeedUpdate; (void)terminateSimulation; (void)nominalsOfContinuousStatesChanged; (void)valuesOfContinuousStatesChanged; (void)nextEventTimeDefined; (void)nextEventTime; return unsupported(instance, "fmi3UpdateDiscreteStates"); }
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{  return unsupported(instance, "fmi3EnterContinuousTimeMode"); }
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance, fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean* enterEventMode, fmi3Boolean* terminateSimulation)
{ (void)noSetFMUStatePriorToCurrentPoint; (void)enterEventMode; (void)terminateSimulation; return unsupported(instance, "fmi3CompletedIntegratorStep"); }
fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{ (void)time; return unsupported(instance, "fmi3SetTime"); }
fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[], size_t nContinuousStates)
{ (void)continuousStates; (void)nContinuousStates; return unsupported(instance, "fmi3SetContinuousStates"); }
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[], size_t nContinuousStates)
{ (void)derivatives; (void)nContinuousStates; return unsupported(instance, "fmi3GetContinuousStateDerivatives"); }
fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators)
{ (void)eventIndicators; (void)nEventIndicators; return unsupported(instance, "fmi3GetEventIndicators"); }
fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates)
{ (void)continuousStates; (void)nContinuousStates; return unsupported(instance, "fmi3GetContinuousStates"); }
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[], size_t nContinuousStates)
{ (void)nominals; (void)nContinuousStates; return unsupported(instance, "fmi3GetNominalsOfContinuousStates"); }
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t* nEventIndicators)
{ (void)nEventIndicators; return unsupported(instance, "fmi3GetNumberOfEventIndicators"); }
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t* nContinuousStates)
{ (void)nContinuousStates; return unsupported(instance, "fmi3GetNumberOfContinuousStates"); }
fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{  return unsupported(instance, "fmi3EnterStepMode"); }
fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues)
{ (void)valueReferences; (void)nValueReferences; (void)orders; (void)values; (void)nValues; return unsupported(instance, "fmi3GetOutputDerivatives"); }
fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference, fmi3Float64 activationTime)
{ (void)clockReference; (void)activationTime; return unsupported(instance, "fmi3ActivateModelPartition"); }
