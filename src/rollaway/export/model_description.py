"""``modelDescription.xml`` of the drum FMU (FMI 2.0, co-simulation).

Variables, units and the model structure come from :mod:`rollaway.export.variables`; the
model's provenance (data file and its SHA-256, the command that calibrated it, the verdict, the
tested range, the rollaway version) is in the model's description and, machine-readable, in
``<VendorAnnotations><Tool name="rollaway"><Provenance .../>``.
"""
from __future__ import annotations

import datetime as _dt
import xml.etree.ElementTree as ET
from pathlib import Path

from rollaway.export.c_source import MODEL_IDENTIFIER
from rollaway.export.variables import UNITS, Variable, all_variables


def provenance(model) -> dict[str, str]:
    """What the FMU says of where its values came from (the model file's [provenance], verdict, range)."""
    from rollaway import __version__
    active = [e.name for e, _ in model.active()]
    out = {str(k): str(v) for k, v in (model.provenance or {}).items()}
    out.setdefault("verdict", ", ".join(active) if active else "none (the paper's chain)")
    out["effects"] = ", ".join(e.name for e in model.effects) or "none"
    out["parameter_set"] = str(model.base if model.provenance else model.params.name)
    for key in ("tested_hand_force_N", "tested_initial_temp_C", "tested_duration_s", "tested_directions"):
        if key in (model.predictive or {}):
            value = model.predictive[key]
            out[key] = " to ".join(map(str, value)) if isinstance(value, list) and key != "tested_directions" \
                else (", ".join(value) if isinstance(value, list) else str(value))
    alternatives = (model.predictive or {}).get("alternatives") or []
    if alternatives:          # the FMU is the point model: competing effect sets and bands stay in rollaway
        out["alternatives_not_exported"] = ", ".join(f"{Path(a['file']).name} (weight {a['weight']:.3g})"
                                                     for a in alternatives)
    out["exported_by"] = f"rollaway {__version__}"
    out.setdefault("rollaway_version", __version__)
    return out


def description(model) -> str:
    prov = provenance(model)
    text = (f"rollaway drum parking brake '{model.name}': Ishak et al. 2018 chain (eqs. 10, 16-24), "
            f"effects: {prov['effects']}; torque of one rear drum")
    if "data_file" in prov:
        text += (f"; calibrated by 'rollaway {prov.get('command', '?')}' on {prov['data_file']}"
                 f" (sha256 {prov.get('data_sha256', '?')[:12]}), verdict: {prov['verdict']}")
    return text + f"; exported by {prov['exported_by']}"


def unit_definitions(variables: list[Variable], extra: tuple[str, ...] = ()) -> ET.Element:
    """``<UnitDefinitions>`` of every unit the variables use, and the *extra* ones (FMI 3.0's time: ``s``)."""
    el = ET.Element("UnitDefinitions")
    by_name = {name: base for name, base in UNITS.values()}
    for name in sorted({v.unit for v in variables if v.unit} | set(extra)):
        unit = ET.SubElement(el, "Unit", name=name)
        base = dict(by_name.get(name, {}))
        offset = base.pop("offset", None)
        attrs = {k: str(x) for k, x in base.items()}
        if offset is not None:
            attrs["offset"] = repr(offset)
        ET.SubElement(unit, "BaseUnit", attrs)
    return el


def _number(x: float) -> str:
    return repr(float(x))


def model_description(model, guid: str, source_files: list[str], stop_time_s: float = 3600.0) -> str:
    """The XML text of ``modelDescription.xml``."""
    from rollaway import __version__
    variables = all_variables(model)
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "2.0", "modelName": model.name, "guid": guid, "description": description(model),
        "generationTool": f"rollaway {__version__}",
        "generationDateAndTime": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "variableNamingConvention": "flat", "numberOfEventIndicators": "0"})
    cs = ET.SubElement(root, "CoSimulation", {
        "modelIdentifier": MODEL_IDENTIFIER, "canHandleVariableCommunicationStepSize": "true",
        "canInterpolateInputs": "false", "canBeInstantiatedOnlyOncePerProcess": "false",
        "canNotUseMemoryManagementFunctions": "false", "canGetAndSetFMUstate": "false",
        "canSerializeFMUstate": "false", "providesDirectionalDerivative": "false"})
    files = ET.SubElement(cs, "SourceFiles")
    for name in source_files:
        ET.SubElement(files, "File", name=name)
    root.append(unit_definitions(variables))
    cats = ET.SubElement(root, "LogCategories")
    ET.SubElement(cats, "Category", name="logStatusError", description="errors: bad parameters, self-locking")
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", stopTime=_number(stop_time_s), stepSize="10.0")
    tool = ET.SubElement(ET.SubElement(root, "VendorAnnotations"), "Tool", name="rollaway")
    ET.SubElement(tool, "Provenance", provenance(model))
    mv = ET.SubElement(root, "ModelVariables")
    for v in variables:
        attrs = {"name": v.name, "valueReference": str(v.vr), "description": v.description,
                 "causality": v.causality, "variability": v.variability}
        if v.causality == "local":
            attrs["initial"] = "exact"
        sv = ET.SubElement(mv, "ScalarVariable", attrs)
        typ = {}
        if v.kind == "Real":
            if v.unit:
                typ["unit"] = v.unit
            if v.min is not None:
                typ["min"], typ["max"] = _number(v.min), _number(v.max)
            if v.start is not None:
                typ["start"] = _number(v.start)
        elif v.start is not None:
            typ["start"] = "true" if v.start else "false"
        ET.SubElement(sv, v.kind, typ)
    ms = ET.SubElement(root, "ModelStructure")
    outputs = ET.SubElement(ms, "Outputs")
    initial = ET.SubElement(ms, "InitialUnknowns")
    for index, v in enumerate(variables, 1):
        if v.causality == "output":
            ET.SubElement(outputs, "Unknown", index=str(index))
            ET.SubElement(initial, "Unknown", index=str(index))
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


__all__ = ["description", "model_description", "provenance", "unit_definitions"]
