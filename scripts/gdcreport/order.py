"""A contact order (Settings::contactOrder) against the default and ODE's options, from the solver
benchmark over seeds: the tables of docs/benchmarks.md, "Columns and heaps (issue 35)".

Input: one or more RESULTS_DIRs written by bench_solver_seeds --out (solver_seeds_runs.csv), run
with the baseline (--baseline, default gdc), the order under test (--rule) and ODE's options
(ode-box, ode-convex, whichever ran). Output (stdout, Markdown), per scene and stepper:
- each contender's collapsed · failed seeds of n (the gross criterion · the fine limits) and the
  ODE messages, if any;
- the rule paired by seed against the baseline and against the best ODE option (per criterion, the
  ODE contender with the fewest of it): seeds where the rule collapses (fails) and the other
  stands / where the other does and the rule stands, with the exact two-sided sign test's p;
- a verdict: "worse" where the rule collapses or fails more seeds than the other and p < 0.05 on
  that criterion, the other named; "more" where it has more but within seed noise.

Usage: python3 -m gdcreport order RESULTS_DIR... [--rule CONTENDER] [--baseline CONTENDER] [--differing] [--drift]
"""
import argparse
import os
import statistics
from collections import defaultdict

from gdcreport.data import read_csv
from gdcreport.steppers import stepper_label, steppers_in
from gdcreport.stats import paired_by_seed, sign_test

ODE = ["ode-box", "ode-convex"]


def load(dirs):
    runs = defaultdict(dict)  # (scene, stepper, contender) -> seed -> (collapsed, failed, messages)
    scenes = []
    for d in dirs:
        # The benchmark's scene order (its runs file follows the workers' order).
        scenes_path = os.path.join(d, "solver_seeds_scenes.csv")
        if os.path.exists(scenes_path):
            scenes.extend(r["scene"] for r in read_csv(scenes_path) if r["scene"] not in scenes)
        for r in read_csv(os.path.join(d, "solver_seeds_runs.csv")):
            if r["scene"] not in scenes:
                scenes.append(r["scene"])
            runs[(r["scene"], r["stepper"], r["contender"])][int(r["seed"])] = (
                r.get("collapsed") == "1", r["failed"] == "1", int(r["messages"]), float(r["drift"]))
    return runs, scenes


def paired(a, b, criterion):
    """(a only, b only, p) over the seeds both ran; criterion 0: collapsed, 1: failed."""
    return paired_by_seed(a, b, lambda result: result[criterion])


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--rule", default="gdc:contactOrder=DeepestFirstWhenLoaded")
    parser.add_argument("--baseline", default="gdc")
    parser.add_argument("--drift", action="store_true",
                        help="also the drift table: mean and median drift per contender, the rule paired with each")
    parser.add_argument("--differing", action="store_true",
                        help="only the rows where the contenders' counts differ (the others listed after the table)")
    args = parser.parse_args(argv)
    runs, scenes = load(args.dirs)
    rule, base = args.rule, args.baseline
    contenders = [base, rule] + ODE
    print("Cells: collapsed · failed seeds of n (+ ODE messages). Paired by seed, collapsed then failed: "
          "seeds where the rule does and the other does not / the other way round (sign test's p). "
          "Verdict: *worse than X* where the rule has more with p < 0.05, *more than X* where more "
          "within seed noise.\n")
    print(f"| scene | stepper | `{base}` | `{rule}` | ode-box | ode-convex | rule vs `{base}` | rule vs best ODE | verdict |")
    print("|---|---|---|---|---|---|---|---|---|")
    keys = {(scene, stepper) for (scene, stepper, _) in runs}
    same = []
    for scene in scenes:
        stepper_rows = [{"stepper": st} for (sc, st) in keys if sc == scene]
        for stepper in steppers_in(stepper_rows):
            if (scene, stepper, rule) not in runs:
                continue
            cells, counts = [], set()
            for c in contenders:
                seeds = runs.get((scene, stepper, c))
                if not seeds:
                    cells.append("–")
                    continue
                fell = sum(v[0] for v in seeds.values())
                failed = sum(v[1] for v in seeds.values())
                messages = sum(v[2] for v in seeds.values())
                counts.add((fell, failed, len(seeds)))
                cells.append(f"{fell} · {failed} of {len(seeds)}" + (f" (+{messages} msgs)" if messages else ""))
            if args.differing and len(counts) == 1 and not any("msgs" in cell for cell in cells):
                same.append(f"{scene} {stepper_label(stepper)}: {cells[0]}")
                continue
            mine = runs[(scene, stepper, rule)]
            verdict = []

            def against(other, name):
                parts = []
                for criterion, word in ((0, "collapsed"), (1, "failed")):
                    a, b, p = paired(mine, runs[(scene, stepper, other)], criterion)
                    parts.append(f"{a} / {b} ({p:.2g})")
                    if a > b:
                        verdict.append(f"{'worse' if p < 0.05 else 'more'} than {name} ({word})")
                return " · ".join(parts)

            versus_base = against(base, f"`{base}`") if (scene, stepper, base) in runs else "–"
            present = [c for c in ODE if (scene, stepper, c) in runs]
            best_cells = []
            for criterion, word in ((0, "collapsed"), (1, "failed")):
                if not present:
                    break
                best = min(present, key=lambda c: (sum(v[criterion] for v in runs[(scene, stepper, c)].values()),
                                                   ODE.index(c)))
                a, b, p = paired(mine, runs[(scene, stepper, best)], criterion)
                best_cells.append(f"{a} / {b} ({p:.2g}, {best})")
                if a > b:
                    verdict.append(f"{'worse' if p < 0.05 else 'more'} than {best} ({word})")
            print(f"| {scene} | {stepper_label(stepper)} | " + " | ".join(cells) + f" | {versus_base} | "
                  + (" · ".join(best_cells) or "–") + f" | {'; '.join(verdict) or 'holds'} |")
    if same:
        print("\nThe same count for every contender (collapsed · failed): " + "; ".join(same) + ".")
    if args.drift:
        drift_table(runs, scenes, rule, contenders)


def drift_table(runs, scenes, rule, contenders):
    """The drift (the largest horizontal distance of a body from its start at the end, m): mean and
    median per contender, and per other contender the seeds where the rule drifts farther / less
    with the sign test's p."""
    print("\nDrift (m), mean / median over seeds; paired: seeds where the rule drifts farther / less (p).\n")
    others = [c for c in contenders if c != rule]
    print("| scene | stepper | " + " | ".join(f"`{c}`" for c in contenders) + " | "
          + " | ".join(f"rule vs `{c}`" for c in others) + " |")
    print("|" + "---|" * (2 + len(contenders) + len(others)))
    for scene in scenes:
        steppers = steppers_in([{"stepper": st} for (sc, st, c) in runs if sc == scene and c == rule])
        for stepper in steppers:
            cells, pairs = [], []
            for c in contenders:
                seeds = runs.get((scene, stepper, c))
                cells.append(f"{statistics.mean(v[3] for v in seeds.values()):.3g} / "
                             f"{statistics.median(v[3] for v in seeds.values()):.3g}" if seeds else "–")
            mine = runs[(scene, stepper, rule)]
            for c in others:
                theirs = runs.get((scene, stepper, c))
                if not theirs:
                    pairs.append("–")
                    continue
                common = set(mine) & set(theirs)
                farther = sum(mine[s][3] > theirs[s][3] for s in common)
                less = sum(mine[s][3] < theirs[s][3] for s in common)
                pairs.append(f"{farther} / {less} ({sign_test(farther, less):.2g})")
            print(f"| {scene} | {stepper_label(stepper)} | " + " | ".join(cells) + " | " + " | ".join(pairs) + " |")


if __name__ == "__main__":
    main()
