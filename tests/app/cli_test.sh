#!/usr/bin/env bash
# Tests of the `mane` program as a user runs it. Usage: cli_test.sh MANE CASE
set -uo pipefail
mane=$1
case=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# CTest's SKIP_RETURN_CODE for these cases (tests/app/CMakeLists.txt).
skip() { echo "SKIP: $*"; exit 77; }

# Counts, in PNG $1's box x0 y0 x1 y1 (pixels, ends excluded), the pure white and the pure black
# pixels: "WHITE BLACK". The overlay of `mane view` draws white text on a black panel
# (render/passes/text_overlay_pass.hpp); a rendered scene has neither over whole glyphs.
overlay_pixels() {
  python3 - "$@" <<'PY'
import struct, sys, zlib
path, x0, y0, x1, y1 = sys.argv[1], *map(int, sys.argv[2:6])
data = open(path, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat = 8, b""
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and colour in (2, 6), "only 8-bit RGB(A)"
        channels = 4 if colour == 6 else 3
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = previous[i], previous[i - channels] if i >= channels else 0
        if kind == 1: line[i] = (line[i] + a) & 255
        elif kind == 2: line[i] = (line[i] + b) & 255
        elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    previous = line
white = black = 0
for y in range(y0, min(y1, height)):
    for x in range(x0, min(x1, width)):
        r, g, b = rows[y][x * channels:x * channels + 3]
        white += r == g == b == 255
        black += r == g == b == 0
print(white, black)
PY
}

case $case in
  info-names-lavapipe)
    out=$(MANE_DEVICE=lavapipe "$mane" info) || fail "mane info exited $?"
    grep -q "llvmpipe" <<<"$out" || fail "no llvmpipe in: $out"
    grep -q "vulkan:  1.3" <<<"$out" || fail "no Vulkan 1.3 in: $out"
    ;;
  sim-hash-independent-of-threads)
    # Same scene and steps → same hash whatever the thread count (docs/design.md#determinism).
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
  sim-robot-independent-of-threads)
    # A skinned, animated character with hair and a cape that follow it: one hash for 1, 2 and 4
    # threads and for a second run, over 240 steps (2 s of walking: two loops of the clip).
    hashes=()
    for threads in 1 2 4 2; do
      line=$("$mane" sim scenes/robot.json --steps 240 --threads "$threads" | tail -n 1) || fail "sim failed"
      [[ $line =~ ^state-hash:\ [0-9a-f]{16}$ ]] || fail "last line is not a state hash: $line"
      hashes+=("$line")
    done
    for h in "${hashes[@]}"; do [ "$h" = "${hashes[0]}" ] || fail "hashes differ: ${hashes[*]}"; done
    ;;
  sim-trace-finds-perturbed-step)
    # The trace holds one "STEP HASH" line per fixed step from the loaded state (0) on; it does not
    # depend on the threads, and a particle moved before step 17 makes line 17 the first to differ.
    "$mane" sim --steps 30 --threads 1 --trace "$scratch/one.trace" >"$scratch/one.log" || fail "sim --trace failed"
    "$mane" sim --steps 30 --threads 2 --trace "$scratch/two.trace" >/dev/null || fail "sim --trace failed"
    "$mane" sim --steps 30 --threads 2 --trace "$scratch/moved.trace" --perturb 17 >/dev/null ||
      fail "sim --perturb failed"
    [ "$(wc -l <"$scratch/one.trace")" -eq 31 ] || fail "expected 31 lines (steps 0 to 30): $(wc -l <"$scratch/one.trace")"
    grep -qvE '^[0-9]+ [0-9a-f]{16}$' "$scratch/one.trace" && fail "a line is not 'STEP HASH': $(head -3 "$scratch/one.trace")"
    cmp -s "$scratch/one.trace" "$scratch/two.trace" || fail "the trace depends on the threads"
    [ "state-hash: $(tail -n 1 "$scratch/one.trace" | cut -d' ' -f2)" = "$(tail -n 1 "$scratch/one.log")" ] ||
      fail "the trace's last hash is not the printed state hash"
    # diff exits 1 when the files differ, which is the point here.
    first=$({ diff "$scratch/one.trace" "$scratch/moved.trace" || true; } | grep -m1 '^>' | cut -d' ' -f2)
    [ "$first" = 17 ] || fail "the first differing step is '$first', not 17"
    "$mane" sim --steps 30 --perturb 31 2>"$scratch/err" >/dev/null && fail "--perturb past the end accepted"
    grep -q "^mane: --perturb 31 is past the last step 30$" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    ;;
  sim-save-state-and-hair)
    # --save FILE --at STEPS: one state file per step (docs/sim-state-format.md) and each groom as a
    # HAIR file, with the counts of the loaded groom (762 guides × 16 points on nalu's head).
    "$mane" sim --steps 12 --save "$scratch/saved/nalu.msim" --at 0,12 >"$scratch/log" || fail "sim --save failed"
    for step in 000000 000012; do
      state="$scratch/saved/nalu_$step.msim"
      [ "$(head -c 8 "$state" | od -An -c | tr -d ' ')" = 'MANESIM\0' ] || fail "$state has no MANESIM signature"
      [ "$(od -An -tu4 -j24 -N4 "$state" | tr -d ' ')" = "$((10#$step))" ] || fail "$state is not step $step"
      hair=$(ls "$scratch"/saved/nalu_${step}_*.hair) || fail "no .hair for step $step: $(ls "$scratch/saved")"
      [ "$(head -c 4 "$hair")" = HAIR ] || fail "$hair is no HAIR file"
      # Hair count and point count: bytes 4..11, little-endian.
      [ "$(od -An -tu4 -j4 -N8 "$hair" | tr -s ' ')" = " 762 12192" ] || fail "$hair counts: $(od -An -tu4 -j4 -N8 "$hair")"
      grep -q "^wrote .*nalu_$step.msim$" "$scratch/log" || fail "no 'wrote' line for step $step"
    done
    cmp -s "$scratch"/saved/nalu_000000_*.hair "$scratch"/saved/nalu_000012_*.hair && fail "the groom did not move"
    "$mane" sim --steps 12 --save "$scratch/x.msim" --at 13 2>"$scratch/err" >/dev/null && fail "--at 13 accepted"
    grep -q "^mane: --at 13 is past the last step 12$" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    ;;
  sim-json-version-and-usage-errors)
    # --json: one JSON object on stdout; --version: the project's version; a usage error: one line
    # on stderr, status 1, like every other error.
    "$mane" sim --steps 5 --json >"$scratch/sim.json" || fail "sim --json failed"
    python3 - "$scratch/sim.json" <<'PY' || fail "sim --json: $(cat "$scratch/sim.json")"
import json, re, sys
report = json.load(open(sys.argv[1]))
assert report["command"] == "sim" and report["steps"] == 5 and report["guide_strands"] == 762, report
assert re.fullmatch("[0-9a-f]{16}", report["state_hash"]) and report["wall_seconds"] >= 0, report
PY
    [ "$("$mane" sim --steps 5 | tail -n 1)" = "state-hash: $(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["state_hash"])' "$scratch/sim.json")" ] ||
      fail "--json gives another hash than the text"
    version=$(grep -oP 'project\(mane VERSION \K[0-9.]+' CMakeLists.txt)
    [ "$("$mane" --version)" = "mane $version" ] || fail "--version: $("$mane" --version), not mane $version"
    for bad in "sim --steps -1" "sim --no-such-option" "render --msaa 3" "" "sim --frames 3"; do
      # shellcheck disable=SC2086
      "$mane" $bad 2>"$scratch/err" >"$scratch/out"
      status=$?
      [ "$status" -eq 1 ] || fail "'mane $bad' exited $status, not 1"
      [ "$(wc -l <"$scratch/err")" -eq 1 ] && grep -q "^mane: " "$scratch/err" || fail "'mane $bad': $(cat "$scratch/err")"
      [ ! -s "$scratch/out" ] || fail "'mane $bad' printed on stdout: $(cat "$scratch/out")"
    done
    ;;
  render-json-report)
    # --json: per-frame and per-pass GPU times, frame times and the state hash, nothing else on
    # stdout; and without a terminal, no progress bar in the text output.
    "$mane" render scenes/cape.json --frames 2 --size 160x90 --msaa 1 --out "$scratch/out" --json \
      >"$scratch/render.json" 2>"$scratch/err" || fail "render --json failed: $(cat "$scratch/err")"
    python3 - "$scratch/render.json" <<'PY' || fail "render --json: $(cat "$scratch/render.json")"
import json, sys
report = json.load(open(sys.argv[1]))
assert report["command"] == "render" and report["width"] == 160 and report["source"] == "simulated", report
assert [f["frame"] for f in report["frames"]] == [0, 1], report["frames"]
assert all(f["passes_gpu_ms"] and f["wall_ms"] > 0 for f in report["frames"]), report["frames"]
assert report["passes"][-1]["pass"] == "all passes" and len(report["state_hash"]) == 16, report["passes"]
PY
    "$mane" render scenes/cape.json --frames 3 --size 160x90 --msaa 1 --out "$scratch/out" >"$scratch/log" 2>&1 ||
      fail "render failed: $(cat "$scratch/log")"
    grep -q $'\r' "$scratch/log" && fail "a progress bar was drawn into a file"
    grep -q "^wrote 3 frames" "$scratch/log" || fail "no 'wrote' line: $(cat "$scratch/log")"
    ;;
  cache-split-renders-identical)
    # A simulation cache of 6 frames at 24 fps rendered in two ranges (as two farm machines would)
    # gives the same bytes as one run over the cache and as a plain render that simulates.
    "$mane" sim scenes/cape.json --cache "$scratch/cache" --frames 6 --fps 24 >"$scratch/log" ||
      fail "sim --cache failed: $(cat "$scratch/log")"
    [ "$(ls "$scratch"/cache/frame_*.msim | wc -l)" -eq 6 ] || fail "expected 6 frames: $(ls "$scratch/cache")"
    common=(--size 160x90 --msaa 1)
    "$mane" render --cache "$scratch/cache" --frame-range 0:2 "${common[@]}" --out "$scratch/split" >"$scratch/log" 2>&1 &&
      "$mane" render --cache "$scratch/cache" --frame-range 3:5 "${common[@]}" --out "$scratch/split" >>"$scratch/log" 2>&1 &&
      "$mane" render --cache "$scratch/cache" "${common[@]}" --out "$scratch/whole" >>"$scratch/log" 2>&1 &&
      "$mane" render scenes/cape.json --frames 6 --fps 24 "${common[@]}" --out "$scratch/plain" >>"$scratch/log" 2>&1 ||
      fail "render failed: $(cat "$scratch/log")"
    for frame in 0000 0001 0002 0003 0004 0005; do
      cmp "$scratch/whole/cape_$frame.png" "$scratch/split/cape_$frame.png" || fail "frame $frame: split differs"
      cmp "$scratch/whole/cape_$frame.png" "$scratch/plain/cape_$frame.png" || fail "frame $frame: plain differs"
    done
    cmp -s "$scratch/whole/cape_0000.png" "$scratch/whole/cape_0005.png" && fail "the cape did not move"
    "$mane" render --cache "$scratch/cache" --frame-range 4:6 "${common[@]}" --out "$scratch/x" 2>"$scratch/err" >/dev/null &&
      fail "a range past the cache accepted"
    grep -q "^mane: --frame-range 4:6: the cache .* holds frames 0 to 5$" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    "$mane" render scenes/robot.json --cache "$scratch/cache" "${common[@]}" --out "$scratch/x" 2>"$scratch/err" >/dev/null &&
      fail "a cache of another scene accepted"
    grep -q "^mane: .*frame_000000.msim: .*another scene" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    ;;
  view-character-keys)
    # C plays the next clip of the character, E blends in its next expression; each is printed.
    xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view scenes/robot.json --frames 6 --press CEEC \
      --screenshot "$scratch/view.png" >"$scratch/log" 2>&1 || fail "mane view failed: $(cat "$scratch/log")"
    grep -q "^clips: robot: WalkJump$" "$scratch/log" || fail "C did not go from Walking to WalkJump: $(cat "$scratch/log")"
    grep -q "^expressions: robot: Angry$" "$scratch/log" || fail "E did not blend in Angry: $(cat "$scratch/log")"
    grep -q "^expressions: robot: Surprised$" "$scratch/log" || fail "E did not go on to Surprised: $(cat "$scratch/log")"
    grep -q "^clips: robot: Wave$" "$scratch/log" || fail "C did not go on to Wave: $(cat "$scratch/log")"
    grep -q "^Keys: .*C a character's next animation clip" "$scratch/log" || fail "C is not in the key list"
    ;;
  view-ship-keys)
    # W and Q make the sea's wind stronger and calmer (new waves), B fires the cannon; each is
    # printed. A scene without a sea says so.
    xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view scenes/clear_sailing.json --frames 5 --press WQB \
      >"$scratch/log" 2>&1 || fail "mane view failed: $(cat "$scratch/log")"
    grep -q "^wind 17.5 m/s$" "$scratch/log" || fail "W did not raise the wind from 14 to 17.5 m/s: $(cat "$scratch/log")"
    grep -q "^wind 14 m/s$" "$scratch/log" || fail "Q did not calm it back to 14 m/s: $(cat "$scratch/log")"
    grep -q "^cannon fired$" "$scratch/log" || fail "B did not fire the cannon: $(cat "$scratch/log")"
    xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view scenes/sphere.json --frames 3 --press WB \
      >"$scratch/log" 2>&1 || fail "mane view failed: $(cat "$scratch/log")"
    grep -q "^the scene has no sea$" "$scratch/log" || fail "W on a scene without a sea: $(cat "$scratch/log")"
    grep -q "^the scene has no cannon$" "$scratch/log" || fail "B on a scene without a cannon: $(cat "$scratch/log")"
    ;;
  render-writes-png)
    "$mane" render --out "$scratch/out" --size 160x90 --msaa 1 >"$scratch/log" 2>&1 || fail "render failed: $(cat "$scratch/log")"
    png=$(ls "$scratch"/out/*.png) || fail "no PNG written"
    [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$png is not a PNG"
    # IHDR (bytes 16..23): width and height, big-endian, as asked with --size.
    [ "$(od -An -tx1 -j16 -N8 "$png" | tr -d ' \n')" = "000000a00000005a" ] || fail "$png is not 160x90"
    grep -q "wrote .*\.png" "$scratch/log" || fail "no 'wrote' line"
    grep -q "^main pass " "$scratch/log" || fail "no per-pass time for the main pass"
    ;;
  render-writes-exr)
    # --exr: an OpenEXR file beside each PNG (its contents: tests/render/environment_render_test.cpp).
    "$mane" render --out "$scratch/out" --size 160x90 --msaa 1 --exr >"$scratch/log" 2>&1 ||
      fail "render failed: $(cat "$scratch/log")"
    exr=$(ls "$scratch"/out/*_0000.exr) || fail "no OpenEXR file beside the PNG: $(ls "$scratch/out")"
    [ "$(head -c 4 "$exr" | od -An -tx1 | tr -d ' \n')" = "762f3101" ] || fail "$exr is not an OpenEXR file"
    grep -q "wrote .*_0000\.exr (linear fp16 RGB)" "$scratch/log" || fail "no 'wrote' line for the EXR"
    "$mane" render --out "$scratch/json" --size 160x90 --msaa 1 --frames 2 --exr --json >"$scratch/report" 2>&1 ||
      fail "render --json failed: $(cat "$scratch/report")"
    grep -q '"exr_file": ".*_0001\.exr"' "$scratch/report" || fail "no exr_file in the report: $(cat "$scratch/report")"
    [ -s "$scratch/json/$(basename "${exr%_0000.exr}")_0001.exr" ] || fail "frame 1's EXR is missing"
    ;;
  cape-sequence)
    # A simulated sequence: cloth uploaded every frame, frames numbered, the timing table.
    "$mane" render scenes/cape.json --frames 3 --size 160x90 --msaa 1 --out "$scratch/out" >"$scratch/log" 2>&1 ||
      fail "render failed: $(cat "$scratch/log")"
    [ "$(ls "$scratch"/out/cape_000[0-2].png | wc -l)" -eq 3 ] || fail "expected 3 frames: $(ls "$scratch/out")"
    grep -q "^surfaces " "$scratch/log" || fail "no timing table"
    # The span from the first pass's begin to the last one's end holds every pass: it is at least
    # as long as the longest one (medians do not add up, so no sum).
    awk '/^pass / { table = 1; next } table && /^all passes / { span = $3; next }
         table && $(NF-1) + 0 > longest { longest = $(NF-1) + 0 }
         END { exit !(span + 0 > 0 && span + 0.01 >= longest) }' "$scratch/log" ||
      fail "the span of all passes is missing or shorter than a pass: $(cat "$scratch/log")"
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
    grep -q "^Keys: Space" "$scratch/log" || fail "no key list on start: $(cat "$scratch/log")"
    # The frame time and the toggles, white on black, in the top-left corner (scale 2 at 1280x720:
    # two lines of 14-pixel glyphs on a 40-pixel panel from (8, 8)).
    if command -v python3 >/dev/null; then
      read -r white black < <(overlay_pixels "$scratch/view.png" 8 8 408 48) || fail "cannot read the screenshot"
      [ "$white" -gt 300 ] && [ "$black" -gt 2000 ] || fail "no overlay text: $white white, $black black pixels"
    fi
    ;;
  view-light-control)
    # J / L turn the key light about the vertical by 15 degrees, I / M raise and lower it by 10. The
    # torus scene is static (no simulation, no auto gain), so its frames depend on the light alone:
    # four turns change the image, and four turns back restore it byte for byte. O hides the
    # overlay, whose frame time differs from run to run. The printed angles follow the keys.
    for presses in O OLLLL OLLLLJJJJ OIIIIIIIIII; do
      xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view scenes/torus.json --frames 12 --press "$presses" \
        --screenshot "$scratch/$presses.png" >"$scratch/$presses.log" 2>&1 ||
        fail "mane view --press $presses failed: $(cat "$scratch/$presses.log")"
    done
    cmp -s "$scratch/O.png" "$scratch/OLLLL.png" && fail "turning the light 60 degrees changed nothing"
    cmp -s "$scratch/O.png" "$scratch/OLLLLJJJJ.png" || fail "turning the light back did not restore the image"
    # torus.json's key light comes from (0.35, 0.15, -1) (the scene gives (-0.35, -0.15, 1), the way
    # it travels): azimuth atan2(0.35, -1) = 160.7 degrees, elevation asin(0.15 / 1.0706) = 8.1.
    grep -q "^LIGHT AZ 176 EL 8$" "$scratch/OLLLL.log" || fail "L: $(grep LIGHT "$scratch/OLLLL.log")"
    grep -q "^LIGHT AZ -139 EL 8$" "$scratch/OLLLL.log" || fail "4 L: $(grep LIGHT "$scratch/OLLLL.log")"
    grep -q "^LIGHT AZ 161 EL 8$" "$scratch/OLLLLJJJJ.log" || fail "back: $(grep LIGHT "$scratch/OLLLLJJJJ.log")"
    # Ten raises would reach 108 degrees: the elevation stops at 85.
    [ "$(grep -c "^LIGHT AZ 161 EL 85$" "$scratch/OIIIIIIIIII.log")" -ge 2 ] ||
      fail "the elevation is not held at 85: $(grep LIGHT "$scratch/OIIIIIIIIII.log")"
    ;;
  view-technique-toggles)
    # K (texture-space skin) and H (deep opacity maps) rebuild the renderer's scene mid-run, S turns
    # the soft shadows off; O then hides the overlay. Validation stays clean (MANE_VALIDATION=1) and
    # the frame is still drawn.
    xvfb-run -a -s "-screen 0 1280x800x24" "$mane" view --frames 6 --press KHSO --screenshot "$scratch/view.png" \
      >"$scratch/log" 2>&1 || fail "mane view failed: $(cat "$scratch/log")"
    grep -q "K SKIN TEXTURE  H SHADOWS OSM" "$scratch/log" || fail "K did not switch the skin: $(cat "$scratch/log")"
    grep -q "K SKIN TEXTURE  H SHADOWS DEEP  S SOFT ON" "$scratch/log" ||
      fail "H did not switch the shadows: $(cat "$scratch/log")"
    grep -q "H SHADOWS DEEP  S SOFT OFF" "$scratch/log" || fail "S did not switch the soft shadows: $(cat "$scratch/log")"
    size=$(stat -c %s "$scratch/view.png") || fail "no screenshot"
    [ "$size" -gt 20000 ] || fail "the screenshot looks blank ($size bytes)"
    if command -v python3 >/dev/null; then
      read -r white black < <(overlay_pixels "$scratch/view.png" 8 8 408 48) || fail "cannot read the screenshot"
      [ "$white" -lt 20 ] || fail "O did not hide the overlay: $white white pixels"
    fi
    "$mane" view --press "K!" 2>"$scratch/err" >/dev/null && fail "--press accepted '!'"
    grep -q "^mane: --press: no key for '!'" "$scratch/err" || fail "bad --press message: $(cat "$scratch/err")"
    ;;
  render-mp4)
    # An H.264 MP4 of the frames at the render's frame rate, checked by ffprobe.
    command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null || skip "ffmpeg or ffprobe is not installed"
    "$mane" render scenes/cape.json --frames 4 --fps 24 --size 160x90 --msaa 1 --out "$scratch/out" \
      --mp4 "$scratch/video/cape.mp4" >"$scratch/log" 2>&1 || fail "render failed: $(cat "$scratch/log")"
    grep -q "wrote .*cape.mp4" "$scratch/log" || fail "no 'wrote' line for the MP4: $(cat "$scratch/log")"
    probe=$(ffprobe -v error -count_frames -select_streams v:0 \
      -show_entries stream=codec_name,width,height,r_frame_rate,nb_read_frames -of default=noprint_wrappers=1 \
      "$scratch/video/cape.mp4") || fail "ffprobe cannot read the MP4"
    for expected in codec_name=h264 width=160 height=90 r_frame_rate=24/1 nb_read_frames=4; do
      grep -qx "$expected" <<<"$probe" || fail "expected $expected in: $probe"
    done
    # An odd size is padded to even (yuv420p), and a longer sequence left in --out is not picked up.
    "$mane" render scenes/cape.json --frames 2 --size 161x91 --msaa 1 --out "$scratch/out" \
      --mp4 "$scratch/odd.mp4" >"$scratch/log" 2>&1 || fail "odd-size render failed: $(cat "$scratch/log")"
    probe=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=width,height,nb_read_frames \
      -of default=noprint_wrappers=1 "$scratch/odd.mp4") || fail "ffprobe cannot read the odd-size MP4"
    for expected in width=162 height=92 nb_read_frames=2; do
      grep -qx "$expected" <<<"$probe" || fail "expected $expected in: $probe"
    done
    ;;
  mp4-needs-ffmpeg)
    # Without ffmpeg on PATH: one line naming the program, before any frame is rendered.
    mkdir "$scratch/empty"
    PATH="$scratch/empty" "$mane" render --mp4 "$scratch/a.mp4" --out "$scratch/out" 2>"$scratch/err" >/dev/null &&
      fail "exit status 0 without ffmpeg"
    [ "$(wc -l <"$scratch/err")" -eq 1 ] || fail "expected one line, got: $(cat "$scratch/err")"
    grep -q "^mane: .*ffmpeg.*not on PATH.*apt-get install ffmpeg" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    [ ! -e "$scratch/out" ] || fail "frames were rendered before the check: $(ls "$scratch/out")"
    # A folder is no MP4 file: refused as early, whether ffmpeg is there or not.
    "$mane" render --mp4 "$scratch/empty" --out "$scratch/out" 2>"$scratch/err" >/dev/null && fail "a folder accepted"
    grep -q "^mane: --mp4 .*empty is a folder" "$scratch/err" || fail "message: $(cat "$scratch/err")"
    [ ! -e "$scratch/out" ] || fail "frames were rendered before the check: $(ls "$scratch/out")"
    ;;
  help-for-each-command)
    for command in info render sim view; do
      "$mane" "$command" --help | grep -qi "usage" || fail "$command --help"
    done
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
