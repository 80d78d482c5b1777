#!/usr/bin/env bash
# A sanitized build's tests as one entry of the normal suite (CTest label `sanitize`).
# Usage: sanitized_suite.sh asan|tsan — the presets of CMakePresets.json, built in build/<preset>.
#
#   tsan  configures and builds build/tsan when needed (the physics tests alone, a few minutes),
#         then runs them under ThreadSanitizer: the physics' thread pool and task runner are the
#         threads worth checking, and they are cheap to build.
#   asan  runs build/asan's `unit` and `determinism` labels under AddressSanitizer and
#         UndefinedBehaviorSanitizer once that tree exists, rebuilding what changed. Building it
#         from nothing (every library, the program and the test binaries) takes longer than the
#         whole normal suite, so this entry never starts it: it skips and says how.
#
# Exit status 77 (CTest's skip) when g++ cannot build and run a program with the sanitizers, or
# when build/asan has not been built.
set -uo pipefail
preset=${1:-}
cd "$(dirname "$0")/../.."
skip() { echo "SKIP: $*"; exit 77; }

case $preset in
  asan) sanitizers=address,undefined ;;
  tsan) sanitizers=thread ;;
  *) echo "usage: $0 asan|tsan" >&2; exit 2 ;;
esac

# The runtime libraries come with g++ (libasan, libubsan, libtsan); a compiler without them, or a
# kernel whose address layout the runtime refuses, fails here rather than in every test.
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
echo 'int main() { return 0; }' >"$probe/probe.cpp"
if ! g++ -fsanitize=$sanitizers "$probe/probe.cpp" -o "$probe/probe" >"$probe/log" 2>&1 ||
   ! "$probe/probe" >>"$probe/log" 2>&1; then
  skip "g++ cannot build and run a program with -fsanitize=$sanitizers: $(head -n 1 "$probe/log")"
fi

case $preset in
  asan)
    [ -f build/asan/CTestTestfile.cmake ] ||
      skip "build/asan does not exist. Build it once (every library and test binary with ASan and" \
           "UBSan; see the README's Tests section for the time it takes) with" \
           "'cmake --preset asan && cmake --build --preset asan'; this entry then runs its tests."
    ;;
  tsan)
    cmake --preset tsan >/dev/null || exit 1
    ;;
esac
cmake --build --preset "$preset" || exit 1
ctest --preset "$preset" -j 2
