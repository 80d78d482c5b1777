#!/usr/bin/env bash
# Builds the loader fuzzers (clang, libFuzzer + ASan + UBSan) in build/fuzz and runs each in
# turn, one process at a time.
#
#   tests/fuzz/run.sh [seconds] [harness...]    fuzz each harness for `seconds` (default 60)
#   tests/fuzz/run.sh --runs N [harness...]     fuzz each harness for N executions
#   tests/fuzz/run.sh --merge [harness...]      minimise the kept corpus (below)
#   --assets (before the rest)                  also seed from small files of ../shared/assets
#
# A harness is named by itself (fuzz_obj) or by its format (obj); none named: every harness.
#
# Inputs: the kept corpus tests/fuzz/corpus/<harness>/ (checked in, minimised), the hand-made
# seeds tests/fuzz/seeds/<harness>/ and, for the scene and manifest harnesses, scenes/*.json.
# New inputs go to build/fuzz/corpus/<harness>/; `--merge` folds them into the kept corpus
# (libFuzzer -merge=1 over the kept corpus, the build corpus and the seeds, into a fresh folder
# that then replaces the kept one), so the next run resumes where this one stopped.
#
# With --assets, small glTF, OBJ and image files from ../shared/assets (or $MANE_ASSETS) are
# linked in as extra seeds and what they lead to is kept apart, in build/fuzz/corpus-assets/:
# those files are third-party work, and --merge never reads that folder, so none of their bytes
# reach the repository.
#
# Findings go to build/fuzz/artifacts/<harness>/, logs to build/fuzz/logs/. Exits non-zero when
# any harness reports a crash, leak, undefined behaviour, timeout or memory blow-up.
# Reproduce one: build/fuzz/tests/fuzz/fuzz_obj build/fuzz/artifacts/fuzz_obj/crash-…
#
# Needs clang >= 16 with libFuzzer (clang 14 cannot compile libstdc++ 12's std::expected); the
# newest of clang 19, 18, 17, 16 found is used, or $FUZZ_CXX / $FUZZ_CC. Debian 12:
#   apt-get install -y clang-19 libclang-rt-19-dev
set -euo pipefail

mode=time
seconds=60
runs=0
withAssets=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --assets) withAssets=1 ;;
    --runs) mode=runs runs="$2"; shift ;;
    --merge) mode=merge ;;
    [0-9]*) seconds="$1" ;;
    *) break ;;
  esac
  shift
done
harnesses=("$@")
[[ ${#harnesses[@]} -eq 0 ]] && harnesses=(fuzz_scene fuzz_gltf fuzz_obj fuzz_image fuzz_manifest fuzz_groom fuzz_sim_state fuzz_environment fuzz_exr)
harnesses=("${harnesses[@]/#fuzz_/}") && harnesses=("${harnesses[@]/#/fuzz_}")  # "obj" = "fuzz_obj"

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build/fuzz"
assets="${MANE_ASSETS:-$root/../shared/assets}"
if [[ -z "${FUZZ_CXX:-}" ]]; then
  for version in 19 18 17 16; do
    if command -v "clang++-$version" >/dev/null; then
      FUZZ_CXX="clang++-$version" FUZZ_CC="${FUZZ_CC:-clang-$version}"
      break
    fi
  done
fi
cxx="${FUZZ_CXX:-clang++-19}"
cc="${FUZZ_CC:-${cxx/clang++/clang}}"
if ! command -v "$cxx" >/dev/null; then
  echo "run.sh: $cxx not found; install it with: apt-get install -y clang-19 libclang-rt-19-dev" >&2
  exit 2
fi

# Another compiler than the cached one: start the configuration afresh (CMake would otherwise
# reset the cache itself and drop the options below with it).
cached="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null || true)"
[[ -n "$cached" && "$(basename "$cached")" != "$(basename "$cxx")" ]] &&
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" \
  -DMANE_FUZZ=ON -DMANE_BUILD_TESTS=OFF -DMANE_BUILD_BENCH=OFF >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target "${harnesses[@]}" -j "${FUZZ_BUILD_JOBS:-2}"

# Largest input worth mutating per format, bytes: big enough for every seed's structure.
declare -A maxLen=([fuzz_scene]=8192 [fuzz_gltf]=16384 [fuzz_obj]=8192 [fuzz_image]=16384
                   [fuzz_manifest]=4096 [fuzz_groom]=4096 [fuzz_sim_state]=4096 [fuzz_environment]=16384
                   [fuzz_exr]=16384)
# A few images decode to hundreds of MB (any size up to loadImage's limit of 8192 x 8192 is
# legal, from a few KB of PNG or GIF) and take seconds each under the sanitizers: weight inputs
# by their speed to keep the search on the rest, and allow such a decode 20 s before calling it
# a hang (the rest: 5 s).
declare -A tuning=([fuzz_image]=-entropic_scale_per_exec_time=1)
declare -A timeout=([fuzz_image]=20)
declare -A dict=([fuzz_scene]=json.dict [fuzz_gltf]=json.dict [fuzz_manifest]=json.dict
                 [fuzz_obj]=obj.dict [fuzz_sim_state]=sim_state.dict)

# The project's own files that make good seeds, by format.
projectSeeds() {
  case "$1" in
    fuzz_scene) ls "$root"/scenes/*.json | grep -v '/assets\.json$' ;;
    fuzz_manifest) ls "$root/scenes/assets.json" ;;
  esac 2>/dev/null || true
}

# Small shared assets as extra seeds, by format (missing assets are simply skipped).
sharedSeeds() {
  case "$1" in
    fuzz_gltf) find "$assets/gltf" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -64k ;;
    fuzz_obj) find "$assets/subdiv" "$assets/meshes" -type f -name '*.obj' -size -4k ;;
    fuzz_image) find "$assets" -type f \( -name '*.png' -o -name '*.jpg' \) -size -16k ;;
    # The shipped .tfx/.hair files are 90 KB and up, far over max_len: synthetic seeds only.
  esac 2>/dev/null || true
}

linkSeeds() {  # folder, then the files to link into it
  local folder="$1" file
  shift
  rm -rf "$folder" && mkdir -p "$folder"
  for file in "$@"; do
    [[ -n "$file" ]] && ln -sf "$file" "$folder/$(basename "$(dirname "$file")")_$(basename "$file")"
  done
  return 0
}

# Scratch input files go to memory when it can hold them: the harnesses write one per run.
[[ -z "${TMPDIR:-}" && -d /dev/shm && -w /dev/shm ]] && export TMPDIR=/dev/shm

status=0
for name in "${harnesses[@]}"; do
  kept="$here/corpus/$name"
  handMade="$here/seeds/${name#fuzz_}"
  project="$build/seeds/$name"
  artifacts="$build/artifacts/$name"
  log="$build/logs/$name.log"
  mkdir -p "$kept" "$handMade" "$artifacts" "$build/logs"
  mapfile -t files < <(projectSeeds "$name")
  linkSeeds "$project" "${files[@]}"
  options=(-max_len="${maxLen[$name]}" -timeout="${timeout[$name]:-5}" -rss_limit_mb=2048 -print_final_stats=1
           -artifact_prefix="$artifacts/")
  [[ -n "${dict[$name]:-}" ]] && options+=(-dict="$here/${dict[$name]}")
  [[ -n "${tuning[$name]:-}" ]] && options+=("${tuning[$name]}")

  if [[ "$mode" == merge ]]; then
    fresh="$build/merged/$name"
    rm -rf "$fresh" && mkdir -p "$fresh" "$build/corpus/$name"
    echo "== $name: merging into tests/fuzz/corpus/$name (log: build/fuzz/logs/$name.merge.log)"
    if "$build/tests/fuzz/$name" -merge=1 "${options[@]}" "$fresh" "$kept" "$build/corpus/$name" \
         "$handMade" "$project" >"$build/logs/$name.merge.log" 2>&1; then
      rm -rf "$kept" && cp -r "$fresh" "$kept"
      echo "   $(ls "$kept" | wc -l) files, $(du -sh "$kept" | cut -f1)"
    else
      status=1
      echo "!! $name: merge failed; see build/fuzz/logs/$name.merge.log"
    fi
    continue
  fi

  corpus="$build/corpus/$name"
  extra=()
  if [[ "$withAssets" == 1 ]]; then
    corpus="$build/corpus-assets/$name"
    mapfile -t files < <(sharedSeeds "$name")
    linkSeeds "$build/seeds-assets/$name" "${files[@]}"
    extra=("$build/seeds-assets/$name" "$build/corpus/$name")
  fi
  mkdir -p "$corpus"
  if [[ "$mode" == runs ]]; then
    options+=(-runs="$runs")
    echo "== $name: $runs runs, max_len ${maxLen[$name]} (log: build/fuzz/logs/$name.log)"
  else
    options+=(-max_total_time="$seconds")
    echo "== $name: ${seconds} s, max_len ${maxLen[$name]} (log: build/fuzz/logs/$name.log)"
  fi
  if "$build/tests/fuzz/$name" "${options[@]}" "$corpus" "$kept" "$handMade" "$project" "${extra[@]}" \
       >"$log" 2>&1; then
    grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec|^Done ' "$log" || true
    grep -E '^#[0-9]+.*(DONE|pulse)' "$log" | tail -n 1 || true
  else
    status=1
    echo "!! $name found a problem; see build/fuzz/logs/$name.log and $artifacts/"
    grep -E '^==[0-9]+==ERROR|runtime error|SUMMARY|Test unit written' "$log" | head -n 8 || true
  fi
done
exit "$status"
