#!/usr/bin/env bash
# The whole test suite: install what is missing, build the release preset (tests included),
# run every test through CTest. Validation layers are on in every GPU test.
set -euo pipefail
cd "$(dirname "$0")/.."
# clang 19: the second compiler of determinism.across-compilers (skipped without it).
bash scripts/install-deps.sh clang-19
cmake --preset release >/dev/null
cmake --build --preset release
# In CI the shared assets must be there: a missing one fails its tests instead of skipping them.
if [ "${CI:-}" = true ]; then export MANE_REQUIRE_ASSETS=1; fi
ctest --preset release -j 2
