#!/usr/bin/env bash
# Quick start: install everything (system libraries included), then run the main job on the bundled defaults.
set -euo pipefail
cd "$(dirname "$0")"
bash scripts/install.sh
export MUJOCO_GL="${MUJOCO_GL:-egl}"
echo; echo "== 1. compliance gate: FMVSS 135 + UN R13-H simulated in MuJoCo"
rollaway check
echo; echo "== 2. the paper's analytic check of every preset (exit 1 means a case fails: read its reason)"
rollaway check --analytic all || echo "[quickstart] rollaway check --analytic all exited $?: a case fails, see the reason column"
echo; echo "== 3. hot parking: the drum cools and the brake lets go"
rollaway simulate scenarios/hot-parking-rollaway.toml --render renders/quickstart/hot-parking-rollaway.mp4 \
  --json renders/quickstart/hot-parking-rollaway.json
echo; echo "== 4. sweep: grade x occupants x hand force, MuJoCo on the hold/roll boundary"
rollaway sweep scenarios/sweeps/grade-load.toml --out out/grade-load --quiet
echo; echo "== 5. the paper's Figures 9-14"
rollaway paper
echo; echo "== 6. from bench data to the road: diagnose bundled bench data, save the calibrated model, ask again"
mkdir -p out
rollaway diagnose examples/identify/bench-hidden-effect.csv --save-model out/calibrated.toml --report out/diagnose.html \
  > out/diagnose.txt
head -1 out/diagnose.txt; tail -1 out/diagnose.txt
rollaway hold --grade-pct 30 --hand-force-N 250 --occupants 5 --duration-s 3600 | tail -1 | sed 's/^/  paper model:      /' || true
rollaway hold --grade-pct 30 --hand-force-N 250 --occupants 5 --duration-s 3600 --params out/calibrated.toml \
  --uncertainty 1000 | tail -3 | sed 's/^/  calibrated model: /' || true
rollaway chart --params paper --params out/calibrated.toml --out out/design-chart-calibrated.png
echo; echo "== 7. your own brake: a drum that is not the paper's, tested facing downhill only"
rollaway diagnose examples/identify/bench-own-drum-downhill.csv --save-model out/own-drum.toml > out/own-drum.txt
head -1 out/own-drum.txt; sed -n '/^Your drum/,/^$/p' out/own-drum.txt | cut -c1-150
rollaway hold --grade-pct 20 --hand-force-N 300 --occupants 1 --duration-s 3600 --direction uphill \
  --params out/own-drum.toml --uncertainty 1000 | tail -3 || true
echo; echo "== 8. the calibrated drum for Simulink, Dymola, OpenModelica: an FMI 2.0 FMU that runs without rollaway"
rollaway export-fmu --params out/calibrated.toml out/calibrated.fmu
python -m fmpy validate out/calibrated.fmu
echo; echo "== 9. a production fleet: roll-away rate in ppm with its interval, what drives it, the least hand force for 0.1 ppm"
rollaway risk scenarios/populations/fmvss135-production.toml --sensitivity --design hand_force_N --target 1e-7 \
  --chart out/fleet-risk.png --quiet
echo
echo "== done. What was written, and what to open:"
echo "  renders/quickstart/hot-parking-rollaway.mp4   the car rolling away when the drum has cooled (open it)"
echo "  renders/quickstart/hot-parking-rollaway.json  that simulation's result as data"
echo "  out/grade-load/plots/design-chart.png          least hand force against grade, per load (open it)"
echo "  out/grade-load/plots/map-grade-*.png           hold / roll-away maps; results.csv holds every point"
echo "  renders/paper/fig09..fig14*.png                the paper's Figures 9-14 redrawn"
echo "  out/diagnose.html, out/calibrated.toml         the missing effect found in bench data; the calibrated model"
echo "  out/design-chart-calibrated.png                least hand force: paper model vs calibrated model (open it)"
echo "  out/own-drum.txt, out/own-drum.toml            your own brake: the identifiability report; its calibrated model"
echo "  out/calibrated.fmu                             the calibrated drum as an FMU (docs/how-to/fmu-export.md)"
echo "  out/fleet-risk.png, out/fleet-risk-design.png  a fleet's drivers (Sobol indices) and rate against hand force"
echo "  docs/model.md                                  the model, equation by equation"
