#!/usr/bin/env bash
# Quick start: install everything, then run the main job on the bundled defaults.
set -euo pipefail
cd "$(dirname "$0")"
bash scripts/install.sh
rollaway check --analytic
rollaway paper
