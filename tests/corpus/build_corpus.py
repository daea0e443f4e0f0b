"""Rebuild the malformed-input corpus: ``python tests/corpus/build_corpus.py tests/corpus VALID_BENCH.csv``.

The files and ``manifest.json`` are committed (the effect-plugin cases live in ``plugin_cases.py``
and are written at test time); this script documents how each was made (a case
is added here, then the corpus rebuilt).  VALID_BENCH.csv: ``rollaway synth --hand-force-N 250
--hand-force-N 340 --dt-s 900``.  It deletes and rewrites the folder it is given.
"""
import json, os, shutil, sys
from pathlib import Path

ROOT = Path(sys.argv[1])
if (ROOT / "manifest.json").exists():      # only ever a corpus folder
    for sub in ("scenario", "params", "sweep", "bench", "plugin"):
        shutil.rmtree(ROOT / sub, ignore_errors=True)
cases = []

def add(kind, name, content, expect, needles=(), effect=None, xfail=None, note="", args=()):
    """One case: a file (text or bytes), a folder of files ({name: content}) or None (a folder given where a
    file is expected); *args*: more command-line arguments ('{corpus}' stands for the corpus folder)."""
    path = ROOT / kind / name
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(content, str):
        content = content.encode("utf-8")
    if content is None:
        path.mkdir(parents=True, exist_ok=True)
        (path / "README").write_text("a folder given where a file is expected\n")
    elif isinstance(content, dict):
        path.mkdir(parents=True, exist_ok=True)
        for n, text in content.items():
            (path / n).write_bytes(text.encode("utf-8") if isinstance(text, str) else text)
    else:
        path.write_bytes(content)
    c = {"file": f"{kind}/{name}", "expect": expect, "needles": list(needles), "note": note}
    if args: c["args"] = list(args)
    if effect: c["effect"] = effect
    if xfail: c["xfail"] = xfail
    cases.append(c)

SC = '''name = "corpus"
description = "20 % grade, facing uphill"
grade_pct = 20
direction = "uphill"
occupants = 5
hand_force_N = 400
duration_s = 300
'''
def sc(**kw):
    lines = []
    for line in SC.splitlines():
        k = line.split("=")[0].strip()
        if k in kw:
            v = kw.pop(k)
            if v is None:
                continue
            lines.append(f"{k} = {v}")
        else:
            lines.append(line)
    extra = kw.pop("_extra", "")
    for k, v in kw.items():
        lines.append(f"{k} = {v}")
    return "\n".join(lines) + "\n" + extra

S = "scenario"
add(S, "ok-plain.toml", sc(), "accept")
add(S, "ok-bom.toml", "\ufeff" + sc(), "accept", note="UTF-8 with a byte-order mark")
add(S, "ok-crlf.toml", sc().replace("\n", "\r\n"), "accept")
add(S, "ok-unicode-comments.toml", "# Prüfung: Gefälle 20 %\n" + sc(description='"Gefälle — 20 % ✓"'), "accept")
add(S, "ok-negative-grade.toml", sc(grade_pct=-20, direction='"downhill"'), "accept")
add(S, "ok-no-occupants-no-force.toml", sc(occupants=0, hand_force_N=0, grade_pct=0), "accept")
add(S, "ok-overrides.toml", sc(mu_drum=0.35, tyre_road_mu=0.9, initial_drum_temp_C=150,
    _extra="\n[parameters]\nheat_transfer_W_m2K = 35\n"), "accept")
add(S, "ok-params-file.toml", sc(params='"params-ok.toml"'), "accept")
(ROOT / S).mkdir(parents=True, exist_ok=True)
(ROOT / S / "params-ok.toml").write_text('extends = "paper"\nmu_drum = 0.38\n')
(ROOT / S / "params-bad.toml").write_text('extends = "paper"\ngravity_m_s2 = 1e6\n')
add(S, "missing-name.toml", sc(name=None), "error", ["'name'"])
add(S, "unknown-key.toml", sc(grade_pc=20), "error", ["'grade_pc'", "grade_pct"])
add(S, "grade-150.toml", sc(grade_pct=150), "error", ["'grade_pct'"])
add(S, "grade-nan.toml", sc(grade_pct="nan"), "error", ["'grade_pct'"])
add(S, "grade-string.toml", sc(grade_pct='"20"'), "error", ["'grade_pct'"])
add(S, "grade-1e400.toml", sc(grade_pct="1e400"), "error", ["'grade_pct'"])
add(S, "direction-sideways.toml", sc(direction='"sideways"'), "error", ["'direction'"])
add(S, "direction-number.toml", sc(direction=1), "error", ["'direction'"])
add(S, "occupants-fraction.toml", sc(occupants=2.5), "error", ["'occupants'"])
add(S, "occupants-7.toml", sc(occupants=7), "error", ["'occupants'"])
add(S, "occupants-bool.toml", sc(occupants="true"), "error", ["'occupants'"])
add(S, "hand-force-nan.toml", sc(hand_force_N="nan"), "error", ["'hand_force_N'"])
add(S, "hand-force-inf.toml", sc(hand_force_N="inf"), "error", ["'hand_force_N'"])
add(S, "hand-force-negative.toml", sc(hand_force_N=-1), "error", ["'hand_force_N'"])
add(S, "hand-force-huge.toml", sc(hand_force_N=1e9), "error", ["'hand_force_N'"])
add(S, "duration-zero.toml", sc(duration_s=0), "error", ["'duration_s'"])
add(S, "duration-negative.toml", sc(duration_s=-5), "error", ["'duration_s'"])
add(S, "duration-year.toml", sc(duration_s=31536000), "error", ["'duration_s'"])
add(S, "duration-nan.toml", sc(duration_s="nan"), "error", ["'duration_s'"])
add(S, "mu-drum-5.toml", sc(mu_drum=5), "error", ["'mu_drum'"])
add(S, "mu-drum-nan.toml", sc(mu_drum="-nan"), "error", ["'mu_drum'"])
add(S, "tyre-mu-negative.toml", sc(tyre_road_mu=-0.1), "error", ["'tyre_road_mu'"])
add(S, "t0-5000.toml", sc(initial_drum_temp_C=5000), "error", ["'initial_drum_temp_C'"])
add(S, "regulation-unknown.toml", sc(regulation='"fmvss999"'), "error", ["'regulation'"])
add(S, "params-missing-file.toml", sc(params='"nowhere.toml"'), "error", ["key 'params'", "nowhere.toml"])
add(S, "params-number.toml", sc(params=3), "error", ["'params'"])
add(S, "params-referenced-bad.toml", sc(params='"params-bad.toml"'), "error",
    ["key 'params'", "params-bad.toml", "'gravity_m_s2'"], note="error inside a referenced file names both")
add(S, "parameters-unknown.toml", sc(_extra="\n[parameters]\nheat_transfer = 35\n"), "error", ["'heat_transfer'"])
add(S, "parameters-gravity-huge.toml", sc(_extra="\n[parameters]\ngravity_m_s2 = 1e6\n"), "error", ["'gravity_m_s2'"])
add(S, "parameters-h-zero.toml", sc(_extra="\n[parameters]\nheat_transfer_W_m2K = 0\n"), "error",
    ["'heat_transfer_W_m2K'"])
add(S, "parameters-cg-behind-rear-axle.toml", sc(_extra="\n[parameters]\ncg_behind_front_m = 3.0\n"), "error",
    ["'cg_behind_front_m'", "'wheelbase_m'"])
add(S, "parameters-not-a-table.toml", sc(parameters=5), "error", ["'parameters'"])
add(S, "parameters-inline-table.toml", sc(_extra="\n[parameters]\nmu_drum = { value = 0.4 }\n"), "error", ["'mu_drum'"])
add(S, "syntax-error.toml", sc() + "grade_pct 20\n", "error", ["line 8"])
add(S, "duplicate-key.toml", sc() + "grade_pct = 25\n", "error", ["line 8"])
add(S, "not-utf8.toml", sc(description='"caf\xe9"').encode("latin-1"), "error", ["UTF-8"])
add(S, "nul-byte.toml", sc().encode() + b"\x00\n", "error", ["line 8"])
add(S, "empty.toml", "", "error", ["'name'"])
add(S, "deep-nesting.toml", sc() + "x = " + "[" * 3000 + "]" * 3000 + "\n", "error", ["TOML"])
add(S, "a-folder.toml", None, "error", ["folder"])

P = "params"
FULL = "".join(f"{k} = {v!r}\n" for k, v in __import__("rollaway.model.parameters", fromlist=["x"]).PARAMETER_SETS["paper"].items())
add(P, "ok-extends.toml", 'extends = "paper"\nmu_drum = 0.35\n', "accept")
add(P, "ok-full.toml", FULL, "accept")
add(P, "ok-bom.toml", "\ufeffextends = \"paper\"\nmu_drum = 0.35\n", "accept")
add(P, "ok-int-values.toml", 'extends = "paper"\nvehicle_mass_kg = 1500\n', "accept")
add(P, "extends-list.toml", 'extends = ["paper"]\n', "error", ["'extends'"])
add(P, "extends-table.toml", 'extends = { set = "paper" }\n', "error", ["'extends'"])
add(P, "extends-typo.toml", 'extends = "papr"\n', "error", ["'extends'", "paper"])
add(P, "inline-table.toml", 'extends = "paper"\nmu_drum = { value = 0.4 }\n', "error", ["'mu_drum'"])
add(P, "section.toml", 'extends = "paper"\n[vehicle]\nmass = 1300\n', "error", ["'vehicle'"])
add(P, "unknown-key.toml", 'extends = "paper"\nmu_drums = 0.4\n', "error", ["'mu_drums'", "mu_drum"])
add(P, "missing-keys.toml", "mu_drum = 0.4\n", "error", ["missing parameter", "extends"])
add(P, "string-value.toml", 'extends = "paper"\nmu_drum = "0.4"\n', "error", ["'mu_drum'"])
add(P, "bool-value.toml", 'extends = "paper"\nmu_drum = true\n', "error", ["'mu_drum'"])
add(P, "array-value.toml", 'extends = "paper"\nmu_drum = [0.4]\n', "error", ["'mu_drum'"])
add(P, "nan.toml", 'extends = "paper"\ndrum_radius_m = nan\n', "error", ["'drum_radius_m'"])
add(P, "inf.toml", 'extends = "paper"\nvehicle_mass_kg = inf\n', "error", ["'vehicle_mass_kg'"])
add(P, "negative-mass.toml", 'extends = "paper"\nvehicle_mass_kg = -1250\n', "error", ["'vehicle_mass_kg'"])
add(P, "gravity-huge.toml", 'extends = "paper"\ngravity_m_s2 = 1e6\n', "error", ["'gravity_m_s2'"])
add(P, "gravity-zero.toml", 'extends = "paper"\ngravity_m_s2 = 0\n', "error", ["'gravity_m_s2'"])
add(P, "h-zero.toml", 'extends = "paper"\nheat_transfer_W_m2K = 0\n', "error", ["'heat_transfer_W_m2K'"])
add(P, "specific-heat-zero.toml", 'extends = "paper"\ndrum_specific_heat_J_kgK = 0\n', "error",
    ["'drum_specific_heat_J_kgK'"])
add(P, "cg-behind-rear-axle.toml", 'extends = "paper"\ncg_behind_front_m = 2.6\n', "error", ["'cg_behind_front_m'"])
add(P, "mu-drum-high.toml", 'extends = "paper"\nmu_drum = 2.5\n', "error", ["'mu_drum'"])
add(P, "occupant-mass-ton.toml", 'extends = "paper"\noccupant_mass_kg = 1000\n', "error", ["'occupant_mass_kg'"])
add(P, "u6-slope-negative.toml", 'extends = "paper"\nu6_slope_m_per_N = -1e-7\n', "error", ["'u6_slope_m_per_N'"])
add(P, "syntax.toml", 'extends = "paper"\nmu_drum = \n', "error", ["line 2"])
add(P, "not-utf8.toml", b'extends = "paper"\n# \xff\xfe\n', "error", ["UTF-8"])
COV3 = '[covariance]\nnames = ["mu_drum", "heat_transfer_W_m2K", "u6_offset_m"]\nmatrix = '
add(P, "ok-covariance-zero-rows.toml", 'extends = "paper"\n' + COV3 + '[[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1e-10]]\n',
    "accept", note="zero variances: parameters held fixed")
add(P, "covariance-negative-variance.toml", 'extends = "paper"\n' + COV3 + '[[-1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]]\n',
    "error", ["'covariance.matrix[0][0]'", "negative variance"])
add(P, "covariance-fixed-but-correlated.toml", 'extends = "paper"\n' + COV3 +
    '[[0.0, 1e-30, 0.0], [1e-30, 0.0, 0.0], [0.0, 0.0, 4.0]]\n', "error", ["'covariance.matrix[0][1]'", "held fixed"])
add(P, "covariance-inconsistent.toml", 'extends = "paper"\n' + COV3 +
    '[[1.0, 0.9, -0.9], [0.9, 1.0, 0.9], [-0.9, 0.9, 1.0]]\n', "error", ["'covariance.matrix'", "semi-definite"])
add(P, "covariance-nan.toml", 'extends = "paper"\n' + COV3 + '[[1.0, 0, 0], [0, nan, 0], [0, 0, 1.0]]\n', "error",
    ["'covariance.matrix[1][1]'"])
PRED = '[predictive]\nmodel_error_rel_sd = 0.01\nmodel_error_dof = 5\n'
add(P, "predictive-dof-nan.toml", 'extends = "paper"\n' + PRED.replace("= 5", "= nan"), "error",
    ["'predictive.model_error_dof'"])
add(P, "predictive-alternative-missing.toml", 'extends = "paper"\n' + PRED +
    'alternatives = [{ weight = 0.3, file = "gone.toml" }]\n', "error", ["'predictive.alternatives[0].file'"])
add(P, "predictive-alternative-itself.toml", 'extends = "paper"\n' + PRED +
    'alternatives = [{ weight = 0.3, file = "predictive-alternative-itself.toml" }]\n', "error", ["itself"])
add(P, "effect-unknown.toml", 'extends = "paper"\n[effects.lining_crep]\nrelaxed_fraction = 0.1\n', "error",
    ["lining_crep", "lining_creep"])
add(P, "effect-value-nan.toml", 'extends = "paper"\n[effects.lining_creep]\nrelaxed_fraction = nan\n', "error",
    ["'effects.lining_creep.relaxed_fraction'"])
add(P, "effects-not-a-table.toml", 'extends = "paper"\neffects = []\n', "error", ["'effects'"])

W = "sweep"
(ROOT / W).mkdir(parents=True, exist_ok=True)
(ROOT / W / "base-ok.toml").write_text(sc())
(ROOT / W / "base-bad.toml").write_text(sc(hand_force_N="nan"))
HEAD = 'base_preset = "fmvss135"\nsimulate = "none"\n'
add(W, "ok-grid.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, num = 5 }\noccupants = [1, 5]\n", "accept")
add(W, "ok-step.toml", HEAD + "[grid]\ngrade_pct = { start = 40, stop = 0, step = 10 }\n", "accept")
add(W, "ok-base-file.toml", 'base = "base-ok.toml"\nsimulate = "none"\n[grid]\nhand_force_N = [200, 400]\n', "accept")
add(W, "ok-points.toml", HEAD + "[[points]]\ngrade_pct = 30\nhand_force_N = 445\n[[points]]\noccupants = 0\n", "accept")
add(W, "ok-bom.toml", "\ufeff" + HEAD + "[grid]\ngrade_pct = [10, 20]\n", "accept")
add(W, "ok-out-of-range-point.toml", HEAD + "[grid]\ngrade_pct = [20, 150]\n", "accept",
    note="a value the model cannot take is a row with its error, not a refused sweep")
add(W, "step-denormal.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, step = 5e-324 }\n", "error",
    ["'grade_pct'", "step"])
add(W, "range-huge.toml", HEAD + "[grid]\ngrade_pct = { start = -1e308, stop = 1e308, num = 3 }\n", "error",
    ["'grade_pct'"])
add(W, "range-huge-step.toml", HEAD + "[grid]\nhand_force_N = { start = -1e308, stop = 1e308, step = 1 }\n", "error",
    ["'hand_force_N'"])
add(W, "num-zero.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, num = 0 }\n", "error", ["'num'"])
add(W, "num-huge.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, num = 3000000 }\n", "error", ["'num'"])
add(W, "step-zero.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, step = 0 }\n", "error", ["'step'"])
add(W, "step-nan.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, step = nan }\n", "error", ["'step'"])
add(W, "num-and-step.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 40, num = 3, step = 1 }\n", "error",
    ["'grade_pct'", "num"])
add(W, "range-no-stop.toml", HEAD + "[grid]\ngrade_pct = { start = 0, num = 3 }\n", "error", ["'stop'"])
add(W, "range-inf.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = inf, num = 3 }\n", "error", ["'stop'"])
add(W, "range-unknown-key.toml", HEAD + "[grid]\ngrade_pct = { from = 0, stop = 40, num = 3 }\n", "error", ["'from'"])
add(W, "grid-too-big.toml", HEAD + "[grid]\ngrade_pct = { start = 0, stop = 50, num = 2000 }\n"
    "hand_force_N = { start = 0, stop = 600, num = 2000 }\n", "error", ["[grid]", "max 2000000"])
add(W, "base-missing.toml", 'base = "nowhere.toml"\n[grid]\ngrade_pct = [10]\n', "error", ["'base'", "nowhere.toml"])
add(W, "base-folder.toml", 'base = "."\n[grid]\ngrade_pct = [10]\n', "error", ["'base'", "folder"])
add(W, "base-invalid.toml", 'base = "base-bad.toml"\n[grid]\ngrade_pct = [10]\n', "error",
    ["key 'base'", "base-bad.toml", "'hand_force_N'"])
add(W, "base-and-preset.toml", 'base = "base-ok.toml"\nbase_preset = "fmvss135"\n[grid]\ngrade_pct = [10]\n',
    "error", ["'base'", "'base_preset'"])
add(W, "no-base.toml", "[grid]\ngrade_pct = [10]\n", "error", ["'base'"])
add(W, "preset-unknown.toml", 'base_preset = "fmvss1355"\n[grid]\ngrade_pct = [10]\n', "error", ["base_preset"])
add(W, "simulate-maybe.toml", 'base_preset = "fmvss135"\nsimulate = "maybe"\n[grid]\ngrade_pct = [10]\n', "error",
    ["'simulate'"])
add(W, "band-reversed.toml", HEAD + "band = [1.1, 0.9]\n[grid]\ngrade_pct = [10]\n", "error", ["'band'"])
add(W, "band-nan.toml", HEAD + "band = [nan, 1.1]\n[grid]\ngrade_pct = [10]\n", "error", ["'band'"])
add(W, "unknown-top-key.toml", HEAD + "grids = 3\n[grid]\ngrade_pct = [10]\n", "error", ["'grids'"])
add(W, "grid-not-table.toml", HEAD + "grid = 3\n", "error", ["'grid'"])
add(W, "points-not-tables.toml", HEAD + "points = [1, 2]\n", "error", ["'points'"])
add(W, "points-unknown-axis.toml", HEAD + "[[points]]\ngrade = 30\n", "error", ["'grade'", "[[points]] #1"])
add(W, "points-string-value.toml", HEAD + "[[points]]\ngrade_pct = \"30\"\n", "error", ["'grade_pct'", "#1"])
add(W, "direction-sideways.toml", HEAD + "[grid]\ndirection = [\"sideways\"]\n", "error", ["'direction'"])
add(W, "direction-range.toml", HEAD + "[grid]\ndirection = { start = 0, stop = 1, num = 2 }\n", "error", ["'direction'"])
add(W, "grid-empty-list.toml", HEAD + "[grid]\ngrade_pct = []\n", "error", ["'grade_pct'", "empty"])
add(W, "grid-unknown-axis.toml", HEAD + "[grid]\ngrade = [10]\n", "error", ["'grade'"])
add(W, "nothing-to-sweep.toml", HEAD, "error", ["nothing to sweep"])
add(W, "syntax.toml", HEAD + "[grid\n", "error", ["line 3"])
add(W, "description-number.toml", HEAD + "description = 5\n[grid]\ngrade_pct = [10]\n", "error", ["'description'"])

B = "bench"
VALID = (Path(sys.argv[2]).read_text())
(ROOT / B).mkdir(parents=True, exist_ok=True)
lines = VALID.splitlines()
hdr = lines[0]
def csv(rows, header=hdr):
    return "\n".join([header] + rows) + "\n"
add(B, "ok-valid.csv", VALID, "accept")
add(B, "ok-bom-crlf.csv", "\ufeff" + VALID.replace("\n", "\r\n"), "accept")
add(B, "ok-extra-column.csv", csv([l + ",x" for l in lines[1:]], hdr + ",operator"), "accept")
add(B, "ok-quoted.csv", csv(['"' + l.split(",")[0] + '",' + ",".join(l.split(",")[1:]) for l in lines[1:]]), "accept")
add(B, "huge-cell.csv", csv([lines[1].replace(lines[1].split(",")[4], "9" * 140000, 1)] + lines[2:]), "error",
    ["line 2"])
add(B, "unterminated-quote.csv", csv(['"' + lines[1]] + lines[2:]), "error", ["line"])
add(B, "nul-byte.csv", csv(lines[1:2] + ["\x00" + lines[2]] + lines[3:]), "error", ["line 3"])
add(B, "not-utf8.csv", csv(lines[1:]).encode() + b"\xff\xfe\n", "error", ["UTF-8"])
add(B, "empty.csv", "", "error", ["line 1", "empty"])
add(B, "header-only.csv", hdr + "\n", "error", ["line 2"])
add(B, "missing-column.csv", csv([",".join(l.split(",")[:5] + l.split(",")[6:]) for l in lines[1:]],
    "test_id,direction,hand_force_N,time_s,drum_temp_C,ambient_C"), "error", ["'torque_Nm'"])
add(B, "renamed-column.csv", csv(lines[1:], hdr.replace("torque_Nm", "torque_Nm_axle")), "error",
    ["'torque_Nm'", "torque_Nm_axle"])
add(B, "duplicate-column.csv", csv([l + "," + l.split(",")[5] for l in lines[1:]], hdr + ",torque_Nm"), "error",
    ["'torque_Nm'", "duplicate"])
add(B, "field-count.csv", csv(lines[1:3] + [lines[3] + ",1,2"] + lines[4:]), "error", ["line 4"])
def cell(row, col, value):
    parts = lines[row].split(","); parts[col] = value; return ",".join(parts)
add(B, "not-a-number.csv", csv([lines[1], cell(2, 5, "12O.5")] + lines[3:]), "error", ["line 3", "'torque_Nm'"])
add(B, "nan-torque.csv", csv([lines[1], cell(2, 5, "nan")] + lines[3:]), "error", ["line 3", "'torque_Nm'"])
add(B, "inf-temp.csv", csv([lines[1], cell(2, 4, "inf")] + lines[3:]), "error", ["line 3", "'drum_temp_C'"])
add(B, "hand-force-out-of-range.csv", csv([cell(i, 2, "9000") for i in range(1, len(lines))]), "error",
    ["line 2", "'hand_force_N'"])
add(B, "direction-unknown.csv", csv([cell(1, 1, "sideways")] + lines[2:]), "error", ["line 2", "'direction'"])
add(B, "time-decreases.csv", csv([lines[1], lines[3], lines[2]] + lines[4:]), "error", ["'time_s'"])
add(B, "starts-late.csv", csv(lines[2:]), "error", ["'time_s'"])
add(B, "empty-test-id.csv", csv([cell(1, 0, "")] + lines[2:]), "error", ["line 2", "'test_id'"])
rows = [l.split(",") for l in lines[1:]]
def joined(rs, header=hdr):
    return csv([",".join(r) for r in rs], header)
def with_time(f):
    return [r[:3] + [f(float(r[3]))] + r[4:] for r in rows]
add(B, "time-in-ms-no-unit.csv", joined(with_time(lambda t: f"{t * 1000:g}")), "error",
    ["'time_s'", "looks like ms", "time_s=time_s[ms]"], note="a DAQ export in ms with no unit in the header")
add(B, "ok-time-in-ms-with-unit.csv", joined(with_time(lambda t: f"{t * 1000:g}"), hdr.replace("time_s", "time_s [ms]")),
    "accept")
add(B, "time-epoch.csv", joined(with_time(lambda t: f"{t + 1.7e9:.1f}")), "error", ["'time_s'", "Unix time stamp"])
pre = []
for r in rows:
    if r[3] == "0":
        pre.append(r[:3] + ["-30"] + r[4:])
    pre.append(r)
add(B, "ok-rows-before-the-lever.csv", joined(pre), "accept", note="rows before time 0: not used, said on stderr")
add(B, "duplicate-timestamp.csv", joined(rows[:2] + [rows[1]] + rows[2:]), "error", ["line 4", "duplicate time"])
add(B, "ambient-all-empty.csv", joined([r[:6] + [""] for r in rows]), "error", ["line 2", "'ambient_C'"])
add(B, "ok-semicolons-decimal-commas.csv", "\n".join([hdr.replace(",", ";")] + [";".join(c.replace(".", ",") for c in r)
                                                                            for r in rows]) + "\n", "accept")
add(B, "ok-tab-separated.csv", "\n".join([hdr.replace(",", "\t")] + ["\t".join(r) for r in rows]) + "\n", "accept")
add(B, "ok-spaces-after-commas.csv", csv([", ".join(r) for r in rows], ", ".join(hdr.split(","))), "accept")
add(B, "ok-interleaved-tests.csv", joined([r for pair in zip(rows[:5], rows[5:10]) for r in pair] + rows[10:]),
    "accept", note="rows of two tests alternate")
add(B, "decimal-comma-with-comma-separator.csv", joined([rows[0][:4] + ["205,464"] + rows[0][5:]] + rows[1:]),
    "error", ["line 2", "fields"])
add(B, "unit-only-header.csv", joined(rows, "[-],[-],[N],[s],[degC],[Nm],[degC]"), "error", ["line 1", "units but no column names"])
add(B, "na-in-torque.csv", joined([rows[0][:5] + ["NA"] + rows[0][6:]] + rows[1:]), "error", ["line 2", "'torque_Nm'"])
add(B, "column-for-two-quantities.csv", VALID, "error", ["'drum_temp_C'", "read as both"],
    args=["--columns", "torque_Nm=drum_temp_C"])
degc = hdr.replace("drum_temp_C", "T_drum [degC]")
add(B, "unit-map-disagrees.csv", joined(rows, degc), "error", ["'T_drum [degC]'", "°C", "°F", "!"],
    args=["--columns", "drum_temp_C=T_drum[degF]"])
add(B, "ok-unit-map-overrides.csv", joined(rows, degc), "accept", args=["--columns", "drum_temp_C=T_drum[degF]!"],
    note="an override stated with '!': noted on stderr and in the JSON")
tests = {}
for r in rows:
    tests.setdefault(r[0], []).append(r)
man = "test_id,direction,hand_force_N\n" + "".join(f"{t},{rs[0][1]},{rs[0][2]}\n" for t, rs in tests.items())
per = {f"{t}.csv": "time_s,drum_temp_C,torque_Nm,ambient_C\n" + "".join(",".join(r[3:]) + "\n" for r in rs)
       for t, rs in tests.items()}
first = next(iter(tests))
add(B, "ok-folder", {"manifest.csv": man, **per}, "accept")
add(B, "folder-manifest-lists-a-test-twice", {"manifest.csv": man + f"{first},downhill,300\n", **per}, "error",
    ["manifest.csv, line 6", f"'{first}'", "twice", "line 2"])
add(B, "folder-manifest-row-without-file", {"manifest.csv": man, **{k: v for k, v in list(per.items())[1:]}}, "error",
    ["manifest.csv, line 2", f"'{first}'", "no data"])
add(B, "folder-file-without-row", {"manifest.csv": "".join(man.splitlines(True)[:-1]), **per}, "error",
    ["no manifest entry"])
add(B, "folder-empty-test-file", {"manifest.csv": man, **per, f"{first}.csv": "time_s,drum_temp_C,torque_Nm,ambient_C\n"},
    "error", [f"{first}.csv, line 2", "no data rows"])
add(B, "folder-direction-disagrees", {"manifest.csv": man, **{k: "direction," + v.splitlines()[0] + "\n" + "".join(
    ("uphill," if k == f"{first}.csv" else f"{tests[k[:-4]][0][1]},") + l + "\n" for l in v.splitlines()[1:])
    for k, v in per.items()}}, "error", [f"{first}.csv, line 2", "uphill here but downhill", "manifest.csv, line 2"])
(ROOT / B / "aux").mkdir(parents=True, exist_ok=True)
(ROOT / B / "aux" / "manifest-of-single.csv").write_text(man)
add(B, "ok-single-log-with-manifest.csv", joined([[r[0]] + r[3:] for r in rows],
    "test_id,time_s,drum_temp_C,torque_Nm,ambient_C"), "accept", args=["--manifest", "{corpus}/bench/aux/manifest-of-single.csv"])
add(B, "single-log-force-disagrees-with-manifest.csv", joined([r[:2] + ["260" if r[0] == first else r[2]] + r[3:]
    for r in rows]), "error", ["line 2", "260 N here but 250 N", "manifest-of-single.csv, line 2"],
    args=["--manifest", "{corpus}/bench/aux/manifest-of-single.csv"])

E = "plugin"
(ROOT / E).mkdir(parents=True, exist_ok=True)
(ROOT / E / "data.csv").write_text(VALID)     # the plugin files themselves: plugin_cases.py, written at test time

(ROOT / "manifest.json").write_text(json.dumps({"cases": cases}, indent=1, ensure_ascii=True) + "\n")
print(len(cases), "cases")
