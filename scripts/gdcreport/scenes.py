"""Writes results/report.md and its PNG plots from the scene runs of scripts/run.

Input, in the results directory: for every run SCENE_METHOD_BOXES.json (the summary a scene
program writes with --summary) and .csv (its per-step measures, --csv); manifold_demo.txt and
ode_stack.txt when present; SCENE_animation.gif from scripts/animate.py, or animations.txt saying
why there are none. Plots use matplotlib (Debian's python3-matplotlib); numbers, tables, reading the runs and saving
the plots come from the rest of this package (gdcreport), shared with the other reports.

The report answers first: a summary with one line per scene run (scene and box shape), each
method's PASS/FAIL from the scene's own check and what gdcontact costs per step against ODE's
native colliders; then per scene a compact table of numbers (sentences go in the notes under it),
its plot and animation; the full tables of every measure come last. `python3 -m gdcreport check`
(check.py) checks the summary against the runs.

Usage: python3 -m gdcreport scenes RESULTS_DIR [--build BUILD_DIR] [--seconds N]
"""
import argparse
import math
import os
import platform
import subprocess
import sys

import matplotlib

from gdcreport import data, plots
from gdcreport.numbers import fmt, ratio
from gdcreport.plots import plt
from gdcreport.tables import table, table_lines

METHODS = ["gdc", "tracking", "ode"]
METHOD_LABEL = {"gdc": "gdcontact", "tracking": "contact tracking", "ode": "ODE 0.16.2 native"}
# One look per method in every plot. Lines that coincide stay visible: gdcontact's is wide and
# drawn first, the others are narrower, dashed or dotted, and drawn on top of it.
METHOD_STYLE = {
    "gdc": dict(color="tab:blue", linestyle="-", linewidth=3.0, alpha=0.75, marker="o", zorder=2),
    "tracking": dict(color="tab:orange", linestyle="--", linewidth=1.5, marker="s", zorder=3),
    "ode": dict(color="tab:green", linestyle=":", linewidth=2.0, marker="^", zorder=4),
}
BOXES_LABEL = {"box": "dBox", "convex": "dConvex"}
SCENES = ["box_drop", "tower", "brick_wall", "composites"]
# Scenes beyond the paper's, reported after them where scripts/run ran them (issue 33: curved shapes).
EXTRA_SCENES = ["barrels", "terrain"]
SCENE_TITLE = {"box_drop": "Box drop", "tower": "Tower", "brick_wall": "Brick wall", "composites": "Composites",
               "barrels": "Barrels", "terrain": "Terrain"}
SUMMARY_HEADING = "## Summary"
# A log-scale plot cannot show 0; values below this are drawn at it (stated under each plot).
LOG_FLOOR = 1e-18
# Per-step times below this (ms) are a few microseconds: single-run ratios of them are noise.
NOISE_MS = 0.05


def floor_for_log(values):
    return [max(v, LOG_FLOOR) if not math.isnan(v) else float("nan") for v in values]


def method_order(method):
    return METHODS.index(method) if method in METHODS else len(METHODS)


def scene_configurations(runs):
    """(scene, boxes) pairs in report order: the paper's scene order; within a scene the dBox run
    first, except the brick wall's dConvex run, the one that separates the methods."""
    def order(configuration):
        scene, boxes = configuration
        first = "convex" if scene == "brick_wall" else "box"
        known = SCENES + EXTRA_SCENES
        return (known.index(scene) if scene in known else len(known), scene, boxes != first, boxes)
    return sorted({(scene, boxes) for scene, _, boxes in runs}, key=order)


def methods_of(runs, scene, boxes):
    return sorted((m for (s, m, b) in runs if s == scene and b == boxes), key=method_order)


def scene_runs(runs, scene):
    """(method, boxes, summary) of every run of the scene, in report order."""
    for s, boxes in scene_configurations(runs):
        if s == scene:
            for method in methods_of(runs, scene, boxes):
                yield method, boxes, runs[(scene, method, boxes)][0]


def configuration_label(runs, scene, boxes):
    """Scene name, with the box shape only where the scene was run with both."""
    shapes = {b for (s, _, b) in runs if s == scene}
    title = SCENE_TITLE.get(scene, scene)
    return f"{title}, {BOXES_LABEL.get(boxes, boxes)}" if len(shapes) > 1 else title


def verdict(summary):
    return "PASS" if summary["success"] else "FAIL"


# ---- what each scene's check is about: the one number beside the verdict in the summary
def _tower_levels(summary):
    values = summary["values"]
    return f"{values['stacked_before_push']:.0f} → {values['stacked_now']:.0f}"


HEADLINE = {
    "box_drop": ("oscillation after rest, m/s", lambda s: fmt(s["oscillation"])),
    "tower": ("objects stacked before → after the push", _tower_levels),
    "brick_wall": ("max displacement of the rest of the wall, mm", lambda s: fmt(1e3 * s["values"]["max_displacement"])),
    "composites": ("fastest body's speed at the end, m/s", lambda s: fmt(s["values"]["final_speed"])),
    "barrels": ("most sag since rest, m", lambda s: fmt(s["values"]["max_sag"])),
    "terrain": ("most drift since rest, m", lambda s: fmt(s["values"]["max_drift"])),
}


def headline(scene, summary):
    if scene not in HEADLINE:
        return ""
    try:
        return HEADLINE[scene][1](summary)
    except KeyError:  # a scene program that no longer reports the value: the verdict stands alone
        return ""


def has_messages(results, scene, method, boxes):
    """Did ODE print anything during the run (scripts/run keeps its stderr only when not empty)?"""
    path = os.path.join(results, f"{scene}_{method}_{boxes}.stderr")
    return os.path.exists(path) and os.path.getsize(path) > 0


def step_ms(summary):
    return summary["collision_ms"] + summary["solver_ms"]


def summary_section(runs, results):
    """The report's first section: one line per scene run, a verdict per method, the cost."""
    configurations = scene_configurations(runs)
    columns = [m for m in METHODS if any(m == key[1] for key in runs)]
    out = [SUMMARY_HEADING + "\n"]
    passes = {m: sum(1 for (s, mm, b) in runs if mm == m and runs[(s, mm, b)][0]["success"]) for m in columns}
    counts = {m: sum(1 for (s, mm, b) in runs if mm == m) for m in columns}
    out.append("Checks passed: " + ", ".join(f"**{METHOD_LABEL[m]} {passes[m]} of {counts[m]}**" for m in columns)
               + ". Each scene's check is its own (the scene program's PASS/FAIL line); the number beside a "
               "verdict is what the check is about (column *measured*).\n")
    header = (["scene", "measured"] + [METHOD_LABEL[m] for m in columns]
              + ["gdcontact ÷ ODE: collision ms/step", "gdcontact ÷ ODE: whole step"])
    rows = []
    like_for_like = []  # (collision ratio, step ratio, label, gdc run, ODE run) where both pass
    for scene, boxes in configurations:
        cells = []
        for method in columns:
            run = runs.get((scene, method, boxes))
            cells.append(f"{verdict(run[0])} {headline(scene, run[0])}".strip() if run else "not run")
        gdc, ode = runs.get((scene, "gdc", boxes)), runs.get((scene, "ode", boxes))
        if gdc and ode:
            collision = ratio(gdc[0]["collision_ms"], ode[0]["collision_ms"])
            step = ratio(step_ms(gdc[0]), step_ms(ode[0]))
            mark = "" if ode[0]["success"] else " †"
            cost = [f"{fmt(collision, 2)}×{mark}", f"{fmt(step, 2)}×{mark}"]
            if ode[0]["success"] and gdc[0]["success"]:
                like_for_like.append((collision, step, configuration_label(runs, scene, boxes), gdc[0], ode[0]))
        else:
            cost = ["–", "–"]
        rows.append([configuration_label(runs, scene, boxes), HEADLINE.get(scene, ("",))[0]] + cells + cost)
    out.extend(table_lines(header, rows))
    out.append("")
    notes = ["Cost: the mean wall-clock time per step of gdcontact's run divided by that of ODE's native "
             "colliders' run of the same scene and box shape — the collision pass (`dSpaceCollide` with its "
             "near-callback) and the whole step (collision + world step; gdcontact's fuller manifolds give the "
             "solver more contact rows). One run each on this machine, so expect tens of per cent of noise "
             "(docs/benchmarks.md has the careful per-pair figures)."]
    # Steps this short are a few microseconds: one run's mean is mostly timer and cache noise.
    quick = {}
    for (scene, method, boxes), (summary, _) in sorted(runs.items()):
        if method == "ode" and step_ms(summary) < NOISE_MS:
            quick.setdefault(SCENE_TITLE.get(scene, scene), []).append(BOXES_LABEL.get(boxes, boxes))
    timed = [entry for entry in like_for_like if step_ms(entry[4]) >= NOISE_MS]
    if timed:
        collisions = [entry[0] for entry in timed]
        notes.append(f"Where both pass (the same world simulated) and a step takes ODE at least {NOISE_MS} ms: "
                     f"collision {fmt(min(collisions), 2)}–{fmt(max(collisions), 2)}× ODE's.")
        worst = max(timed, key=lambda entry: entry[1])
        if "mean_contacts" in worst[3] and "mean_contacts" in worst[4]:
            notes.append(f"The whole step costs most in {worst[2]}: {fmt(worst[1], 2)}×, with "
                         f"{fmt(worst[3]['mean_contacts'])} contacts per step from gdcontact against "
                         f"{fmt(worst[4]['mean_contacts'])} from ODE's colliders — the world step's LCP grows "
                         "with the contact rows.")
    if quick:
        which = "; ".join(f"{scene} ({', '.join(shapes)})" for scene, shapes in quick.items())
        notes.append(f"{which}: ODE's steps take under {NOISE_MS} ms, so those ratios are mostly timer noise.")
    if any(key[1] == "ode" and not runs[key][0]["success"] for key in runs):
        notes.append("†: ODE's run failed its check, so it simulated another world (an unbuilt tower, a fallen "
                     "wall) with other contacts; that ratio is not like for like.")
    messages = [f"{configuration_label(runs, scene, boxes)} ({METHOD_LABEL.get(method, method)})"
                for scene, boxes in scene_configurations(runs) for method in methods_of(runs, scene, boxes)
                if has_messages(results, scene, method, boxes)]
    if messages:
        # A solver message often comes with a kick the verdict alone does not show.
        notes.append("ODE printed messages during " + ", ".join(messages) + ": see *Messages from ODE* at the end.")
    animations = [scene for scene in SCENES + EXTRA_SCENES if os.path.exists(os.path.join(results, f"{scene}_animation.gif"))]
    skipped = os.path.join(results, "animations.txt")
    if animations:
        notes.append("Animations of the runs (the viewer replaying each scene headless, methods side by side): "
                     + ", ".join(f"[{SCENE_TITLE[s].lower()}]({s}_animation.gif)" for s in animations) + ".")
    elif os.path.exists(skipped):
        with open(skipped) as f:
            notes.append("No animations: " + f.read().strip())
    out.extend(f"- {note}" for note in notes)
    out.append("")
    return out


# ---- compact per-scene tables: numbers only
def compact_table(runs, scene, columns):
    """columns: (header, function of the summary returning text). One row per method and shape."""
    # The box shape gets a column only in scenes run with both.
    both = len({b for (s, _, b) in runs if s == scene}) > 1
    header = ["method"] + (["boxes"] if both else []) + [title for title, _ in columns]
    rows, shown = [], []
    for method, boxes, summary in scene_runs(runs, scene):
        shape = [BOXES_LABEL.get(boxes, boxes)] if both else []
        rows.append([METHOD_LABEL.get(method, method)] + shape + [function(summary) for _, function in columns])
        shown.append((method, boxes, summary))
    return table(header, rows), shown


def verdict_cell(summary):
    return f"**{verdict(summary)}**"


TIMING_COLUMNS = [("contacts/step", lambda s: fmt(s.get("mean_contacts"))),
                  ("ms/step: collision / whole", lambda s: f"{fmt(s['collision_ms'])} / {fmt(step_ms(s))}")]


def outcome_notes(shown):
    """The scene's own verdict sentences, under the table rather than in it."""
    return [f"- {METHOD_LABEL.get(m, m)}, {BOXES_LABEL.get(b, b)}: {verdict(s)} — {s['outcome']}" for m, b, s in shown]


def identical_runs(runs, scene, method):
    """True when the method's dBox and dConvex runs of a scene gave the very same measures."""
    box, convex = runs.get((scene, method, "box")), runs.get((scene, method, "convex"))
    if not box or not convex:
        return False
    skip = {"collision_seconds", "solver_seconds"}
    columns = [c for c in box[1] if c not in skip]
    return bool(columns) and all(box[1][c] == convex[1].get(c) for c in columns)


# ---- plots
def save_figure(figure, results, name):
    """Writes the figure to results/name, closes it and returns the file name for the report."""
    return os.path.basename(plots.save_figure(figure, os.path.join(results, name)))


def line_style(method, points):
    """The method's style; markers on about 12 points of a long series so they do not blot it out,
    staggered between the methods so that coinciding lines still show every method's marker."""
    style = dict(METHOD_STYLE[method])
    every = max(1, points // 12)
    style["markevery"] = (method_order(method) * every // len(METHODS), every)
    style["markersize"] = 5
    return style


def plot_box_drop(runs, results):
    shapes = [b for b in ("box", "convex") if any(k[0] == "box_drop" and k[2] == b for k in runs)]
    panels = [("penetration", "penetration error (m)"), ("alignment", "alignment error (rad)"),
              ("speed", "speed |v| + |ω|·r (m/s)")]
    figure, axes = plt.subplots(len(panels), len(shapes), figsize=(6 * len(shapes), 9), sharex=True, sharey="row",
                                squeeze=False)
    for column, boxes in enumerate(shapes):
        for method in METHODS:
            key = ("box_drop", method, boxes)
            if key not in runs:
                continue
            series = runs[key][1]
            for row, (name, _) in enumerate(panels):
                axes[row][column].semilogy(series["time"], floor_for_log(series[name]),
                                           label=METHOD_LABEL[method], **line_style(method, len(series["time"])))
        axes[0][column].set_title(f"{BOXES_LABEL[boxes]} box")
        axes[-1][column].set_xlabel("time (s)")
    for row, (_, label) in enumerate(panels):
        axes[row][0].set_ylabel(label)
        for axis in axes[row]:
            axis.axvline(2.0, color="grey", linewidth=0.8, linestyle="--")
            axis.grid(True, which="major", alpha=0.3)
    axes[0][0].legend(fontsize=8)
    figure.suptitle("Box drop (paper Fig. 9): measures count after t = 2 s (dashed line)")
    return save_figure(figure, results, "box_drop_errors.png")


def plot_wall(runs, results):
    shapes = [b for b in ("convex", "box") if any(k[0] == "brick_wall" and k[2] == b for k in runs)]
    figure, axes = plt.subplots(1, len(shapes), figsize=(6 * len(shapes), 4.8), sharey=True, squeeze=False)
    for axis, boxes in zip(axes[0], shapes):
        for method in METHODS:
            key = ("brick_wall", method, boxes)
            if key not in runs:
                continue
            values = runs[key][0]["values"]
            points = [(k, values[f"after_removal_{k}"]) for k in range(1, 11) if f"after_removal_{k}" in values]
            if not points:
                continue
            style = dict(METHOD_STYLE[method], markersize=6)
            axis.semilogy([k for k, _ in points], [1e3 * max(v, 1e-12) for _, v in points],
                          label=METHOD_LABEL[method], **style)
        axis.axhline(10.0, color="red", linewidth=0.8, linestyle="-.", label="stands: below 10 mm")
        axis.set_title(f"{BOXES_LABEL[boxes]} bricks")
        axis.set_xlabel("bricks removed")
        axis.grid(True, which="major", alpha=0.3)
    axes[0][0].set_ylabel("max displacement of the remaining bricks (mm)")
    axes[0][0].legend(fontsize=8, loc="center left")
    figure.suptitle("Brick wall (paper Fig. 7–8): displacement after each removal")
    return save_figure(figure, results, "brick_wall_displacement.png")


def plot_tower(runs, results):
    figure, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    push_window = None
    for method in METHODS:
        key = ("tower", method, "box")
        if key not in runs:
            continue
        series = runs[key][1]
        if "top_tilt" not in series:
            continue
        time = series["time"]
        pushing = [t for t, f in zip(time, series["push_force"]) if f > 0]
        if pushing:
            push_window = (min(pushing), max(pushing))
        start = next((i for i, t in enumerate(time) if t >= (push_window[0] - 1.0 if push_window else 0)), 0)
        style = line_style(method, len(time) - start)
        axes[0].semilogy(time[start:], floor_for_log(series["top_tilt"][start:]), label=METHOD_LABEL[method], **style)
        axes[1].semilogy(time[start:], floor_for_log(series["lean_change"][start:]), label=METHOD_LABEL[method],
                         **style)
    for axis in axes:
        if push_window:
            axis.axvspan(*push_window, color="grey", alpha=0.15, label="push")
        axis.grid(True, alpha=0.3)
    axes[0].set_ylabel("top object's tilt (rad)")
    axes[1].set_ylabel("tower lean change (rad)")
    axes[1].set_xlabel("time (s)")
    axes[0].legend(fontsize=8)
    axes[0].set_title("Tower (paper Fig. 5–6): tilt under the downward push on the top object")
    return save_figure(figure, results, "tower_tilt.png")


def rest_time(series):
    """The first time the scene measures drift (it is NaN until the scene declares rest)."""
    return next((t for t, d in zip(series["time"], series["drift"]) if not math.isnan(d)), None)


def plot_composites(runs, results):
    panels = [("speed", "fastest body's speed\n|v| + |ω|·r (m/s)"),
              ("drift", "drift since rest (m)"),
              ("penetration", "deepest overlap of\nany two parts (m)")]
    figure, axes = plt.subplots(len(panels), 1, figsize=(9, 9), sharex=True)
    rest, end = None, None
    for method in METHODS:
        key = ("composites", method, "box")
        if key not in runs:
            continue
        series = runs[key][1]
        rest = rest_time(series) if rest is None else rest
        end = series["time"][-1]
        for axis, (column, _) in zip(axes, panels):
            # Exact zeros (before the first contact; drift at the moment of rest) are left out
            # rather than drawn at a floor: here they would only stretch the axis.
            values = [v if v > 0 else float("nan") for v in series[column]]
            axis.semilogy(series["time"], values, label=METHOD_LABEL[method], **line_style(method, len(values)))
    for axis, (_, label) in zip(axes, panels):
        axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
        if rest is not None:
            axis.axvspan(rest, end, color="grey", alpha=0.12, label="at rest (measures count)")
    axes[-1].set_xlabel("time (s)")
    axes[0].legend(fontsize=8, loc="lower left")
    axes[0].set_title("Composites (paper Fig. 10): how still the stack rests, and overlaps")
    return save_figure(figure, results, "composites_rest.png")


def command_output(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def full_measures_table(runs, scene):
    header = ["method", "boxes", "solver", "penetration max / mean (m)", "alignment max / mean (rad)", "drift (m)",
              "twist (rad)", "sag (m)", "oscillation (m/s)", "collision / solver (ms per step)"]
    rows = []
    for method, boxes, summary in scene_runs(runs, scene):
        solver = summary["stepper"] + (f" {summary['iterations']} it" if summary["stepper"] == "quick" else "")
        rows.append([METHOD_LABEL.get(method, method), BOXES_LABEL.get(boxes, boxes), f"{solver}, dt {summary['dt']}",
                     f"{fmt(summary['max_penetration'])} / {fmt(summary['mean_penetration'])}",
                     f"{fmt(summary['max_alignment'])} / {fmt(summary['mean_alignment'])}", fmt(summary["max_drift"]),
                     fmt(summary["max_twist"]), fmt(summary["max_sag"]), fmt(summary["oscillation"]),
                     f"{fmt(summary['collision_ms'])} / {fmt(summary['solver_ms'])}"])
    return table(header, rows)


def animation(results, scene):
    name = f"{scene}_animation.gif"
    if not os.path.exists(os.path.join(results, name)):
        return []
    return [f"![{SCENE_TITLE[scene].lower()}, the methods side by side]({name})\n",
            "The viewer replaying the same scripted run headless (`scripts/animate.py`), sped up; each "
            "panel's label is that method's verdict above.\n"]


def scene_section(runs, results, scene, heading, setup, columns, extra=None, plot=None, plot_note=None):
    if not any(key[0] == scene for key in runs):
        return []
    out = [f"## {heading}\n", setup + "\n"]
    table, shown = compact_table(runs, scene, columns)
    out.append(table + "\n")
    out.extend(outcome_notes(shown))
    out.append("")
    if extra:
        out.extend(extra)
    if plot:
        out.append(f"![{heading}]({plot(runs, results)})\n")
        if plot_note:
            out.append(plot_note + "\n")
    out.extend(animation(results, scene))
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--build", default="build")
    parser.add_argument("--seconds", type=float, default=None, help="wall time of the runs, for the report")
    arguments = parser.parse_args(argv)
    results = arguments.results
    runs = data.load_scene_runs(results)
    if not runs:
        sys.exit(f"no scene results (*.json) in {results}")

    out = []
    out.append("# gdcontact: the paper's scenes with ODE — results\n")
    out.append("Generated by `scripts/run` (overwritten by every run). "
               f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.system()} {platform.release()}; "
               f"ODE {command_output(['pkg-config', '--modversion', 'ode'])} (double precision); "
               f"matplotlib {matplotlib.__version__}."
               + (f" The build and runs took {arguments.seconds:.0f} s." if arguments.seconds is not None else "") + "\n")
    out.append("Methods: **gdcontact** (`gdc::ode::collide`, the paper's method), **contact tracking** "
               "(a Bullet-style persistent manifold fed by libccd's MPR, the paper's baseline), **ODE 0.16.2 "
               "native** (`dCollide`: dBoxBox / dBoxPlane for dBox, libccd for dConvex pairs).\n")
    out.extend(summary_section(runs, results))
    animated = any(name.endswith("_animation.gif") for name in os.listdir(results))
    out.append("Below, per scene: a table of the measures that matter for it (definitions in docs/measures.md; "
               "taken after the scene declares its bodies at rest; penetration is the geometric overlap of every "
               "touching pair by the separating-axis oracle, not what a method reports), the scene's own verdict "
               f"lines, {'a plot and an animation' if animated else 'a plot'}. Every measure of every run is in the "
               "last section.\n")

    # ---- box drop
    extra = []
    for boxes in ("box", "convex"):
        gdc, tracking = runs.get(("box_drop", "gdc", boxes)), runs.get(("box_drop", "tracking", boxes))
        if gdc and tracking:
            g, t = gdc[0], tracking[0]
            extra.append(f"Tracking ÷ gdcontact ({BOXES_LABEL[boxes]}): penetration max "
                         f"{fmt(ratio(t['max_penetration'], g['max_penetration']))}×, alignment max "
                         f"{fmt(ratio(t['max_alignment'], g['max_alignment']))}×, oscillation "
                         f"{fmt(ratio(t['oscillation'], g['oscillation']))}×.\n")
    same = [METHOD_LABEL[m] for m in METHODS if identical_runs(runs, "box_drop", m)]
    if same:
        extra.append(f"Identical dBox and dConvex runs (every per-step measure): {', '.join(same)} — both shapes "
                     "give the method the same polytope.\n")
    out.extend(scene_section(
        runs, results, "box_drop", "Box drop (paper Fig. 9)",
        "A 0.5 × 0.4 × 0.3 m box (60 kg) dropped tilted from 1 m onto the plane; dWorldStep, dt 0.01 s, ERP 0.2, "
        "CFM 1e-10 (ODE's defaults). Measures after t = 2 s.",
        [("verdict", verdict_cell), ("penetration max (m)", lambda s: fmt(s["max_penetration"])),
         ("alignment max (rad)", lambda s: fmt(s["max_alignment"])),
         ("oscillation (m/s)", lambda s: fmt(s["oscillation"]))] + TIMING_COLUMNS,
        extra, plot_box_drop,
        f"Values below {LOG_FLOOR:g} (exact zeros) are drawn at {LOG_FLOOR:g}. Where lines coincide, the wide "
        "blue line is gdcontact's and the dotted green one on it ODE's. The penetration of a box resting on four "
        "exact contacts is not zero but ODE's constraint compliance, weight per contact × dt × CFM / ERP."))

    # ---- tower
    out.extend(scene_section(
        runs, results, "tower", "Tower (paper Fig. 5–6)",
        "Nine convex objects and two gears are picked up one by one by a scripted builder and stacked; then the "
        "top object is pushed down, 3 cm off its axis (inside every level's support), with the tower's weight "
        "for 2 s (0.5 s ramp), and let go.",
        [("verdict", verdict_cell),
         ("stacked before / after push", lambda s: _tower_levels(s).replace(" → ", " / ")),
         ("top tilt in push (rad)", lambda s: fmt(s["values"].get("max_top_tilt_during_push"))),
         ("lean change (rad)", lambda s: fmt(s["values"].get("max_lean_change_during_push")))] + TIMING_COLUMNS,
        None, plot_tower, f"Values below {LOG_FLOOR:g} (exact zeros) are drawn at {LOG_FLOOR:g}."))

    # ---- wall
    same = [METHOD_LABEL[m] for m in METHODS if identical_runs(runs, "brick_wall", m)]
    extra = []
    if same:
        extra.append(f"Identical dConvex and dBox runs: {', '.join(same)} (the same polytope either way); "
                     "ODE's native colliders differ: libccd for dConvex, dBoxBox for dBox.\n")
    out.extend(scene_section(
        runs, results, "brick_wall", "Brick wall (paper Fig. 7–8)",
        "63 bricks in running bond (10 per course, 6 courses, half bricks at the ends of odd courses); after 2 s "
        "of settling, ten bricks that nothing rests on are removed one per second, cutting a stepped notch. "
        "QuickStep (50 iterations): compare with ODE's exact dBoxBox on dBox bricks. Stands: no remaining brick "
        "moved more than 10 mm.",
        [("verdict", verdict_cell),
         ("max displacement (mm)", lambda s: fmt(1e3 * s["values"]["max_displacement"])
          if "max_displacement" in s["values"] else "–"),
         ("twist max (rad)", lambda s: fmt(s["max_twist"]))] + TIMING_COLUMNS,
        extra, plot_wall,
        "Left and right differ only in ODE's collider; the series after each removal are in the last section."))

    # ---- composites
    out.extend(scene_section(
        runs, results, "composites", "Composites (paper Fig. 10)",
        "A table, two gears, a cross and an L (each one body of several convex parts) are let go one after "
        "another onto one spot and stack; a dumbbell with octagonal wheels lands beside them. dWorldStep, four "
        "contacts per pair of parts.",
        [("verdict", verdict_cell), ("speed at the end (m/s)", lambda s: fmt(s["values"].get("final_speed"))),
         ("oscillation after rest (m/s)", lambda s: fmt(s["oscillation"])),
         ("drift max (m)", lambda s: fmt(s["max_drift"]))] + TIMING_COLUMNS,
        None, plot_composites,
        "The shaded span is the time after the scene declares rest, over which oscillation and drift are "
        "measured (exact zeros are not drawn); a spike there is a kick — look for the run's ODE message under "
        "*Messages from ODE*."))

    # The columns of the scenes of bodies at rest (samples/scenes/resting_scene.hpp: barrels, terrain).
    RESTING_COLUMNS = [("verdict", verdict_cell),
                       ("speed at the end (m/s)", lambda s: fmt(s["values"].get("final_speed"))),
                       ("sag since rest (m)", lambda s: fmt(s["values"].get("max_sag"))),
                       ("drift since rest (m)", lambda s: fmt(s["values"].get("max_drift"))),
                       ("penetration (m)", lambda s: fmt(s["values"].get("max_penetration")))] + TIMING_COLUMNS

    # ---- barrels (beyond the paper: ODE's curved shapes)
    out.extend(scene_section(
        runs, results, "barrels", "Barrels: cylinders and capsules (beyond the paper)",
        "ODE's curved geoms at rest: a crate (dBox), three standing barrels (dCylinder; two on the ground, one on "
        "the crate), a lying barrel, a wheel on its tread and four lying capsules (dCapsule; three on the ground, "
        "one on the crate). ODE 0.16 gives one point for most of these pairs (docs/ode.md, \"Cylinders, capsules "
        "and spheres\"); gdcontact the cap's disc, the side's segment, the capsule's two ends. Contact tracking "
        "sees each curved part as its tessellation. The check: everything still, nothing sunk or slid more than "
        "1 mm since rest.",
        RESTING_COLUMNS))

    # ---- terrain (beyond the paper: a triangle mesh under boxes, hulls and curved shapes)
    out.extend(scene_section(
        runs, results, "terrain", "Terrain: a triangle mesh (beyond the paper)",
        "A dCreateTriMesh ground of 24 × 24 cells of 0.25 m (1152 triangles): a flat plateau with two smooth "
        "bumps and a 4° slope. On it four boxes (dBox; two on the plateau, two on the slope), four rocks (random "
        "hulls, dConvex; one at a bump's foot), a standing and a lying barrel (dCylinder), a lying capsule "
        "(dCapsule) and a wheel on its tread on the slope. gdcontact collides every body with the mesh; ODE's "
        "own trimesh colliders do under ODE native, and under contact tracking too (MPR needs two convex "
        "shapes: that run is ODE's). The check: everything still, nothing sunk or slid more than 1 mm since "
        "rest.",
        RESTING_COLUMNS))

    # ---- details
    out.append("## Details: every measure of every run\n")
    for scene in SCENES + EXTRA_SCENES:
        if any(key[0] == scene for key in runs):
            out.append(f"### {SCENE_TITLE[scene]}\n")
            out.append(full_measures_table(runs, scene) + "\n")
    wall = [(m, b) for b in ("convex", "box") for m in METHODS if ("brick_wall", m, b) in runs]
    if wall:
        out.append("Brick wall: maximum displacement of the remaining bricks (mm) just before the next removal:\n")
        rows = []
        for method, boxes in wall:
            values = runs[("brick_wall", method, boxes)][0]["values"]
            rows.append([METHOD_LABEL[method], BOXES_LABEL[boxes]]
                        + [fmt(1e3 * values[f"after_removal_{k}"]) if f"after_removal_{k}" in values else "–"
                           for k in range(1, 11)])
        out.extend(table_lines(["method", "bricks"] + [str(k) for k in range(1, 11)], rows))
        out.append("")

    # ---- solver warnings
    warnings = []
    for name in sorted(os.listdir(results)):
        if name.endswith(".stderr"):
            with open(os.path.join(results, name)) as f:
                lines = [line.strip() for line in f if line.strip()]
            if lines:
                warnings.append(f"- `{name[:-7]}`: {len(lines)} line(s), e.g. `{lines[0]}`")
    if warnings:
        out.append("## Messages from ODE during the runs\n")
        out.extend(warnings)
        out.append("")

    # ---- other demos
    for name, title in (("ode_stack.txt", "The 10-high cube stack (samples/ode_stack)"),
                        ("manifold_demo.txt", "Manifolds of canonical pairs (samples/manifold_demo)")):
        path = os.path.join(results, name)
        if os.path.exists(path):
            with open(path) as f:
                out.append(f"## {title}\n\n```\n{f.read().rstrip()}\n```\n")

    with open(os.path.join(results, "report.md"), "w") as f:
        f.write("\n".join(out))

