#!/usr/bin/env bash
# Install rollaway and everything it needs on a fresh Debian machine (root, no GPU).
# System libraries: Mesa EGL/OSMesa for off-screen MuJoCo rendering; gcc (+ libc headers) builds exported FMUs.
set -euo pipefail
cd "$(dirname "$0")/.."
need=()
for pkg in libegl1 libegl-mesa0 libgl1-mesa-dri libosmesa6 gcc libc6-dev; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "[install] apt-get install ${need[*]}"
    log=$(mktemp)   # apt and debconf talk a lot: keep it in a log, show it only on failure
    if ! { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}"; } >"$log" 2>&1; then
      cat "$log" >&2; exit 1
    fi
  else
    echo "[install] missing system packages ${need[*]}: run 'sudo apt-get install -y ${need[*]}'" >&2
  fi
fi
echo "[install] pip install -e .[test,docs]"
# pip's output is shown without its notes about local index folders configured on this kind of
# machine but absent (harmless); every real warning and error is kept.
log=$(mktemp)
status=0
python -m pip install -q --disable-pip-version-check --root-user-action=ignore -e '.[test,docs]' >"$log" 2>&1 || status=$?
grep -v "is ignored: it is neither a file nor a directory" "$log" || true
rm -f "$log"
[ "$status" = 0 ] || { echo "[install] pip install failed (exit $status)" >&2; exit "$status"; }
# An editable install runs rollaway from src/ and pip compiles nothing there; where PYTHONDONTWRITEBYTECODE is set
# (as on this kind of machine) Python would then compile every module of rollaway again at each command (0.3-0.5 s
# of a diagnose).  Compiled once here, the modules are read (and recompiled only where a source file changed).
python -m compileall -q -j 0 src/rollaway >/dev/null
echo "[install] done: $(python -c 'import mujoco, rollaway; print("mujoco", mujoco.__version__, "rollaway", rollaway.__version__)')"
