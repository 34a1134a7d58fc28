"""Turns the solver benchmark over seeds (bench_solver_seeds, issue 22) into a report section and a plot.

Input, in RESULTS_DIR: solver_seeds_summary.csv (one row per scene x stepper x contender),
solver_seeds_scenes.csv, solver_seeds_limits.csv and solver_seeds_command.txt, as
bench_solver_seeds --out RESULTS_DIR writes them. Output: the Markdown section "Solver over seeds"
(appended to --append FILE, or written to --markdown FILE) and RESULTS_DIR/solver_seeds.png, the
stability of each contender against its whole-step cost on identical states, one panel per scene.
Plots use matplotlib (Debian's python3-matplotlib), drawn as scenes.py draws; numbers, tables,
statistics, files and plots come from the rest of this package, shared with the other reports.

Usage: python3 -m gdcreport solver-seeds RESULTS_DIR [--append REPORT_MD] [--markdown OUT_MD] [--docs DOCS_DIR]
                                         [--plot-link PATH] [--heading-level N]
"""
import argparse
import math
import os
import shutil

from gdcreport import data, plots, stats
from gdcreport.numbers import fmt, number
from gdcreport.plots import plt
from gdcreport.steppers import STEPPER_LABEL, STEPPER_ORDER, stepper_label, steppers_in
from gdcreport.tables import table_lines

STEPPER_MARKER = {"quick10": "v", "quick20": "o", "quick50": "^", "world": "s"}
CONTENDER_LABEL = {"gdc": "gdcontact", "ode-box": "ODE dBox", "ode-convex": "ODE dConvex"}
BASE_COLOURS = {"gdc": "tab:blue", "ode-box": "tab:green", "ode-convex": "tab:red"}
VARIANT_COLOURS = ["tab:purple", "tab:orange", "tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray"]


def contender_order(name):
    base = ["gdc", "ode-box", "ode-convex"]
    return (base.index(name) if name in base else len(base), name)


def contender_label(name):
    return CONTENDER_LABEL.get(name, name.replace("gdc:", "gdcontact "))


def colours_for(contenders):
    colours, variants = {}, 0
    for name in contenders:
        if name in BASE_COLOURS:
            colours[name] = BASE_COLOURS[name]
        else:
            colours[name] = VARIANT_COLOURS[variants % len(VARIANT_COLOURS)]
            variants += 1
    return colours


def plot(rows, scenes, results):
    """One panel per scene: fraction of seeds standing (y) against the whole step on identical states
    (x, log). Colour = contender (and settings variant), marker = stepper: a legend instead of
    labels, so nothing overlaps however close the points lie."""
    contenders = sorted({r["contender"] for r in rows}, key=contender_order)
    colours = colours_for(contenders)
    names = [s["scene"] for s in scenes]
    columns = 4
    lines = max(1, math.ceil(len(names) / columns))
    figure, axes = plt.subplots(lines, columns, figsize=(4.2 * columns, 3.3 * lines + 1.2), squeeze=False)
    # (the figure's height: 3.3 in per line of panels, 1.2 in for the title and the legend)
    for index, scene in enumerate(names):
        ax = axes[index // columns][index % columns]
        for r in rows:
            if r["scene"] != scene:
                continue
            cost = number(r["cost_whole_ms"])
            if math.isnan(cost):
                continue
            standing = 1.0 - number(r["fail_fraction"])
            low, high = 1.0 - number(r["fail_high95"]), 1.0 - number(r["fail_low95"])
            # gdcontact's marker is larger and drawn first, so that a contender on the same spot shows on top of it
            # (as scenes.py draws coinciding lines).
            big = r["contender"] == "gdc"
            ax.errorbar([cost], [standing], yerr=[[standing - low], [high - standing]], fmt=STEPPER_MARKER.get(r["stepper"].partition("/")[0], "o"),
                        color=colours[r["contender"]], markersize=10 if big else 6, capsize=2, elinewidth=0.8, alpha=0.85,
                        markeredgecolor="black", markeredgewidth=0.5, zorder=2 if big else 3)
            if r.get("collapse_fraction"):  # the gross criterion: seeds not collapsed, a hollow marker of the same colour
                ax.plot([cost], [1.0 - number(r["collapse_fraction"])], STEPPER_MARKER.get(r["stepper"].partition("/")[0], "o"),
                        markerfacecolor="none", markeredgecolor=colours[r["contender"]], markersize=12 if big else 8, zorder=4)
        ax.set_xscale("log")
        # Ticks at 1, 2 and 5 of each decade, labelled plainly; no labels on the minor ticks (they overlapped).
        plots.plain_log_ticks(ax.xaxis)
        ax.set_ylim(-0.05, 1.05)
        ax.set_title(scene, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        if index % columns == 0:
            ax.set_ylabel("seeds standing")
        if index // columns == lines - 1:
            ax.set_xlabel("whole step on identical states, ms")
    for index in range(len(names), lines * columns):
        axes[index // columns][index % columns].axis("off")
    handles = [plt.Line2D([], [], color=colours[c], marker="o", linestyle="", markersize=8, label=contender_label(c))
               for c in contenders]
    handles += [plt.Line2D([], [], color="black", marker=STEPPER_MARKER[s], linestyle="", markersize=7, markerfacecolor="white",
                           label=STEPPER_LABEL[s]) for s in STEPPER_ORDER if any(r["stepper"] == s for r in rows)]
    figure.legend(handles=handles, loc="lower center", ncol=min(len(handles), 7), frameon=False, fontsize=9)
    figure.suptitle("Stability over seeds against the cost of a step (filled: within the fine limits, bars: 95 % Wilson "
                    "interval; hollow: not collapsed)", fontsize=11)
    height = 3.3 * lines + 1.2
    figure.tight_layout(rect=(0, 0.75 / height, 1, 1 - 0.45 / height))  # room for the legend and the title
    return plots.save_figure(figure, os.path.join(results, "solver_seeds.png"), dpi=100, tight=False)


def sleep_lines(results, scenes):
    """Sleeping, paired by seed: per scene and stepper where bodies fell asleep, when every body of a
    gdcontact run slept against the same seed's dBox run (never = later than any time), with a
    two-sided sign test over the seeds that differ."""
    runs_path = os.path.join(results, "solver_seeds_runs.csv")
    if not os.path.exists(runs_path):
        return []
    times = {}
    for r in data.read_csv(runs_path):
        t = float(r["sleep_time"])
        times[(r["scene"], r["stepper"], r["contender"], r["seed"])] = t if t >= 0 else math.inf
    lines = []
    for sc in scenes:
        for stepper in steppers_in({"stepper": k[1]} for k in times):
            seeds = [k[3] for k in times if k[:3] == (sc["scene"], stepper, "gdc") and (sc["scene"], stepper, "ode-box", k[3]) in times]
            if not seeds:
                continue
            g = [times[(sc["scene"], stepper, "gdc", s)] for s in seeds]
            b = [times[(sc["scene"], stepper, "ode-box", s)] for s in seeds]
            if all(math.isinf(x) for x in g + b):
                continue
            later = sum(x > y for x, y in zip(g, b))
            sooner = sum(x < y for x, y in zip(g, b))
            n = later + sooner
            p = stats.sign_test(later, sooner)

            def median(values):
                m = stats.median(values)
                return "never" if math.isinf(m) else fmt(m, 2)
            lines.append([sc["scene"], stepper_label(stepper), str(len(seeds)),
                          f"{sum(not math.isinf(x) for x in g)} / {sum(not math.isinf(x) for x in b)}",
                          f"{median(g)} / {median(b)}", f"{later} / {sooner} / {len(seeds) - n}", fmt(p, 2)])
    if not lines:
        return []
    out = ["Sleeping (issue 22: bodies asleep no later than with dBox), paired by seed: the seeds where every body "
           "slept within the run (gdcontact / dBox), the median time until they did (a run where they never did "
           "counts as later than any), the seeds where gdcontact slept later / sooner / at the same step as "
           "dBox, and the two-sided sign test's p over the seeds that differ (p < 0.05: a difference beyond "
           "seed noise). Scenes and steppers where neither contender's bodies all slept in any seed are left "
           "out.\n"]
    out.extend(table_lines(["scene", "stepper", "seeds", "all asleep", "median s", "later / sooner / same", "sign test p"], lines))
    out.append("")
    return out


def section(results, plot_link, level, reproduce=None):
    h = "#" * level
    rows = data.read_csv(os.path.join(results, "solver_seeds_summary.csv"))
    scenes = data.read_csv(os.path.join(results, "solver_seeds_scenes.csv"))
    limits = data.read_csv(os.path.join(results, "solver_seeds_limits.csv"))
    with open(os.path.join(results, "solver_seeds_command.txt")) as f:
        command = f.read().strip().splitlines()
    out = [f"{h} Solver over seeds\n"]
    out.append("Each scene runs under `dWorldQuickStep` (10, 20, 50 iterations) and `dWorldStep` over many seeds: "
               "`dRandSetSeed(seed)` and a seeded jitter of every body's start pose (±1 mm horizontally, ±0.01 rad "
               "about the vertical, ±0.002 rad about x and y; the same for every contender of a seed). dt 0.01 s, "
               "ERP 0.2, CFM 1e-10 (ODE's double default), friction 0.6 (`dContactApprox1`), 16 contacts asked per "
               "geom pair; ODE's auto-disable on with its default thresholds. Contenders: **gdcontact** "
               "(`gdc::ode::collide` in the near callback, boxes as dBox geoms; the pairs `gdc::ode::handles` refuses "
               "go to `dCollide`), **ODE dBox** (ODE's own colliders, boxes as dBox; in the curved scenes — "
               "dCylinder and dCapsule geoms — ODE's own colliders on the same geoms, its own answer for them; "
               "ODE dConvex is not run there), **ODE dConvex** (ODE's own colliders, every shape a dConvex: libccd's one-point "
               "collider), and gdcontact settings variants (`gdc:NAME=VALUE`).\n")
    out.append(f"Command: `{command[0]}` — {command[1] if len(command) > 1 else ''}"
               + (f". Reproduce: `{reproduce}`." if reproduce else "") + "\n")
    out.append("Failure limits (one table, `failureLimits()` in bench/solver_seeds/solver_seeds.cpp); a run fails when "
               "a limit is crossed and still crossed at the end of the run, or at once when it explodes:\n")
    out.extend(table_lines(["failure", "scenes", "rule", "kind"],
                           [[l["failure"], l["scenes"], l["rule"], l.get("kind", "fine")] for l in limits]))
    out.append("\nKind *fine*: the failure limits; *collapse*: the gross criterion beside them (the structure fell), "
               "so that scenes where every contender crosses the fine limits still tell contenders apart.\n")
    out.append("")
    out.append("Scenes (simulated seconds per run; seeds per stepper; where `dWorldStep` is not run, why):\n")
    out.extend(table_lines(["scene", "what", "s", "seeds (QuickStep)", "seeds (dWorldStep)"],
                           [[s["scene"], s["description"], fmt(number(s["seconds"])), s["seeds"],
                             s["world_seeds"] if s["world_step"] == "1" else f"not run: {s['world_skip_reason']}"]
                            for s in scenes]))
    out.append("")
    out.append("Columns: *fail* = fraction of seeds failing [95 % Wilson interval] and why; *drift* = the largest "
               "horizontal distance of a body from its start at the end, median / 90th percentile / max over seeds "
               "(m); *contacts* per step; *coll.*, *solver* = ms per step of the free runs (mean; noisy, the machine "
               "is shared); *asleep* = median time until every body slept (s) and the fraction of seeds where they "
               "did; *msgs* = ODE messages (LCP internal errors); *identical states* = one step from the same body "
               "states (a reference run's states sampled at several times, copied into every contender's world), "
               "collision + solver ms (fastest of the repetitions, each after one untimed step of the same contender "
               "from the same state), and the whole step ÷ the best ODE option "
               "(the ODE contender failing the fewest seeds, the cheaper on a tie; where it fails more than half, "
               "the cheapest).\n")
    out.append("How to run: `scripts/run` runs the default mode (a few minutes on 2 cores: fewer seeds where a run "
               "costs seconds — the wall 50, the 1000-box pile 4, the 20-stack and the pyramid under dWorldStep 20 and 12) and appends this section to results/report.md; `scripts/solver_seeds` "
               "runs the full mode (50 seeds of everything) and writes it here; `scripts/solver_seeds --quick` the default "
               "mode. Flags of `bench_solver_seeds` pass through: `--scene NAME`, `--stepper quick10|quick20|quick50|world`, "
               "`--contender gdc:maxContacts=4` (any field of gdc::Settings by name, several as `gdc:a=1,b=2`), "
               "`--seeds N`, `--seeds-for SCENE[:STEPPER]=N`, `--no-sleep`, `--jobs N` (worker processes: ODE's random "
               "generator, which QuickStep's row shuffle draws from, is process-wide).\n")
    # The overview a user chooses from: each contender's fail fraction and whole step ÷ best ODE option.
    contenders = sorted({r["contender"] for r in rows}, key=contender_order)
    index = {(r["scene"], r["stepper"], r["contender"]): r for r in rows}
    # Paired seeds (the same seed is the same start for every contender): where gdcontact and dBox disagree.
    paired = {}
    runs_path = os.path.join(results, "solver_seeds_runs.csv")
    if os.path.exists(runs_path):
        runs = data.read_csv(runs_path)
        failed = {(r["scene"], r["stepper"], r["contender"], r["seed"]): r["failed"] == "1" for r in runs}
        collapsed = {(r["scene"], r["stepper"], r["contender"], r["seed"]): r.get("collapsed") == "1" for r in runs}
        for (scene, stepper, contender, seed), gdc_failed in failed.items():
            if contender != "gdc" or (scene, stepper, "ode-box", seed) not in failed:
                continue
            box_failed = failed[(scene, stepper, "ode-box", seed)]
            gdc_fell, box_fell = collapsed[(scene, stepper, "gdc", seed)], collapsed[(scene, stepper, "ode-box", seed)]
            counts = paired.setdefault((scene, stepper), [0, 0, 0, 0])
            counts[0] += gdc_failed and not box_failed
            counts[1] += box_failed and not gdc_failed
            counts[2] += gdc_fell and not box_fell
            counts[3] += box_fell and not gdc_fell
    out.append("Overview — per scene and stepper, each contender's **fraction of seeds failing · collapsed** (the fine "
               "limits · the gross criterion) and, in brackets, its "
               "**whole step on identical states ÷ the best ODE option** (named in the next column); the last two columns "
               "pair the seeds of gdcontact and ODE dBox: seeds where gdcontact fails and dBox stands / where dBox "
               "fails and gdcontact stands, and the same for collapses, each with the two-sided sign test's p:\n")
    overview = []
    for sc in scenes:
        for stepper in steppers_in(rows):
            present = [index.get((sc["scene"], stepper, c)) for c in contenders]
            if not any(present):
                continue
            cells, best = [], ""
            for r in present:
                if r is None:
                    cells.append("–")
                    continue
                ratio = number(r["ratio_to_best_ode"])
                fell = f" · {fmt(number(r['collapse_fraction']), 2)}" if r.get("collapse_fraction") else ""
                cells.append(f"{fmt(number(r['fail_fraction']), 2)}{fell}" + (f" ({fmt(ratio, 2)}×)" if not math.isnan(ratio) else ""))
                best = best or contender_label(r["best_ode"]) if r["best_ode"] else best
            pair = paired.get((sc["scene"], stepper))
            overview.append([sc["scene"], stepper_label(stepper)] + cells + [best]
                            + ([f"{pair[0]} / {pair[1]} (p {fmt(stats.sign_test(pair[0], pair[1]), 2)})",
                                f"{pair[2]} / {pair[3]} (p {fmt(stats.sign_test(pair[2], pair[3]), 2)})"] if pair else ["–", "–"]))
    out.extend(table_lines(["scene", "stepper"] + [contender_label(c) for c in contenders]
                           + ["best ODE option", "gdc-only / dBox-only failures", "gdc-only / dBox-only collapses"], overview))
    out.append("")
    out.extend(sleep_lines(results, scenes))
    out.append("How to read the 20-stack and the timings: docs/benchmarks.md, after this section.\n")
    if plot_link:
        out.append(f"![stability against cost per scene]({plot_link})\n")
    by_scene = {}
    for r in rows:
        by_scene.setdefault(r["scene"], []).append(r)
    for s in scenes:
        name = s["scene"]
        if name not in by_scene:
            continue
        out.append(f"{h}# {name}: {s['description']}\n")
        table_rows = []
        order = steppers_in(rows)
        scene_rows = sorted(by_scene[name], key=lambda r: (order.index(r["stepper"]), contender_order(r["contender"])))
        for r in scene_rows:
            fail = (f"{fmt(number(r['fail_fraction']), 2)} [{fmt(number(r['fail_low95']), 2)}, {fmt(number(r['fail_high95']), 2)}]"
                    f" of {r['seeds']}" + (f" ({r['failures']})" if r["failures"] else ""))
            drift = f"{fmt(number(r['drift_p50']), 2)} / {fmt(number(r['drift_p90']), 2)} / {fmt(number(r['drift_max']), 2)}"
            asleep = f"{fmt(number(r['sleep_p50']), 2)} ({fmt(number(r['slept_fraction']), 2)})"
            msgs = f"{r['messages']} ({r['lcp_errors']})" if r["messages"] != "0" else "0"
            cost = number(r["cost_whole_ms"])
            identical = "–" if math.isnan(cost) else (f"{fmt(number(r['cost_collision_ms']), 2)} + "
                                                       f"{fmt(number(r['cost_solver_ms']), 2)} = {fmt(cost, 3)}")
            ratio = number(r["ratio_to_best_ode"])
            best = f"{fmt(ratio, 2)}× {r['best_ode']}" if not math.isnan(ratio) else "–"
            fell = (f"{fmt(number(r['collapse_fraction']), 2)} [{fmt(number(r['collapse_low95']), 2)}, {fmt(number(r['collapse_high95']), 2)}]"
                    if r.get("collapsed") else "–")
            table_rows.append([stepper_label(r["stepper"]), contender_label(r["contender"]), fail, fell, drift,
                               fmt(number(r["contacts_per_step"]), 3), fmt(number(r["collision_ms"]), 2),
                               fmt(number(r["solver_ms"]), 2), asleep, msgs, identical, best])
        out.extend(table_lines(["stepper", "contender", "fail", "collapsed", "drift p50 / p90 / max", "contacts", "coll. ms",
                                "solver ms", "asleep", "msgs", "identical states: coll. + solver ms", "÷ best ODE"],
                               table_rows))
        out.append("")
    return "\n".join(out) + "\n", rows, scenes


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--append", help="report to append the section to (e.g. results/report.md)")
    parser.add_argument("--markdown", help="write the section to this file")
    parser.add_argument("--plot-link", default="solver_seeds.png", help="how the section links the plot")
    parser.add_argument("--heading-level", type=int, default=2)
    parser.add_argument("--reproduce", help="the repository command that made these results, for the section")
    parser.add_argument("--docs", help="docs directory: write the section into DOCS/benchmarks.md (between its "
                        "markers) and the plot to DOCS/images/bench_solver_seeds.png")
    args = parser.parse_args(argv)
    if args.docs:
        args.plot_link = "images/bench_solver_seeds.png"
    text, rows, scenes = section(args.results, args.plot_link, args.heading_level, args.reproduce)
    path = plot(rows, scenes, args.results)
    if args.docs:
        os.makedirs(os.path.join(args.docs, "images"), exist_ok=True)
        shutil.copyfile(path, os.path.join(args.docs, "images", "bench_solver_seeds.png"))
        doc = os.path.join(args.docs, "benchmarks.md")
        # Between its two marker lines of docs/benchmarks.md, replaced or appended (as big.py places the
        # Big worlds section; bench.py keeps both).
        spliced = data.splice(doc, *data.SOLVER_SEEDS, text)
        with open(doc, "w") as f:
            f.write(spliced)
    if args.append:
        with open(args.append, "a") as f:
            f.write("\n" + text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)
    if not args.append and not args.markdown and not args.docs:
        print(text)

