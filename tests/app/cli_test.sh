#!/usr/bin/env bash
# Tests of the `mane` program as a user runs it. Usage: cli_test.sh MANE CASE
set -uo pipefail
mane=$1
case=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

case $case in
  info-names-lavapipe)
    out=$(MANE_DEVICE=lavapipe "$mane" info) || fail "mane info exited $?"
    grep -q "llvmpipe" <<<"$out" || fail "no llvmpipe in: $out"
    grep -q "vulkan:  1.3" <<<"$out" || fail "no Vulkan 1.3 in: $out"
    ;;
  sim-hash-independent-of-threads)
    # DESIGN.md: same scene and steps → same hash whatever the thread count.
    hashes=()
    for threads in 1 2 4; do
      line=$("$mane" sim --steps 120 --threads "$threads" | tail -n 1) || fail "sim --threads $threads failed"
      [[ $line =~ ^state-hash:\ [0-9a-f]{16}$ ]] || fail "last line is not a state hash: $line"
      hashes+=("$line")
    done
    [ "${hashes[0]}" = "${hashes[1]}" ] && [ "${hashes[0]}" = "${hashes[2]}" ] || fail "hashes differ: ${hashes[*]}"
    again=$("$mane" sim --steps 120 --threads 2 | tail -n 1)
    [ "$again" = "${hashes[0]}" ] || fail "a second run gave $again, not ${hashes[0]}"
    moved=$("$mane" sim --steps 121 | tail -n 1)
    [ "$moved" != "${hashes[0]}" ] || fail "one more step left the hash unchanged"
    ;;
  sim-ponytail-independent-of-threads)
    # Real data: the TressFX ponytail (4,933 guides × 16) on a shaking head.
    one=$("$mane" sim scenes/ponytail.json --steps 60 --threads 1 | tail -n 1) || fail "sim failed"
    four=$("$mane" sim scenes/ponytail.json --steps 60 --threads 4 | tail -n 1) || fail "sim failed"
    [ "$one" = "$four" ] || fail "1 thread: $one, 4 threads: $four"
    "$mane" sim scenes/ponytail.json --steps 1 | grep -q "4933 guide strands, 78928 particles" || fail "not the ponytail"
    ;;
  render-writes-png)
    "$mane" render --out "$scratch/out" --size 160x90 --msaa 1 >"$scratch/log" 2>&1 || fail "render failed: $(cat "$scratch/log")"
    png=$(ls "$scratch"/out/*.png) || fail "no PNG written"
    [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$png is not a PNG"
    # IHDR (bytes 16..23): width and height, big-endian, as asked with --size.
    [ "$(od -An -tx1 -j16 -N8 "$png" | tr -d ' \n')" = "000000a00000005a" ] || fail "$png is not 160x90"
    grep -q "wrote .*\.png" "$scratch/log" || fail "no 'wrote' line"
    grep -q "^surfaces " "$scratch/log" || fail "no per-pass time for surfaces"
    ;;
  cape-sequence)
    # A simulated sequence: cloth uploaded every frame, frames numbered, the timing table.
    "$mane" render scenes/cape.json --frames 3 --size 160x90 --msaa 1 --out "$scratch/out" >"$scratch/log" 2>&1 ||
      fail "render failed: $(cat "$scratch/log")"
    [ "$(ls "$scratch"/out/cape_000[0-2].png | wc -l)" -eq 3 ] || fail "expected 3 frames: $(ls "$scratch/out")"
    grep -q "^surfaces " "$scratch/log" || fail "no timing table"
    ;;
  bad-scene-one-line-error)
    printf '{ "name": "broken", "camera": { "fov_degrees": "wide" } ' >"$scratch/broken.json"
    "$mane" render "$scratch/broken.json" --out "$scratch/out" 2>"$scratch/err" >/dev/null && fail "exit status 0"
    [ "$(wc -l <"$scratch/err")" -eq 1 ] || fail "expected one line, got: $(cat "$scratch/err")"
    grep -q "^mane: .*broken.json" "$scratch/err" || fail "the error does not name the file: $(cat "$scratch/err")"
    "$mane" render --size 12by7 --out "$scratch/out" 2>"$scratch/err" >/dev/null && fail "bad --size accepted"
    grep -q "WIDTHxHEIGHT" "$scratch/err" || fail "bad --size message: $(cat "$scratch/err")"
    ;;
  view-under-xvfb)
    # A real window on a virtual display, presented through the swapchain on lavapipe.
    xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view --frames 30 --screenshot "$scratch/view.png" \
      >"$scratch/log" 2>&1 || fail "mane view failed: $(cat "$scratch/log")"
    # The lit head compresses to well over 20 kB; an empty frame of one colour to about 4 kB.
    size=$(stat -c %s "$scratch/view.png") || fail "no screenshot"
    [ "$size" -gt 20000 ] || fail "the screenshot looks blank ($size bytes)"
    ;;
  help-for-each-command)
    for command in info render sim view; do
      "$mane" "$command" --help | grep -qi "usage" || fail "$command --help"
    done
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
