#!/usr/bin/env bash
# Builds the loader fuzzers (clang, libFuzzer + ASan + UBSan) in build/fuzz and runs each in
# turn, one process at a time.
#
#   tests/fuzz/run.sh [seconds] [harness...]     default: 60 s each, every harness
#                                                (a harness by its name, fuzz_obj, or its format, obj)
#
# Seeds: tests/fuzz/seeds/<harness>/ plus small files from ../shared/assets (or $MANE_ASSETS),
# linked into build/fuzz/seeds/ (never copied into the repository). The growing corpus lives
# in build/fuzz/corpus/<harness>/, findings in build/fuzz/artifacts/<harness>/, logs in
# build/fuzz/logs/. Exits non-zero when any harness reports a crash, leak, UB or timeout.
# Reproduce one: build/fuzz/tests/fuzz/fuzz_obj build/fuzz/artifacts/fuzz_obj/crash-…
#
# Needs clang >= 16 with libFuzzer (clang 14 cannot compile libstdc++ 12's std::expected):
#   apt-get install -y clang-16 libclang-rt-16-dev
set -euo pipefail

seconds="${1:-60}"
shift || true
harnesses=("$@")
[[ ${#harnesses[@]} -eq 0 ]] && harnesses=(fuzz_scene fuzz_gltf fuzz_obj fuzz_image fuzz_manifest fuzz_groom)
harnesses=("${harnesses[@]/#fuzz_/}") && harnesses=("${harnesses[@]/#/fuzz_}")  # "obj" = "fuzz_obj"

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build/fuzz"
assets="${MANE_ASSETS:-$root/../shared/assets}"
cxx="${FUZZ_CXX:-clang++-16}"
cc="${FUZZ_CC:-clang-16}"
if ! command -v "$cxx" >/dev/null; then
  echo "run.sh: $cxx not found; install it with: apt-get install -y clang-16 libclang-rt-16-dev" >&2
  exit 2
fi

cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" \
  -DMANE_FUZZ=ON -DMANE_BUILD_TESTS=OFF -DMANE_BUILD_BENCH=OFF >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target "${harnesses[@]}" -j "${FUZZ_BUILD_JOBS:-2}"

# Largest input worth mutating per format, bytes: big enough for every seed's structure.
declare -A maxLen=([fuzz_scene]=4096 [fuzz_gltf]=16384 [fuzz_obj]=8192 [fuzz_image]=16384
                   [fuzz_manifest]=4096 [fuzz_groom]=4096)
declare -A dict=([fuzz_scene]=json.dict [fuzz_gltf]=json.dict [fuzz_manifest]=json.dict
                 [fuzz_obj]=obj.dict)

# Small shared assets as extra seeds, by format (missing assets are simply skipped).
sharedSeeds() {
  case "$1" in
    fuzz_scene) ls "$root"/scenes/{sphere,nalu}.json ;;
    fuzz_gltf) find "$assets/gltf" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -64k ;;
    fuzz_obj) find "$assets/subdiv" "$assets/meshes" -type f -name '*.obj' -size -4k ;;
    fuzz_image) find "$assets" -type f \( -name '*.png' -o -name '*.jpg' \) -size -16k ;;
    fuzz_manifest) ls "$root/scenes/assets.json" ;;
    # The shipped .tfx/.hair files are 90 KB and up, far over max_len: synthetic seeds only.
    fuzz_groom) true ;;
  esac 2>/dev/null || true
}

# Scratch input files go to memory when it can hold them: the harnesses write one per run.
[[ -z "${TMPDIR:-}" && -d /dev/shm && -w /dev/shm ]] && export TMPDIR=/dev/shm

status=0
for name in "${harnesses[@]}"; do
  seeds="$build/seeds/$name"
  corpus="$build/corpus/$name"
  artifacts="$build/artifacts/$name"
  rm -rf "$seeds"
  mkdir -p "$seeds" "$corpus" "$artifacts" "$build/logs"
  while IFS= read -r file; do
    [[ -n "$file" ]] && ln -sf "$file" "$seeds/$(basename "$(dirname "$file")")_$(basename "$file")"
  done < <(sharedSeeds "$name")
  options=(-max_total_time="$seconds" -max_len="${maxLen[$name]}" -timeout=5 -rss_limit_mb=2048
           -print_final_stats=1 -artifact_prefix="$artifacts/")
  [[ -n "${dict[$name]:-}" ]] && options+=(-dict="$here/${dict[$name]}")
  echo "== $name: ${seconds} s, max_len ${maxLen[$name]} (log: build/fuzz/logs/$name.log)"
  if "$build/tests/fuzz/$name" "${options[@]}" "$corpus" "$here/seeds/${name#fuzz_}" "$seeds" \
       >"$build/logs/$name.log" 2>&1; then
    grep -E '^stat::number_of_executed_units|^Done ' "$build/logs/$name.log" || true
  else
    status=1
    echo "!! $name found a problem; see build/fuzz/logs/$name.log and $artifacts/"
    grep -E '^==[0-9]+==ERROR|runtime error|SUMMARY|Test unit written' "$build/logs/$name.log" |
      head -n 8 || true
  fi
done
exit "$status"
