#!/usr/bin/env bash
# Soak tests: the long runs CI cannot afford, for a release or after a change to the solver or
# the frame loop. Needs a release build (cmake --preset release && cmake --build --preset release).
#
#   scripts/soak.sh [sim|view|all]     default: all
#
#   sim   nalu's physics for 1,000,000 fixed steps (bench/soak.cpp): no particle ever NaN or
#         infinite, the kinetic energy never above 2× its settled value. About 20 minutes of
#         one core.
#   view  `mane view` on nalu under Xvfb for 10 minutes: the resident memory at the end within
#         5 % of the resident memory one minute in (a leak of a few kB a frame shows as tens of MB).
#
# Overrides: SOAK_STEPS (sim), SOAK_VIEW_SECONDS (view, ≥ 120), MANE_BUILD (default build/release).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MANE_BUILD:-$root/build/release}"
what="${1:-all}"

soakSim() {
  "$build/bench/mane_soak" "$root/scenes/nalu.json" --steps "${SOAK_STEPS:-1000000}" --bound 2
}

# VmRSS of a process, kB.
residentKb() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status"; }

soakView() {
  local seconds="${SOAK_VIEW_SECONDS:-600}"
  if ((seconds < 120)); then echo "soak.sh: SOAK_VIEW_SECONDS must be at least 120" >&2; return 2; fi
  command -v Xvfb >/dev/null || { echo "soak.sh: Xvfb not found (apt-get install xvfb)" >&2; return 2; }
  local display=":$((90 + RANDOM % 100))"
  Xvfb "$display" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
  local xvfb=$!
  sleep 2
  DISPLAY="$display" "$build/mane" view "$root/scenes/nalu.json" >/dev/null 2>&1 &
  local view=$!
  trap 'kill $view $xvfb 2>/dev/null || true' RETURN
  local minute=0 now=0 t
  for ((t = 10; t <= seconds; t += 10)); do
    sleep 10
    kill -0 "$view" 2>/dev/null || { echo "soak.sh: mane view exited after ${t} s" >&2; return 1; }
    now=$(residentKb "$view")
    ((t == 60)) && minute=$now
    ((t % 60 == 0)) && echo "view: ${t} s, resident ${now} kB"
  done
  # Within 5 %: the end no more than 1.05 times the value a minute in.
  if ((now * 100 > minute * 105)); then
    echo "view: FAILED: resident memory grew from ${minute} kB at 60 s to ${now} kB at ${seconds} s" >&2
    return 1
  fi
  echo "view: resident ${minute} kB at 60 s, ${now} kB at ${seconds} s: within 5 %"
}

case "$what" in
  sim) soakSim ;;
  view) soakView ;;
  all) soakSim && soakView ;;
  *) echo "usage: scripts/soak.sh [sim|view|all]" >&2; exit 2 ;;
esac
