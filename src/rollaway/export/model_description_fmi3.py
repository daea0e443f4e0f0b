"""``modelDescription.xml`` and ``sources/buildDescription.xml`` of the drum FMU in FMI 3.0 (co-simulation).

The same variables, units and provenance as the FMI 2.0 file (:mod:`rollaway.export.model_description`),
in FMI 3.0's schema: typed variables (``Float64``, ``Boolean``), the model structure by value reference,
the provenance in ``<Annotations><Annotation type="org.rollaway">``.
"""
from __future__ import annotations

import datetime as _dt
import xml.etree.ElementTree as ET

from rollaway.export.c_source import MODEL_IDENTIFIER
from rollaway.export.model_description import description, provenance, unit_definitions
from rollaway.export.variables import all_variables


def _xml(root: ET.Element) -> str:
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def model_description_fmi3(model, token: str, stop_time_s: float = 3600.0) -> str:
    """The XML text of an FMI 3.0 ``modelDescription.xml`` (*token*: the instantiation token)."""
    from rollaway import __version__
    variables = all_variables(model)
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "3.0", "modelName": model.name, "instantiationToken": token,
        "description": description(model), "generationTool": f"rollaway {__version__}",
        "generationDateAndTime": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "variableNamingConvention": "flat"})
    ET.SubElement(root, "CoSimulation", {
        "modelIdentifier": MODEL_IDENTIFIER, "canHandleVariableCommunicationStepSize": "true",
        "canGetAndSetFMUState": "false", "canSerializeFMUState": "false", "providesDirectionalDerivatives": "false",
        "hasEventMode": "false", "providesIntermediateUpdate": "false"})
    root.append(unit_definitions(variables, extra=("s",)))
    cats = ET.SubElement(root, "LogCategories")
    ET.SubElement(cats, "Category", name="logStatusError", description="errors: bad parameters, self-locking")
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", stopTime=repr(float(stop_time_s)), stepSize="10.0")
    mv = ET.SubElement(root, "ModelVariables")
    ET.SubElement(mv, "Float64", name="time", valueReference="0", causality="independent", variability="continuous",
                  unit="s", description="time since the lever was applied")
    for v in variables:
        attrs = {"name": v.name, "valueReference": str(v.vr), "description": v.description,
                 "causality": v.causality, "variability": "discrete" if v.kind == "Boolean" and v.variability ==
                 "continuous" else v.variability}
        if v.kind == "Real":
            if v.unit:
                attrs["unit"] = v.unit
            if v.min is not None:
                attrs["min"], attrs["max"] = repr(float(v.min)), repr(float(v.max))
            if v.start is not None:
                attrs["start"] = repr(float(v.start))
        elif v.start is not None:
            attrs["start"] = "true" if v.start else "false"
        if v.causality == "local":
            attrs["initial"] = "exact"
        ET.SubElement(mv, "Float64" if v.kind == "Real" else "Boolean", attrs)
    ms = ET.SubElement(root, "ModelStructure")
    outputs = [v for v in variables if v.causality == "output"]
    for v in outputs:
        ET.SubElement(ms, "Output", valueReference=str(v.vr))
    for v in outputs:
        ET.SubElement(ms, "InitialUnknown", valueReference=str(v.vr))
    ann = ET.SubElement(ET.SubElement(root, "Annotations"), "Annotation", type="org.rollaway")
    ET.SubElement(ann, "Provenance", provenance(model))
    return _xml(root)


def build_description(source_files: list[str]) -> str:
    """``sources/buildDescription.xml``: how a tool compiles the FMU from its sources (FMI 3.0, section 2.5.1)."""
    root = ET.Element("fmiBuildDescription", fmiVersion="3.0")
    config = ET.SubElement(root, "BuildConfiguration", modelIdentifier=MODEL_IDENTIFIER)
    files = ET.SubElement(config, "SourceFileSet", language="C99")
    for name in source_files:
        ET.SubElement(files, "SourceFile", name=name)
    return _xml(root)


__all__ = ["build_description", "model_description_fmi3"]
