"""Export a drum model as an FMI 2.0 (or 3.0) co-simulation FMU that runs without rollaway.

The FMU (a zip) holds ``modelDescription.xml``, ``sources/`` (the generated chain, the FMI
wrapper and the FMI headers, so any tool can rebuild it) and ``binaries/linux64/rollaway_drum.so``
(FMI 3.0: ``binaries/x86_64-linux/``), compiled at export by the system ``gcc``.  The C code is the Python chain written out
(:mod:`rollaway.export.c_source`); the tests in ``tests/export/`` run the FMU with FMPy and hold
it to :meth:`rollaway.model.drum_model.DrumModel.evaluate`.

Why gcc and not FMPy's own builder (``fmpy.build``): that one drives CMake, which a fresh
machine rarely has; the FMU is one C translation unit per file and needs no build system.
"""
from __future__ import annotations

import hashlib
import math
import platform
import shutil
import subprocess
import sys
import tempfile
import uuid
import zipfile
from pathlib import Path

from rollaway.errors import UserError
from rollaway.export.c_source import MODEL_IDENTIFIER, effect_hooks_in_c, has_c_effect, sources
from rollaway.export.model_description import model_description
from rollaway.export.model_description_fmi3 import build_description, model_description_fmi3

FMI2_HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")
FMI3_HEADERS = ("fmi3Functions.h", "fmi3FunctionTypes.h", "fmi3PlatformTypes.h")
# double precision as Python computes it: no fused multiply-add, no fast-math reordering
CFLAGS = ("-shared", "-fPIC", "-O2", "-std=c99", "-ffp-contract=off", "-fno-fast-math", "-Wall",
          "-fvisibility=hidden")       # only the FMI functions are exported: two FMUs in one process do not clash


def fmi_headers_dir(headers=FMI2_HEADERS) -> Path:
    """The folder of the FMI headers that ship with FMPy (UserError if FMPy is not installed)."""
    try:
        import fmpy
    except ImportError:
        raise UserError("export-fmu needs the FMI headers that ship with FMPy; install them with "
                        "pip install 'rollaway[fmu]' (or pip install fmpy)") from None
    folder = Path(fmpy.__file__).parent / "c-code"
    if not all((folder / h).is_file() for h in headers):
        raise UserError(f"FMPy at {folder.parent} lacks {', '.join(headers)} in c-code/; reinstall it "
                        f"(pip install --force-reinstall 'fmpy>=0.3.20')")
    return folder


def exportable(model) -> None:
    """UserError if *model* cannot become C code: a plugin effect, or a shoe that self-locks."""
    from rollaway.effects import CATALOGUE
    from rollaway.effects.shape_free import is_shape_free
    for e in model.effects:
        if is_shape_free(e):
            raise UserError(f"effect '{e.name}' is the shape-free form of {e.base} (a spline fitted to the bench data, "
                            f"one of the competing effect sets of a diagnosis); it has no C code for an FMU — export "
                            f"the main model file, or a model with {e.base} in its catalogue form")
        if CATALOGUE.get(e.name) is not type(e) or not has_c_effect(e.name):
            where = model.effect_files.get(e.name) or getattr(type(e), "__rollaway_source__", None) \
                or type(e).__module__
            raise UserError(f"effect '{e.name}' is a plugin ({where}): its Python code cannot go into an FMU, "
                            f"which must run without rollaway; export a model without it (only catalogue effects "
                            f"are written in C)")
        missing = set(e.overridden_hooks()) - set(effect_hooks_in_c(e.name))
        if missing:
            raise UserError(f"effect '{e.name}': no C code for its hook(s) {', '.join(sorted(missing))}; "
                            f"it cannot be exported")
    for key, value in model.values.items():
        if not (isinstance(value, (int, float)) and math.isfinite(float(value))):
            raise UserError(f"model value '{key}' = {value!r} is not one finite number; an FMU bakes in one value")
    p = model.params
    if p.shoe_arm_normal_m - p.mu_drum * p.shoe_arm_friction_m <= 0:
        raise UserError(f"the shoe self-locks facing downhill with mu_drum = {p.mu_drum:g} (l_f - mu_d*l_fr <= 0, "
                        f"eqs. 18-21): the model has no finite torque; lower mu_drum in the model file")


def _check_platform() -> None:
    if sys.platform.startswith("linux") and platform.machine() in ("x86_64", "AMD64"):
        return
    raise UserError(f"export-fmu builds a linux64 binary and runs on Linux x86-64 only (this is {sys.platform} "
                    f"{platform.machine()}); the FMU's sources/ can be compiled for other platforms by the importing "
                    f"tool")


def _gcc() -> str:
    gcc = shutil.which("gcc")
    if gcc is None:
        raise UserError("the C compiler gcc was not found on PATH; install it (Debian/Ubuntu: apt-get install gcc) "
                        "to build the FMU's binary")
    return gcc


def _guid(texts: list[str]) -> str:
    digest = hashlib.sha256("\n".join(texts).encode("utf-8")).hexdigest()
    return "{" + str(uuid.UUID(digest[:32])) + "}"


FMI = {   # per FMI version: the interface's C file, its headers, the binary's folder (FMI 2.0 sec. 2.4, 3.0 sec. 2.5)
    "2.0": ("fmi2_cosim.c", FMI2_HEADERS, "linux64"),
    "3.0": ("fmi3_cosim.c", FMI3_HEADERS, "x86_64-linux"),
}


def export_fmu(model, path: str | Path, *, stop_time_s: float = 3600.0, fmi_version: str = "2.0") -> Path:
    """Write *model* (a :class:`~rollaway.model.drum_model.DrumModel`, a set name or a model file) as an
    FMI co-simulation FMU at *path* (``.fmu``); returns the path.

    Parameters of the FMU: ``hand_force_N``, ``initial_drum_temp_C``, ``ambient_temp_C``,
    ``facing_uphill``; outputs: ``torque_Nm`` (one rear drum), ``drum_temp_C``, ``clamp_force_N``,
    ``lining_temp_C``; the FMU's time is the time since the lever was applied [s].
    *stop_time_s* is the DefaultExperiment's stop time; *fmi_version* ``"2.0"`` or ``"3.0"``.
    """
    from rollaway.errors import check_choice
    from rollaway.model.drum_model import as_model
    fmi_version = check_choice(str(fmi_version), FMI, "FMI version")
    model = as_model(model)
    out = Path(path)
    if out.suffix.lower() != ".fmu":
        raise UserError(f"output '{out}' must end in .fmu (an FMU is a zip file named MODEL.fmu), e.g. drum.fmu")
    exportable(model)
    _check_platform()
    gcc = _gcc()
    wrapper, header_files, binary_dir = FMI[fmi_version]
    headers = fmi_headers_dir(header_files)
    title = f"drum model '{model.name}'"
    files = sources(model, "{GUID}", title, wrapper)
    c_files = [f for f in files if f.endswith(".c")]
    guid = _guid([fmi_version, *files.values(), _description(model, "{GUID}", c_files, stop_time_s, fmi_version)
                  .split("generationDateAndTime")[0]])
    files = sources(model, guid, title, wrapper)
    with tempfile.TemporaryDirectory(prefix="rollaway-fmu-") as tmp:
        root = Path(tmp)
        src = root / "sources"
        src.mkdir()
        for name, text in files.items():
            (src / name).write_text(text, encoding="utf-8")
        for h in header_files:
            shutil.copyfile(headers / h, src / h)
        if fmi_version == "3.0":
            (src / "buildDescription.xml").write_text(build_description(c_files), encoding="utf-8")
        lib = root / "binaries" / binary_dir / f"{MODEL_IDENTIFIER}.so"
        lib.parent.mkdir(parents=True)
        cmd = [gcc, *CFLAGS, f"-I{src}", "-o", str(lib), *(str(src / f) for f in c_files), "-lm"]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0 or proc.stderr.strip():
            first = next((ln for ln in proc.stderr.splitlines() if "error" in ln or "warning" in ln),
                         proc.stderr.strip()[:200])
            if "math.h" in proc.stderr or "stdio.h" in proc.stderr:
                raise UserError(f"gcc finds no C library headers ({first.strip()}); install them "
                                f"(Debian/Ubuntu: apt-get install libc6-dev)")
            raise UserError(f"gcc could not compile the generated C sources cleanly: {first.strip()}; this is a bug "
                            f"of rollaway's export, please report it with the model file")
        (root / "modelDescription.xml").write_text(_description(model, guid, c_files, stop_time_s, fmi_version),
                                                   encoding="utf-8")
        if not out.parent.exists():
            from rollaway.errors import ensure_parent_dir
            ensure_parent_dir(out, "OUT.fmu")
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
            for f in sorted(root.rglob("*")):
                if f.is_file():
                    zf.write(f, f.relative_to(root).as_posix())
    return out


def _description(model, guid: str, c_files: list[str], stop_time_s: float, fmi_version: str) -> str:
    if fmi_version == "3.0":
        return model_description_fmi3(model, guid, stop_time_s)
    return model_description(model, guid, c_files, stop_time_s)


__all__ = ["CFLAGS", "FMI", "export_fmu", "exportable", "fmi_headers_dir"]
