#!/usr/bin/env bash
# Quick start: install what is missing, build the release preset, render the default scene
# headless to out/. Extra arguments go to `mane render` (e.g. --frames 60 --size 640x360).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target mane
./build/release/mane render scenes/nalu.json --out out "$@"
