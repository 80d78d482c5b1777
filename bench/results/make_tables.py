#!/usr/bin/env python3
"""Benchmark results → the tables of docs/performance.md.

Every benchmark program writes Google Benchmark JSON into bench/results/<cpu>/<name>.json (one
folder per CPU model; <cpu> is its slug, e.g. amd-epyc). This script

  * with --run, runs the benchmark programs of build/release/bench with the arguments listed in
    BENCHES below and saves their JSON (and their stderr, which holds notes and summaries, as
    <name>.log) under bench/results/<cpu>/, the CPU and the Vulkan driver recorded in the JSON's
    context (--benchmark_context);
  * always, rewrites the text between `<!-- tables:begin -->` and `<!-- tables:end -->` in
    docs/performance.md from every JSON found, leaving the rest of the page as written.

Each table names the command that produced it, the date from the JSON's context, the CPU (the
context's `cpu`, else machine.json's, else the folder name) and the driver (the context's
`driver`, else machine.json's). Python 3 standard library only.

  python3 bench/results/make_tables.py                    # tables from the JSON files there
  python3 bench/results/make_tables.py --run              # run every benchmark, then the tables
  python3 bench/results/make_tables.py --run frame post   # run only these, then the tables
  python3 bench/results/make_tables.py --commands         # print the commands, run nothing

--extra adds arguments to every run (a quick smoke test: --extra=--benchmark_min_time=0.01); the
page then marks those tables as not full runs. --results and --page point elsewhere than
bench/results and docs/performance.md.
"""

from __future__ import annotations

import argparse
import json
import re
import shlex
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "bench" / "results"
PAGE = ROOT / "docs" / "performance.md"
BEGIN, END = "<!-- tables:begin -->", "<!-- tables:end -->"
BIN = "build/release/bench"
MAX_LOG_LINES = 40

# ---------------------------------------------------------------------------------------------
# Reading Google Benchmark JSON


@dataclass
class Run:
    """One benchmark of a JSON file: the median aggregate where there were repetitions."""

    name: str  # run_name without the /real_time, /iterations:N, ... suffixes
    args: dict  # "variant" → "0" for named arguments, "0", "1", … for positional ones
    entry: dict
    order: tuple

    def value(self, key: str) -> Optional[float]:
        if self.entry.get("error_occurred"):
            return None
        if key in ("real_time", "cpu_time"):
            return to_ms(self.entry[key], self.entry.get("time_unit", "ns"))
        value = self.entry.get(key)
        return float(value) if isinstance(value, (int, float)) else None


def to_ms(value: float, unit: str) -> float:
    return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]


SUFFIXES = re.compile(r"/(real_time|manual_time|process_time|iterations:\d+|repeats:\d+|min_time:[\d.]+)$")


def base_name(run_name: str) -> str:
    while True:
        stripped = SUFFIXES.sub("", run_name)
        if stripped == run_name:
            return run_name
        run_name = stripped


def parse_args(name: str) -> dict:
    args = {}
    for i, part in enumerate(name.split("/")[1:]):
        key, sep, value = part.partition(":")
        args[key if sep else str(i)] = value if sep else part
    return args


def read_runs(data: dict) -> list[Run]:
    groups: dict[str, list[dict]] = {}
    for entry in data.get("benchmarks", []):
        groups.setdefault(base_name(entry.get("run_name", entry["name"])), []).append(entry)
    runs = []
    for name, entries in groups.items():
        medians = [e for e in entries if e.get("aggregate_name") == "median"]
        iterations = [e for e in entries if e.get("run_type", "iteration") == "iteration"]
        entry = (medians or iterations or entries)[0]
        order = (entry.get("family_index", 0), entry.get("per_family_instance_index", 0))
        runs.append(Run(name, parse_args(name), entry, order))
    return sorted(runs, key=lambda r: r.order)


# ---------------------------------------------------------------------------------------------
# Formatting


def number(value: float) -> str:
    """Three significant figures, thousands separated: 1,324 · 93.0 · 2.49 · 0.205."""
    magnitude = abs(value)
    if magnitude >= 100:
        return f"{value:,.0f}"
    if magnitude >= 10:
        return f"{value:.1f}"
    if magnitude >= 1:
        return f"{value:.2f}"
    if magnitude == 0:
        return "0"
    return f"{value:.3g}"


def percent(value: float) -> str:
    return f"{100 * value:.0f} %"


def si_rate(value: float) -> str:
    for scale, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(value) >= scale:
            return f"{number(value / scale)} {prefix}/s"
    return f"{number(value)}/s"


def times(value: float) -> str:
    return f"{number(value)}×"


def duration(value_ms: float) -> str:
    """Milliseconds with the unit that keeps them readable: 4.37 µs · 80.8 µs · 1.12 ms."""
    return f"{number(value_ms * 1000)} µs" if abs(value_ms) < 1 else f"{number(value_ms)} ms"


def threads(count: str) -> str:
    return f"{count} thread" + ("" if count == "1" else "s")


# ---------------------------------------------------------------------------------------------
# Table specifications


@dataclass
class Column:
    header: str
    key: str  # "real_time", "cpu_time", a counter, or "items_per_second"
    fmt: Callable[[float], str] = number
    # A ratio: this column's value over the same key's value in the row this names (or None).
    baseline: Optional[Callable[[Run], Optional[str]]] = None


@dataclass
class Table:
    title: str
    include: str  # regex on the run name
    label: Callable[[Run], str]
    columns: list[Column]
    about: str = ""
    row_header: str = "case"
    # Counters matching this regex become columns after `columns`, in `counter_order` first.
    more_counters: Optional[str] = None
    counter_order: list[str] = field(default_factory=list)
    counter_header: Callable[[str], str] = lambda key: key


@dataclass
class Bench:
    name: str  # bench/results/<cpu>/<name>.json
    binary: str
    args: list[str]
    gpu: bool
    tables: list[Table]

    def command(self) -> str:
        return " ".join([f"{BIN}/{self.binary}", *map(shlex.quote, self.args)])


def ms(header: str = "time (ms)") -> Column:
    return Column(header, "real_time")


def time_column(header: str = "time") -> Column:
    """For tables whose times span microseconds to milliseconds."""
    return Column(header, "real_time", duration)


def ratio_to(header: str, baseline: Callable[[Run], Optional[str]], key: str = "real_time") -> Column:
    return Column(header, key, number, baseline)


ENVIRONMENT_STAGES = {
    "0": "the panorama resampled into a 256-texel cube map (CPU, 2 × 2 samples a texel)",
    "1": "the cube's irradiance projected on nine spherical harmonics (CPU, the reference)",
    "2": "the cube uploaded with its mips, its specular chain baked (GPU: 8 levels from 128 texels)",
    "3": "the cube's irradiance projected on nine spherical harmonics (GPU compute, what the renderer runs)",
}

FRAME_VARIANTS = [
    "as shipped: pre-integrated skin, fins, furred bunny",
    "same, 4× MSAA (`mane render`'s default)",
    "texture-space skin diffusion (1024²)",
    "deep opacity maps",
    "50,000 strands × 30",
    "100,000 strands × 30",
    "as shipped, the bunny without fur shells and fins",
    "**original demo content**: head, hair, fins (no bunny)",
    "same, every hair segment shaded and drawn",
    "50,000 strands × 30, the camera 4× as far (about half of them drawn)",
    "same, every strand drawn (no level of detail)",
    "as shipped, under the Venice panorama (environment light and background)",
    "as shipped, without the surfaces' soft shadows",
]

# The frame's passes in the order the Renderer records them; unknown ones follow alphabetically.
PASS_ORDER = [
    "skinning", "strands", "hair density", "hair shadows", "surface shadows", "skin diffusion", "translucency depth", "ocean",
    "skin g-buffer", "hair lighting", "surfaces", "hair", "main pass", "glasses", "clear", "post downsample", "downsample",
    "auto gain", "glow", "god rays", "post overlay", "overlay", "output",
]


def pass_key(name: str) -> str:
    return name.replace(" ", "_") + "_ms"


def same_counter(a: str, b: str) -> bool:
    """Pass counters are named with spaces or underscores, depending on the benchmark."""
    return a.replace(" ", "_").lower() == b.replace(" ", "_").lower()


def pass_header(key: str) -> str:
    return key[: -len("_ms")].replace("_", " ")


ROBOT_VARIANTS = [
    "animated (walking)",
    "the body frozen (rest pose; hair and cape still simulated)",
    "animated, 4× MSAA (`mane render`'s default)",
    "the body frozen, 4× MSAA",
]


TIMBURY_VARIANTS = ["as shipped, with his glasses", "without the glasses"]

CLEAR_SAILING_VARIANTS = ["as shipped", "the sea not drawn (the ship still floats)",
                          "the effects not drawn (spray, smoke, rigging, debris)"]


def clear_sailing_bare_row(run: Run) -> Optional[str]:
    """The row without the sea, for the row with it."""
    return "BM_ClearSailingFrame/variant:1" if run.args.get("variant") == "0" else None


def timbury_bare_row(run: Run) -> Optional[str]:
    """The row without glasses, for the row with them."""
    return "BM_TimburyFrame/variant:1" if run.args.get("variant") == "0" else None


def robot_frozen_row(run: Run) -> Optional[str]:
    """The frozen row at the same MSAA as an animated row (variants 0 → 1, 2 → 3)."""
    variant = run.args.get("variant", "")
    return f"BM_RobotFrame/variant:{int(variant) + 1}" if variant in ("0", "2") else None


NALU_BUNNY_CASES = {
    "0": "skin layer only",
    "1": "15 shells, both faces",
    "2": "15 shells, back faces culled (`double_sided: false`)",
    "3": "culled, one shell per pixel of fur height (`pixels_per_layer: 1`), as shipped",
}
RENDER_SCENES = {
    "0": "nothing drawn (clear, post, output)",
    "1": "head, Lambert + normal map",
    "2": "head, pre-integrated skin",
    "3": "head, texture-space skin 1024²",
    "4": "head, texture-space skin 2048²",
    "5": "head, skin + translucency (depth map)",
    "6": "head, skin + translucency (voxel table, N = 32)",
}
CUBE_METHODS = {"0": "no translucency", "1": "depth map (hollow counted)", "2": "voxel table (hollow subtracted)"}

HAIR_FRAME = re.compile(r"BM_HairFrame(Collisions)?/")


def physics_label(run: Run) -> str:
    a = run.args
    if run.name.startswith("BM_DistanceProjections"):
        return f"distance projections, one strand of {int(a['0']):,} particles"
    if run.name.startswith("BM_StrandLaneProjections"):
        return f"lane projections, 64 strands × {a['0']}, {'AVX2' if a['1'] == '1' else 'scalar'}"
    if HAIR_FRAME.match(run.name):
        what = "10k × 32 frame" + (" + collisions" if "Collisions" in run.name else "")
        steps = "1 step" if a["2"] == "1" else f"{a['2']} steps"
        return f"{what}, {steps}, {'AVX2' if a['1'] == '1' else 'scalar'}, {threads(a['0'])}"
    if run.name.startswith("BM_NaluFrameThreads"):
        return f"Nalu frame, 762 × 16, no collisions, {threads(a['0'])}"
    if run.name.startswith("BM_NaluFrame"):
        return "Nalu frame, 762 × 16, " + ("with collisions" if a["0"] == "1" else "no collisions")
    if run.name.startswith("BM_HairFrameTasks"):
        runner = "the host's job system" if a["1"] == "1" else "the built-in pool"
        return f"10k × 32 frame, 1 step, {a['0']} worker{'' if a['0'] == '1' else 's'} of {runner}"
    if run.name == "BM_SdfBuild":
        return "SDF build, 64³, 20,480 triangles"
    if run.name == "BM_StateHash":
        return "state hash, 10k × 32 groom"
    if run.name.startswith("BM_ClothFrame"):
        return "cloth frame, 48 × 48 sheet over a ball, " + (
            "self collision at 3 mm" if a["0"] == "1" else "no self collision")
    if run.name.startswith("BM_OceanQueries"):
        return "sea, 45 waves: " + ("the water over a point (surfaceAt)" if a["0"] == "1"
                                    else "the water resting at a point (sample)")
    if run.name == "BM_FloatingBody":
        return "floating box, one 1/120 s step, 192 hull columns"
    return run.name


def character_label(run: Run) -> str:
    if run.name.startswith("BM_CharacterBind"):
        return "binding 10,000 roots to the head (load time)"
    if run.name.startswith("BM_CharacterStep"):
        return f"one step with its root update, {threads(run.args['0'])}"
    return run.name


def skinning_label(run: Run) -> str:
    method = "dual-quaternion" if run.args.get("0") == "1" else "linear blend"
    if run.name.startswith("BM_SkinningGpu"):
        return f"GPU pass, {method}"
    return f"CPU, {method}, {threads(run.args.get('1', '?'))}"


CAGES = {"0": "scan", "1": "coarse"}
VIEWS = {"0": "near", "1": "mid", "2": "far"}


def subdiv_label(run: Run) -> str:
    a = run.args
    parts = [CAGES.get(a.get("cage", ""), a.get("cage", "?")) + " cage"]
    if "view" in a:
        parts.append(VIEWS.get(a["view"], a["view"]))
    if "prepared" in a:
        parts.append("prepared (`update`)" if a["prepared"] == "1" else "tessellates itself")
        parts.append("paced 60 Hz" if a["paced"] == "1" else "back to back")
    parts.append(threads(a.get("threads", "?")))
    return ", ".join(parts)


def subdiv_bench_name(run: Run) -> str:
    return {
        "BM_AdaptiveFrame": "tessellation",
        "BM_DeformingCageUpdate": "cage update",
        "BM_DeformAndTessellateFrame": "update + tessellation",
        "BM_DeformAndUpdateVerticesFrame": "update + kept triangles",
    }.get(run.name.split("/")[0], run.name.split("/")[0])


def post_label(run: Run) -> str:
    if run.name == "BM_OutputOnly":
        return "output pass alone (linear exposure)"
    on = [what for what, i in (("glow", "0"), ("auto gain", "1"), ("Reinhard", "2"), ("god rays", "3"))
          if run.args.get(i) == "1"]
    return " + ".join(on)


BENCHES: list[Bench] = [
    Bench("frame", "mane_frame_bench",
          ["--benchmark_repetitions=5", "--benchmark_enable_random_interleaving=true"], True, [
              Table("Whole frame", r"^BM_NaluFrame/",
                    lambda r: FRAME_VARIANTS[int(r.args["variant"])] if r.args["variant"].isdigit()
                    and int(r.args["variant"]) < len(FRAME_VARIANTS) else r.name,
                    [Column("frame (wall, ms)", "frame_ms"), Column("fps", "fps"),
                     Column("simulation", "sim_ms"), Column("head tessellation", "refine_ms"),
                     Column("uploads", "upload_ms"), Column("GPU span", "gpu_ms"),
                     Column("hidden hair", "hidden_hair", percent)],
                    about="`scenes/nalu.json` as `mane render` runs it, at 1280×720, 1× MSAA unless the row "
                          "says otherwise: World::advance on 2 threads, the uploads, the head's tessellation, "
                          "every pass with the scene's post. 9 frames of 1/30 s after an untimed one; medians "
                          "of the frames, then of 5 repetitions. Times in ms; the pass columns are GPU "
                          "timestamps, each pass timed from the end of the one before it; \"hidden hair\" is "
                          "the share of dense hair vertices neither shaded nor drawn.",
                    more_counters=r"_ms$", counter_order=[pass_key(p) for p in PASS_ORDER],
                    counter_header=pass_header),
              Table("The robot frame", r"^BM_RobotFrame/",
                    lambda r: ROBOT_VARIANTS[int(r.args["variant"])] if r.args["variant"].isdigit()
                    and int(r.args["variant"]) < len(ROBOT_VARIANTS) else r.name,
                    [Column("frame (wall, ms)", "frame_ms"), Column("fps", "fps"),
                     ratio_to("ratio to the frozen body", robot_frozen_row, "frame_ms"),
                     Column("simulation", "sim_ms"), Column("tessellation", "refine_ms"),
                     Column("uploads", "upload_ms"), Column("GPU span", "gpu_ms"),
                     Column("hidden hair", "hidden_hair", percent)],
                    about="`scenes/robot.json` the same way, at 1280×720: the glTF character skinned on the "
                          "GPU (walking), 800 hair guides (3,000 strands drawn), two hands drawn as skinned "
                          "subdivision surfaces and a cape simulated against "
                          "it. The frozen rows empty the character's clips and morph tracks: the body stands "
                          "in its rest pose while the hair and the cape are still simulated, so the ratio is "
                          "what the moving body costs. 9 frames of 1/30 s after 15 untimed ones; medians of "
                          "the frames, then of 5 repetitions; the ratio is of those medians.",
                    more_counters=r"_ms$", counter_order=[pass_key(p) for p in PASS_ORDER],
                    counter_header=pass_header),
              Table("Timbury's frame", r"^BM_TimburyFrame/",
                    lambda r: TIMBURY_VARIANTS[int(r.args["variant"])] if r.args["variant"].isdigit()
                    and int(r.args["variant"]) < len(TIMBURY_VARIANTS) else r.name,
                    [Column("frame (wall, ms)", "frame_ms"), Column("fps", "fps"),
                     ratio_to("ratio to no glasses", timbury_bare_row, "frame_ms"),
                     Column("uploads", "upload_ms"), Column("GPU span", "gpu_ms")],
                    about="`scenes/timbury.json` the same way, at 1280×720 and 1× MSAA: the head as a "
                          "subdivision surface under the Venice panorama, its sun cut out as the first light, "
                          "with and without the glasses (two -2 D lenses refracting the frame in screen space, "
                          "and their frame drawn as a mesh). 9 frames of 1/30 s after an untimed one; medians "
                          "of the frames, then of 5 repetitions; the ratio is of those medians.",
                    more_counters=r"_ms$", counter_order=[pass_key(p) for p in PASS_ORDER],
                    counter_header=pass_header),
              Table("Clear Sailing's frame", r"^BM_ClearSailingFrame/",
                    lambda r: CLEAR_SAILING_VARIANTS[int(r.args["variant"])] if r.args["variant"].isdigit()
                    and int(r.args["variant"]) < len(CLEAR_SAILING_VARIANTS) else r.name,
                    [Column("frame (wall, ms)", "frame_ms"), Column("fps", "fps"),
                     ratio_to("ratio to no sea", clear_sailing_bare_row, "frame_ms"),
                     Column("simulation", "sim_ms"), Column("uploads", "upload_ms"), Column("GPU span", "gpu_ms")],
                    about="`scenes/clear_sailing.json` the same way, at 1280×720 and 1× MSAA: 45 Gerstner "
                          "waves on a projected grid of 100 × 150 cells (the rows over the sea built and "
                          "drawn) with foam, a ship floating by its hull's cells "
                          "on them, two cloth sails in the wind, 19 ropes of rigging, spray, 30 pieces of "
                          "debris, the sky's environment, and the cannon fired before the first frame so that "
                          "its smoke is in every one. The second row hands the renderer no sea (the ship still "
                          "floats), so the ratio is what the sea costs; the third no effects (still "
                          "simulated). 9 "
                          "frames of 1/30 s after an untimed one; medians of the frames, then of 5 "
                          "repetitions.",
                    more_counters=r"_ms$", counter_order=[pass_key(p) for p in PASS_ORDER],
                    counter_header=pass_header),
          ]),
    Bench("render", "mane_render_bench", ["--benchmark_min_time=1"], True, [
        Table("The head's shading", r"^BM_NaluFrame/",
              lambda r: RENDER_SCENES.get(r.args.get("scene"), r.name) + (
                  ", 4× MSAA" if r.args.get("msaa") == "4" else ""),
              [ms(), ratio_to("ratio to empty", lambda r: "BM_NaluFrame/scene:0/msaa:1"),
               ratio_to("ratio to Lambert", lambda r: None if r.args.get("scene") == "0"
                        else f"BM_NaluFrame/scene:1/msaa:{r.args.get('msaa')}")],
              about="nalu's head alone at 1280×720 with the scene's post but no god rays; no hair, fins or "
                    "bunny. Ratios against rows of the same run."),
        Table("Translucency", r"^BM_TranslucentCube/",
              lambda r: "cube with a spherical hollow, " + CUBE_METHODS.get(r.args.get("method"), "?"),
              [ms(), ratio_to("ratio to no translucency", lambda r: "BM_TranslucentCube/method:0")],
              about="`scenes/translucent_cube.json` at 1280×720; the voxel table at N = 32, built before "
                    "the timed frames."),
        Table("Environment preparation", r"^BM_EnvironmentPreparation/",
              lambda r: ENVIRONMENT_STAGES.get(r.args.get("stage"), r.name), [ms()],
              about="What setting a scene's environment costs, once per environment: "
                    "`env/venice_sunset_1k.hdr` (1024 × 512) as `scenes/timbury.json` uses it."),
    ]),
    Bench("post", "mane_post_bench", ["--benchmark_min_time=1"], True, [
        Table("HDR post", r"", post_label,
              [ms("frame (ms)"), ratio_to("ratio to output alone", lambda r: "BM_OutputOnly")],
              about="1280×720, a cleared HDR frame; wall time around submit and wait. Pass columns: GPU "
                    "time of each pass (ms).",
              more_counters=r"_ms$", counter_order=[pass_key(p) for p in PASS_ORDER],
              counter_header=pass_header),
    ]),
    Bench("hair_pass", "mane_hair_pass_bench", ["--benchmark_min_time=1"], True, [
        Table("Hair drawing", r"",
              lambda r: (f"empty frame, {r.args['0']}× MSAA" if r.name.startswith("BM_EmptyFrame") else
                         f"4,096 × 32 strands {int(r.args['2']) / 1000:g} mm wide, {r.args['0']}× MSAA, "
                         f"{'key + back light' if r.args['1'] == '2' else 'ambient only'}"),
              [ms(), Column("drawn as lines", "lines", lambda v: "yes" if v else "no"),
               Column("width lines leave uncovered", "uncovered_by_lines", percent)],
              about="per-vertex Marschner shading, the choice of primitive and the draw, at 1280×720; wall "
                    "time around submit and wait."),
    ]),
    Bench("opacity_shadow_map", "mane_opacity_shadow_map_bench", ["--benchmark_min_time=1"], True, [
        Table("Hair shadow maps", r"",
              lambda r: {"0": "opacity shadow map, 16 slices, graphics builder",
                         "1": "opacity shadow map, 16 slices, compute builder",
                         "2": "deep opacity map, 4 layers"}.get(r.args.get("0"), r.name),
              [ms(), ratio_to("ratio to compute builder", lambda r: "BM_OpacityShadowMap/1")],
              about="4,096 strands × 32 vertices at 512², one build per iteration."),
    ]),
    Bench("hair_shadow", "mane_hair_shadow_bench", ["--benchmark_min_time=1"], True, [
        Table("The ponytail's shadows", r"",
              lambda r: "interpolation, 4,933 guides → 50,000 strands" if "Interpolation" in r.name else
              {"0": "plain depth shadow map", "1": "opacity shadow map, graphics builder",
               "2": "opacity shadow map, compute builder", "3": "deep opacity map, 4 layers"}.get(
                  r.args.get("0"), r.name),
              [Column("GPU (ms)", "gpu_ms"), Column("ratio to depth map", "vs_depth"),
               Column("mean |ΔT| vs ray cast", "error")],
              about="the TressFX ponytail's 50,000 strands × 16 at 512² from its key light; the error is "
                    "against rays cast through the strands at 2,000 dense vertices."),
    ]),
    Bench("strand_interpolation_gpu", "mane_strand_interpolation_gpu_bench", ["--benchmark_min_time=1"], True, [
        Table("Dense strands, GPU against CPU", r"",
              lambda r: (f"{'GPU' if 'Gpu' in r.name else 'CPU'}, {int(r.args['0']):,} strands, "
                         f"{'3 guides' if r.args['1'] == '1' else '1 guide'}"
                         + (f", {threads(r.args['2'])}" if "2" in r.args else "")),
              [time_column(), Column("vertices/s", "items_per_second", si_rate)],
              about="positions and tangents of dense strands × 16 from 762 guides, along the Catmull-Rom "
                    "curve through the guides (`render.curve`)."),
    ]),
    Bench("skinning", "mane_skinning_bench", ["--benchmark_min_time=1"], True, [
        Table("Skinning", r"", skinning_label,
              [Column("ns per vertex", "ns_per_vertex"),
               ratio_to("ratio to the CPU on 1 thread", lambda r: f"BM_SkinningCpu/{r.args.get('0')}/1", "ns_per_vertex"),
               time_column("per mesh")],
              about="a 20,000-vertex limb on 40 joints (4 influences a vertex) with 3 morph targets, positions, "
                    "normals and tangents. The GPU rows are whole frames of the skinning pass alone: the "
                    "joint and morph upload, recording, submission and the wait for it, so on lavapipe a "
                    "fixed cost per submission is spread over the vertices."),
    ]),
    Bench("interpolation", "mane_interpolation_bench", ["--benchmark_min_time=1"], False, [
        Table("Dense strands on the CPU", r"",
              lambda r: ("copy baseline" if "Copy" in r.name else
                         "interpolation + tangents" if "Tangents" in r.name else "interpolation")
              + f", {int(r.args['0']):,} strands"
              + ("" if "Copy" in r.name or "Tangents" in r.name else
                 (", 3 guides" if r.args.get("1") == "1" else ", 1 guide"))
              + ("" if "Copy" in r.name else f", {threads(r.args[str(len(r.args) - 1)])}"),
              [time_column(), Column("vertices/s", "items_per_second", si_rate)],
              about="dense strands × 16 from 762 guides × 16, along the Catmull-Rom curve through the guides "
                    "(about twice the cost of straight segments: 732 µs against 374 µs for 4,095 strands "
                    "from one guide on 1 thread); the copy is a memcpy of as many vertices."),
    ]),
    Bench("physics", "mane_physics_bench", ["--benchmark_min_time=0.5", "--benchmark_repetitions=3"], False, [
        Table("Physics", r"^(?!BM_Character)", physics_label,
              [time_column(), Column("rate", "items_per_second", si_rate),
               Column("bytes/s", "bytes_per_second", si_rate)],
              about="10,000 guides × 32 particles on a swaying head, 4 constraint iterations per fixed "
                    "step, tethers on; collisions: a neck capsule and the SDF of a 20,480-triangle head, "
                    "friction 0.3. Rates: constraint projections or particle updates per second. The AVX2 "
                    "kernel is bit-identical to the scalar one; results are the same for any thread count. "
                    "The cloth frames: a 48 × 48 sheet pinned along one edge, draped over a ball and swung "
                    "about the vertical, 1/30 s in 4 steps of 8 sweeps on one thread, with and without self "
                    "collision at 3 mm. The sea: clear_sailing.json's 45 waves, 1,024 queries per "
                    "iteration (rate: queries per second); the floating box asks for the water over each "
                    "of its columns once per step."),
        Table("A groom on a skinned head", r"^BM_Character", character_label,
              [time_column(), Column("root update (µs)", "update_us"), Column("step (µs)", "step_us"),
               Column("update / step", "update_ratio"), Column("surface evaluation", "evaluate_us"),
               Column("colliders", "colliders_us"), Column("root targets", "targets_us"),
               Column("triangles", "triangles"), Column("roots", "points")],
              about="10,000 guides × 32 rooted on a 49,600-triangle skinned head that nods, three joint "
                    "capsules as colliders. A step's root update (the roots evaluated on the skinned "
                    "surface, the colliders moved into the head's frame, the root targets set) against the "
                    "simulation step of 1/120 s it feeds; the skinning itself is not counted. Times of the "
                    "update's parts in µs."),
    ]),
    Bench("ropes_vs_bullet", "mane_ropes_vs_bullet_bench", [], False, [
        Table("Against Bullet", r"",
              lambda r: f"{int(r.args['0']):,} ropes × {r.args['1']}",
              [Column("Bullet (ms per simulated s)", "bullet_ms"), Column("mane, tethers off", "mane_ms"),
               Column("mane, tethers on", "mane_tethers_ms"), Column("Bullet / mane", "bullet/mane", times),
               Column("Bullet / mane with tethers", "bullet/mane_tethers", times),
               Column("max stretch: Bullet", "bullet_stretch_max", percent),
               Column("mane off", "mane_stretch_max", percent),
               Column("mane on", "mane_tethers_stretch_max", percent)],
              about="the same ropes (1 cm segments released horizontally, h = 1/120 s, 4 iterations, "
                    "damping 0.01 a step, 2 s simulated) in Bullet's btSoftBody and in mane, one thread each."),
    ]),
    Bench("subdiv", "mane_subdiv_bench", ["--benchmark_min_time=0.5"], False, [
        Table("Tessellating the head", r"^BM_(AdaptiveFrame|DeformAndTessellateFrame|DeformAndUpdateVerticesFrame)/",
              lambda r: f"{subdiv_bench_name(r)}: {subdiv_label(r)}",
              [ms(), Column("triangles", "triangles")],
              about="the LeePerrySmith head at 1280×720, 1-pixel target, through the scan's own cage "
                    "and through nalu's coarse cage; the updates move the cage (a jaw opening by 3°) "
                    "first. The adaptive-against-uniform comparison is in the bench's log."),
        Table("The animated head", r"^BM_AnimatedHeadFrame/",
              subdiv_label,
              [Column("mean (ms)", "real_time"), Column("p90", "p90_ms"), Column("slowest", "worst_ms"),
               Column("frames that tessellate", "retessellated", percent),
               Column("frames that prepare", "prepared", percent)],
              about="one 4 s cycle at 60 Hz: the jaw moves while the head turns ±20°."),
        Table("Inside the World", r"^BM_(DeformingCageUpdate|WorldRefineForCamera)/",
              lambda r: ("cage update: " if "Cage" in r.name else "World::refineForCamera: ") + subdiv_label(r),
              [ms(), Column("retessellated", "retessellated", percent)],
              about="the cage update alone (the jaw's two poses in turn), and the head as a scene mesh "
                    "turning ±20° at 0.25 Hz through World::refineForCamera."),
        Table("A skinned cage bending", r"^BM_ElbowTubeFrame/",
              lambda r: ("the whole tube in view (1 m)" if r.args.get("distance_cm") == "100" else
                         f"the elbow filling the frame ({r.args.get('distance_cm', '?')} cm)")
              + f", {threads(r.args.get('threads', '?'))}",
              [ms(), Column("triangles", "triangles")],
              about="an open tube of 8 × 12 quads, 10 cm across and 60 cm long, on two joints (dual-quaternion "
                    "skinning), its elbow sweeping 0° → 90° → 0° over 120 frames; each frame skins the cage, "
                    "moves its limit surface and tessellates it for a still 1280×720 camera."),
    ]),
    Bench("fur", "mane_fur_bench", ["--benchmark_min_time=2"], True, [
        Table("Fur", r"^BM_(Empty|Fur)",
              lambda r: "empty frame" if "Empty" in r.name else (
                  "bunny, skin layer only" if r.args.get("0") == "1" else
                  f"{r.args.get('0')} shells" + (" + fins" if r.args.get("1") == "1" else "")),
              [ms(), ratio_to("ratio to the bare bunny", lambda r: "BM_FurFrame/1/0"),
               Column("fins", "fins")],
              about="the Stanford bunny (69,451 triangles) with shells from the cat-fur photo at 1280×720, "
                    "both faces and every shell drawn."),
        Table("Nalu's bunny", r"^BM_NaluBunny/",
              lambda r: NALU_BUNNY_CASES.get(r.args.get("case"), r.name),
              [ms(), ratio_to("ratio to the skin layer", lambda r: "BM_NaluBunny/case:0"),
               Column("shells drawn", "shells", lambda v: f"{v:.0f}"), Column("fins", "fins")],
              about="the bunny as `scenes/nalu.json` draws it at 1280×720: simplified to 3,000 triangles, "
                    "about 200 pixels tall, its 4 mm fur about 8 pixels; 15 shells from the cat-fur photo, "
                    "with fins. Goal: 15 ms."),
    ]),
]

# ---------------------------------------------------------------------------------------------
# Rendering the tables


# What Google Benchmark writes into every entry; the rest are the benchmark's own counters.
STANDARD_KEYS = {
    "name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit", "aggregate_name",
    "aggregate_unit", "label", "error_occurred", "error_message", "items_per_second", "bytes_per_second",
}


def markdown_table(headers: list[str], rows: list[list[str]]) -> str:
    escape = lambda cell: cell.replace("|", "\\|")
    lines = ["| " + " | ".join(map(escape, headers)) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(map(escape, row)) + " |" for row in rows]
    return "\n".join(lines)


def render_table(table: Table, runs: list[Run]) -> Optional[str]:
    runs = [r for r in runs if re.search(table.include, r.name)]
    if not runs:
        return None
    by_name = {r.name: r for r in runs}
    columns = list(table.columns)
    if table.more_counters:
        known = {c.key for c in columns}
        found = {k for r in runs for k, v in r.entry.items()
                 if k not in STANDARD_KEYS and k not in known and isinstance(v, (int, float))
                 and re.search(table.more_counters, k)}
        ordered = [k for o in table.counter_order for k in sorted(found) if same_counter(k, o)]
        ordered += sorted(found - set(ordered))
        columns += [Column(table.counter_header(k), k) for k in ordered]

    def cell(run: Run, column: Column) -> str:
        if run.entry.get("error_occurred"):
            return ""
        value = run.value(column.key)
        if value is None:
            return ""
        if column.baseline:
            base_name = column.baseline(run)
            base = by_name.get(base_name) if base_name else None
            base_value = base.value(column.key) if base else None
            if not base_value:
                return ""
            value /= base_value
        return column.fmt(value)

    cells = [[cell(r, c) for c in columns] for r in runs]
    keep = [i for i in range(len(columns)) if any(row[i] for row in cells)]
    headers = [table.row_header] + [columns[i].header for i in keep]
    rows = []
    for run, row in zip(runs, cells):
        label = table.label(run)
        if run.entry.get("error_occurred"):
            label += f" (skipped: {run.entry.get('error_message', 'error')})"
        rows.append([label] + [row[i] for i in keep])
    return markdown_table(headers, rows)


def slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")


def cpu_model() -> str:
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown CPU"


def cpu_model_of(folder: Path) -> str:
    """The folder's name, or this machine's CPU model where the folder is this machine's."""
    return cpu_model() if folder.name == slug(cpu_model()) else folder.name


def machine_of(folder: Path) -> dict:
    path = folder / "machine.json"
    return json.loads(path.read_text()) if path.exists() else {}


# Google Benchmark's own banner on stderr: the context, already in the JSON.
BANNER = re.compile(r"^(\d{4}-\d\d-\d\dT\S+$|Running |Run on |CPU Caches:|  L\d |Load Average:|\*\*\*WARNING\*\*\* )")


def printed_lines(log: Path, context: dict) -> list[str]:
    """The log's lines that are not the results, each once (with how often it was printed)."""
    custom = {k for k, v in context.items() if isinstance(v, str)}
    counts: dict[str, int] = {}
    for line in log.read_text().splitlines():
        if line.strip() and not BANNER.match(line) and line.split(":", 1)[0] not in custom:
            counts[line] = counts.get(line, 0) + 1
    return [line if n == 1 else f"{line}  (×{n})" for line, n in counts.items()]


def render_folder(folder: Path) -> str:
    machine = machine_of(folder)
    files = {p.stem: p for p in folder.glob("*.json") if p.name != "machine.json"} if folder.is_dir() else {}
    contexts = [json.loads(p.read_text()).get("context", {}) for p in files.values()]
    cpu = next((c["cpu"] for c in contexts if c.get("cpu")), machine.get("cpu") or cpu_model_of(folder))
    out = [f"## {cpu}", ""]
    if machine.get("notes"):
        out += [machine["notes"], ""]
    for bench in BENCHES:
        path = files.pop(bench.name, None)
        data = json.loads(path.read_text()) if path else None
        runs = read_runs(data) if data else []
        context = data.get("context", {}) if data else {}
        date = context.get("date", "")[:10] or "undated"
        driver = context.get("driver") or machine.get("driver", "driver not recorded")
        for table in bench.tables:
            out += [f"### {table.title}", ""]
            text = render_table(table, runs) if runs else None
            if text is None:
                out += [f"Not measured on this CPU yet: `{bench.command()}`.", ""]
                continue
            facts = [date, context.get("cpu") or machine.get("cpu", cpu)]
            facts.append(driver if bench.gpu else "CPU only")
            facts.append(f"{context.get('num_cpus', '?')} CPUs")
            out += [f"`{bench.command()}` · " + " · ".join(facts), ""]
            if context.get("extra_args"):
                extra = " ".join(map(shlex.quote, context["extra_args"]))
                out += [f"**Not a full run**: the command had `{extra}` added, so these rows are a sample, "
                        "not the table's figures.", ""]
            if table.about:
                out += [table.about[0].upper() + table.about[1:], ""]
            out += [text, ""]
        log = folder / f"{bench.name}.log"
        lines = printed_lines(log, context) if path and log.exists() else []
        if lines:  # notes (a missing asset changes what was measured) and summaries
            if len(lines) > MAX_LOG_LINES:
                lines = lines[:MAX_LOG_LINES] + [f"… {len(lines) - MAX_LOG_LINES} more lines in {log.name}"]
            out += ["<details><summary>What the benchmark printed besides its results</summary>", "",
                    "```", *lines, "```", "", "</details>", ""]
    for stem, path in sorted(files.items()):  # JSON no specification knows: listed plainly
        runs = read_runs(json.loads(path.read_text()))
        generic = Table(stem, r"", lambda r: r.name, [ms()], more_counters=r".")
        text = render_table(generic, runs)
        if text:
            out += [f"### {stem} ({path.name})", "", text, ""]
    return "\n".join(out).rstrip() + "\n"


def write_page(results: Path, page_path: Path) -> None:
    folders = sorted(p for p in results.iterdir() if p.is_dir() and any(p.glob("*.json")))
    if not folders:  # every table's heading and command, so links to them resolve
        folders = [results / slug(cpu_model())]
    body = "\n".join(render_folder(f) for f in folders)
    page = page_path.read_text() if page_path.exists() else f"# Performance\n\n{BEGIN}\n{END}\n"
    if BEGIN not in page or END not in page:
        sys.exit(f"{page_path}: no {BEGIN} … {END} markers to write the tables between")
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    generated = (f"{BEGIN}\n<!-- Generated by bench/results/make_tables.py from bench/results/*/*.json: "
                 f"edit the script, not the tables. -->\n\n{body}{END}")
    page_path.write_text(head + generated + tail)
    print(f"wrote {page_path} from {len(folders)} folder(s)")


# ---------------------------------------------------------------------------------------------
# Running the benchmarks


def driver_of_mane() -> str:
    """The driver line of `mane info` ("llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"), or ""."""
    try:
        info = subprocess.run([str(ROOT / "build/release/mane"), "info"], capture_output=True, text=True,
                              timeout=120).stdout
    except (OSError, subprocess.TimeoutExpired):
        return ""
    match = re.search(r"^driver:\s*(.+)$", info, re.M)
    return match.group(1).strip() if match else ""


def context_value(text: str) -> str:
    # --benchmark_context takes key=value pairs separated by commas.
    return text.replace(",", ";").replace("=", ":")


def run_benches(names: list[str], results: Path, extra: list[str]) -> None:
    unknown = set(names) - {b.name for b in BENCHES}
    if unknown:
        sys.exit(f"unknown benchmark(s): {', '.join(sorted(unknown))}; known: "
                 + ", ".join(b.name for b in BENCHES))
    cpu = cpu_model()
    folder = results / slug(cpu)
    folder.mkdir(parents=True, exist_ok=True)
    driver = driver_of_mane()
    # "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)" is Mesa's name for lavapipe's driver.
    driver_text = "lavapipe " + driver.removeprefix("llvmpipe ") if driver.startswith("llvmpipe") else driver
    machine = machine_of(folder)
    machine.update({"cpu": cpu, "driver": driver_text or machine.get("driver", "")})
    (folder / "machine.json").write_text(json.dumps(machine, indent=2) + "\n")
    for bench in BENCHES:
        if names and bench.name not in names:
            continue
        binary = ROOT / BIN / bench.binary
        if not binary.exists():
            print(f"skipped {bench.name}: {binary.relative_to(ROOT)} is not built", file=sys.stderr)
            continue
        context = f"cpu={context_value(cpu)}"
        if bench.gpu and driver_text:
            context += f",driver={context_value(driver_text)}"
        command = [str(binary), *bench.args, *extra, f"--benchmark_out={folder / (bench.name + '.json')}",
                   "--benchmark_out_format=json", f"--benchmark_context={context}"]
        print(f"running {bench.command()}", flush=True)
        with open(folder / f"{bench.name}.log", "w") as log:
            result = subprocess.run(command, cwd=ROOT, stderr=log)
        if result.returncode != 0:
            print(f"{bench.name} exited {result.returncode}; see {folder / (bench.name + '.log')}", file=sys.stderr)
        out = folder / f"{bench.name}.json"
        if extra and out.exists():  # not the listed command: the page says so beside the table
            data = json.loads(out.read_text())
            data.setdefault("context", {})["extra_args"] = extra
            out.write_text(json.dumps(data, indent=2) + "\n")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", nargs="*", metavar="NAME", help="run these benchmarks first (none named: all)")
    parser.add_argument("--commands", action="store_true", help="print each benchmark's command and JSON name")
    parser.add_argument("--results", type=Path, default=RESULTS, help="the folder of per-CPU folders (default: %(default)s)")
    parser.add_argument("--page", type=Path, default=PAGE, help="the page to write the tables into (default: %(default)s)")
    parser.add_argument("--extra", action="append", default=[], metavar="ARG",
                        help="one more argument for every benchmark run, after the listed ones (a smoke test: "
                             "--extra=--benchmark_min_time=0.01)")
    options = parser.parse_args()
    if options.commands:
        for bench in BENCHES:
            print(f"{bench.name + '.json':32} {bench.command()}")
        return
    if options.run is not None:
        run_benches(options.run, options.results, options.extra)
    write_page(options.results, options.page)


if __name__ == "__main__":
    main()
