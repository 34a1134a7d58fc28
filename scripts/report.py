#!/usr/bin/env python3
"""Writes results/report.md and its PNG plots from the scene runs of scripts/run.

Input, in the results directory: for every run SCENE_METHOD_BOXES.json (the summary a scene
program writes with --summary) and .csv (its per-step measures, --csv); manifold_demo.txt and
ode_stack.txt when present. Plots use matplotlib (Debian's python3-matplotlib).

Usage: scripts/report.py RESULTS_DIR [--build BUILD_DIR] [--seconds N]
"""
import argparse
import csv
import json
import math
import os
import platform
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ["gdc", "tracking", "ode"]
METHOD_LABEL = {"gdc": "gdcontact", "tracking": "contact tracking", "ode": "ODE 0.16.2 native"}
METHOD_COLOUR = {"gdc": "tab:blue", "tracking": "tab:orange", "ode": "tab:green"}
BOXES_LABEL = {"box": "dBox", "convex": "dConvex"}
# A log-scale plot cannot show 0; values below this are drawn at it (stated under each plot).
LOG_FLOOR = 1e-18


def load_runs(results):
    runs = {}
    for name in sorted(os.listdir(results)):
        if not name.endswith(".json"):
            continue
        with open(os.path.join(results, name)) as f:
            summary = json.load(f)
        key = (summary["scene"], summary["method"], summary["boxes"])
        series = {}
        csv_path = os.path.join(results, name[:-5] + ".csv")
        if os.path.exists(csv_path):
            with open(csv_path) as f:
                reader = csv.DictReader(f)
                for row in reader:
                    for column, text in row.items():
                        series.setdefault(column, []).append(float(text))
        runs[key] = (summary, series)
    return runs


def fmt(value, digits=3):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def floor_for_log(values):
    return [max(v, LOG_FLOOR) if not math.isnan(v) else float("nan") for v in values]


def measures_table(runs, scene):
    rows = [
        "| method | boxes | solver | verdict | penetration max / mean (m) | alignment max / mean (rad) "
        "| drift (m) | twist (rad) | sag (m) | oscillation (m/s) | collision / solver (ms per step) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for (s, method, boxes), (summary, _) in sorted(runs.items(), key=lambda item: (
            item[0][2], METHODS.index(item[0][1]) if item[0][1] in METHODS else 9)):
        if s != scene:
            continue
        solver = f"{summary['stepper']}" + (f" {summary['iterations']} it" if summary["stepper"] == "quick" else "")
        verdict = ("**PASS**" if summary["success"] else "**FAIL**") + ": " + summary["outcome"]
        rows.append(
            f"| {METHOD_LABEL.get(method, method)} | {BOXES_LABEL.get(boxes, boxes)} | {solver}, dt {summary['dt']} "
            f"| {verdict} | {fmt(summary['max_penetration'])} / {fmt(summary['mean_penetration'])} "
            f"| {fmt(summary['max_alignment'])} / {fmt(summary['mean_alignment'])} | {fmt(summary['max_drift'])} "
            f"| {fmt(summary['max_twist'])} | {fmt(summary['max_sag'])} | {fmt(summary['oscillation'])} "
            f"| {fmt(summary['collision_ms'])} / {fmt(summary['solver_ms'])} |")
    return "\n".join(rows)


def ratio(numerator, denominator):
    if denominator <= 0:
        return float("inf") if numerator > 0 else float("nan")
    return numerator / denominator


def save_figure(figure, results, name):
    """Writes the figure to results/name, closes it and returns the file name for the report."""
    figure.tight_layout()
    path = os.path.join(results, name)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return os.path.basename(path)


def plot_box_drop(runs, results):
    figure, axes = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    panels = [("penetration", "penetration error (m)"), ("alignment", "alignment error (rad)"),
              ("speed", "speed |v| + |ω|·r (m/s)")]
    for boxes, style in (("box", "-"), ("convex", ":")):
        for method in METHODS:
            key = ("box_drop", method, boxes)
            if key not in runs:
                continue
            series = runs[key][1]
            for axis, (column, _) in zip(axes, panels):
                axis.semilogy(series["time"], floor_for_log(series[column]), style, color=METHOD_COLOUR[method],
                              linewidth=1.2, label=f"{METHOD_LABEL[method]} ({BOXES_LABEL[boxes]})")
    for axis, (_, label) in zip(axes, panels):
        axis.set_ylabel(label)
        axis.axvline(2.0, color="grey", linewidth=0.8, linestyle="--")
        axis.grid(True, which="major", alpha=0.3)
    axes[0].legend(fontsize=8, ncol=2)
    axes[0].set_title("Box drop (paper Fig. 9): settling after t = 2 s (dashed line)")
    axes[-1].set_xlabel("time (s)")
    return save_figure(figure, results, "box_drop_errors.png")


def plot_wall(runs, results):
    figure, axis = plt.subplots(figsize=(11, 5))
    any_line = False
    for boxes, style in (("convex", "o-"), ("box", "s--")):
        for method in METHODS:
            key = ("brick_wall", method, boxes)
            if key not in runs:
                continue
            summary = runs[key][0]
            values = [summary["values"].get(f"after_removal_{k}") for k in range(1, 11)]
            points = [(k, v) for k, v in zip(range(1, 11), values) if v is not None]
            if not points:
                continue
            axis.semilogy([k for k, _ in points], [max(v, 1e-12) for _, v in points], style,
                          color=METHOD_COLOUR[method], label=f"{METHOD_LABEL[method]} ({BOXES_LABEL[boxes]} bricks)")
            any_line = True
    axis.axhline(0.01, color="red", linewidth=0.8, linestyle=":", label="stands below 1 cm (10 % of a brick's height)")
    axis.set_xlabel("bricks removed")
    axis.set_ylabel("max displacement of the remaining bricks (m)")
    axis.set_title("Brick wall (paper Fig. 7–8): displacement after each removal")
    axis.grid(True, alpha=0.3)
    if any_line:
        axis.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
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
        axes[0].semilogy(time[start:], floor_for_log(series["top_tilt"][start:]), color=METHOD_COLOUR[method],
                         label=METHOD_LABEL[method])
        axes[1].semilogy(time[start:], floor_for_log(series["lean_change"][start:]), color=METHOD_COLOUR[method],
                         label=METHOD_LABEL[method])
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


def plot_composites(runs, results):
    figure, axis = plt.subplots(figsize=(9, 4.5))
    for method in METHODS:
        key = ("composites", method, "box")
        if key not in runs:
            continue
        series = runs[key][1]
        axis.semilogy(series["time"], floor_for_log(series["penetration"]), color=METHOD_COLOUR[method],
                      label=METHOD_LABEL[method])
    axis.set_xlabel("time (s)")
    axis.set_ylabel("deepest overlap of any two parts (m)")
    axis.set_title("Composites (paper Fig. 10): penetration while dropping and stacking")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=8)
    return save_figure(figure, results, "composites_penetration.png")


def command_output(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--build", default="build")
    parser.add_argument("--seconds", type=float, default=None, help="wall time of the runs, for the report")
    arguments = parser.parse_args()
    results = arguments.results
    runs = load_runs(results)
    if not runs:
        sys.exit(f"no scene results (*.json) in {results}")

    out = []
    out.append("# gdcontact: the paper's scenes with ODE — results\n")
    out.append("Generated by `scripts/run` (this file is overwritten by every run). "
               f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.system()} {platform.release()}; "
               f"ODE {command_output(['pkg-config', '--modversion', 'ode'])} (double precision); "
               f"matplotlib {matplotlib.__version__}."
               + (f" The build and runs took {arguments.seconds:.0f} s." if arguments.seconds is not None else "") + "\n")
    out.append("Methods: **gdcontact** (`gdc::ode::collide`, the paper's method), **contact tracking** "
               "(a Bullet-style persistent manifold fed by libccd's MPR, the paper's baseline), **ODE 0.16.2 "
               "native** (`dCollide`: dBoxBox / dBoxPlane for dBox, libccd for dConvex pairs). Measures as "
               "defined in docs/measures.md, over the time after the scene declares its bodies at rest; "
               "penetration is the geometric overlap (separating-axis oracle) of every touching pair, not "
               "what the method reports. Timings are wall-clock means per step on this machine.\n")

    # ---- box drop
    out.append("## Box drop (paper Fig. 9)\n")
    out.append("A 0.5 × 0.4 × 0.3 m box (60 kg) dropped tilted from 1 m onto the plane; dWorldStep, dt 0.01 s, "
               "ERP 0.2, CFM 1e-10 (ODE's defaults). Measures after t = 2 s.\n")
    out.append(measures_table(runs, "box_drop") + "\n")
    for boxes in ("box", "convex"):
        gdc = runs.get(("box_drop", "gdc", boxes))
        tracking = runs.get(("box_drop", "tracking", boxes))
        if gdc and tracking:
            g, t = gdc[0], tracking[0]
            out.append(f"Tracking ÷ gdcontact ({BOXES_LABEL[boxes]}): penetration max "
                       f"{fmt(ratio(t['max_penetration'], g['max_penetration']))}×, mean "
                       f"{fmt(ratio(t['mean_penetration'], g['mean_penetration']))}×; alignment max "
                       f"{fmt(ratio(t['max_alignment'], g['max_alignment']))}×, mean "
                       f"{fmt(ratio(t['mean_alignment'], g['mean_alignment']))}×; oscillation "
                       f"{fmt(ratio(t['oscillation'], g['oscillation']))}×.\n")
    out.append(f"![box drop errors]({plot_box_drop(runs, results)})\n")
    out.append(f"Values below {LOG_FLOOR:g} (exact zeros) are drawn at {LOG_FLOOR:g}. The penetration of a "
               "box resting on four exact contacts is not zero but ODE's constraint compliance, "
               "weight per contact × dt × CFM / ERP.\n")

    # ---- tower
    out.append("## Tower (paper Fig. 5–6)\n")
    out.append("Nine convex objects and two gears are picked up one by one by a scripted builder and stacked; "
               "then the top object is pushed down, 3 cm off its axis (inside every level's support), with the "
               "tower's weight for 2 s (0.5 s ramp), and let go.\n")
    out.append(measures_table(runs, "tower") + "\n")
    out.append(f"![tower tilt]({plot_tower(runs, results)})\n")

    # ---- wall
    out.append("## Brick wall (paper Fig. 7–8)\n")
    out.append("63 bricks in running bond (10 per course, 6 courses, half bricks at the ends of odd courses); "
               "after 2 s of settling, ten bricks that nothing rests on are removed one per second, cutting a "
               "stepped notch. QuickStep (50 iterations): compare with ODE's exact dBoxBox on dBox bricks.\n")
    out.append(measures_table(runs, "brick_wall") + "\n")
    header = "| method | bricks | " + " | ".join(str(k) for k in range(1, 11)) + " |"
    out.append("Maximum displacement of the remaining bricks (mm) just before the next removal:\n")
    out.append(header)
    out.append("|---|---|" + "---|" * 10)
    for boxes in ("convex", "box"):
        for method in METHODS:
            key = ("brick_wall", method, boxes)
            if key not in runs:
                continue
            values = runs[key][0]["values"]
            cells = [fmt(1e3 * values[f"after_removal_{k}"]) if f"after_removal_{k}" in values else "–"
                     for k in range(1, 11)]
            out.append(f"| {METHOD_LABEL[method]} | {BOXES_LABEL[boxes]} | " + " | ".join(cells) + " |")
    out.append("")
    out.append(f"![wall displacement]({plot_wall(runs, results)})\n")

    # ---- composites
    out.append("## Composites (paper Fig. 10)\n")
    out.append("A table, two gears, a cross and an L (each one body of several convex parts) are let go one after "
               "another onto one spot and stack; a dumbbell with octagonal wheels lands beside them. dWorldStep, "
               "four contacts per pair of parts.\n")
    out.append(measures_table(runs, "composites") + "\n")
    out.append(f"![composites penetration]({plot_composites(runs, results)})\n")

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


if __name__ == "__main__":
    main()
