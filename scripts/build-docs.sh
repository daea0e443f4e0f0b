#!/usr/bin/env bash
# Build the documentation site into site/ (or $SITE_DIR): the tutorials (docs/tutorials/*.py, jupytext percent
# notebooks) are executed, the API reference is read from the docstrings, and any warning (a broken
# link, a failing tutorial cell, an unknown docstring parameter) fails the build.
# Needs the docs extra: bash scripts/install.sh installs it (or: pip install -e '.[docs]').
set -euo pipefail
cd "$(dirname "$0")/.."
export MUJOCO_GL="${MUJOCO_GL:-egl}"        # the MuJoCo tutorial renders a GIF off-screen
export PYTHONPATH="$PWD/src${PYTHONPATH:+:$PYTHONPATH}"   # the tutorials and the API page document this checkout
export NO_MKDOCS_2_WARNING=1                # (MkDocs 2 notice of the Material theme: not a warning of this build)
# pictures the pages show that the repository keeps beside the README
mkdir -p docs/assets
cp renders/design-chart.png renders/hot-parking-rollaway.gif docs/assets/
cp renders/fmu-vs-rollaway.png docs/assets/           # scripts/fmu-figure.py draws it (FMU export how-to)
start=$(date +%s)
site="${SITE_DIR:-site}"                    # where to build (default: site/)
python -m mkdocs build --strict --clean --site-dir "$site"
python scripts/check-links.py "$site"
echo "[build-docs] $site/ built in $(( $(date +%s) - start )) s: open $site/index.html"
