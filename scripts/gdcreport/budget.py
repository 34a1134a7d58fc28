"""The contact budget (Settings::maxContacts) against the default and ODE's options, from the solver
benchmark over seeds: the tables of docs/algorithm.md ("The budget over every scene").

Input: one or more RESULTS_DIRs written by bench_solver_seeds --out (solver_seeds_runs.csv and
solver_seeds_summary.csv), each run with the contenders gdc, ode-box, ode-convex and the budget
variants (--contender gdc:maxContacts=N). Output (stdout, Markdown), per scene and stepper:
- each contender's failed seeds of n with the Wilson 95 % interval, contacts per step and the whole
  step (collision + solver) on identical states divided by the best ODE option's and by the
  baseline's (--baseline);
- per budget variant, paired by seed against the baseline (--baseline, default gdc) and against the best ODE option: seeds
  where the variant fails and the other stands / where the other fails and the variant stands, and
  the two-sided sign (McNemar exact) test's p over those discordant seeds.

With --costs COST_DIR (a run of the same contenders with few seeds and more cost states and
repetitions, e.g. --seeds 1 --cost-states 16 --cost-repetitions 7), the whole-step ratios come from
that run's identical states instead (the best ODE option is still the one of RESULTS_DIRs' seeds).

Usage: python3 -m gdcreport budget RESULTS_DIR... [--contenders gdc,gdc:maxContacts=6,...]
                                    [--costs COST_DIR] [--baseline CONTENDER]
"""
import argparse
import math
import os
from collections import defaultdict

from gdcreport.data import read_csv
from gdcreport.stats import median, sign_test, wilson

STEPPERS = ["quick10", "quick20", "quick50", "world"]
STEPPER_LABEL = {"quick10": "QuickStep 10", "quick20": "QuickStep 20", "quick50": "QuickStep 50", "world": "dWorldStep"}


def load(dirs):
    runs = defaultdict(dict)     # (scene, stepper, contender) -> seed -> failed
    contacts = defaultdict(dict)  # (scene, stepper, contender) -> seed -> contacts per step
    sleep = defaultdict(dict)    # (scene, stepper, contender) -> seed -> seconds until all asleep (inf: never)
    drift = defaultdict(dict)
    summary = {}
    for d in dirs:
        for r in read_csv(os.path.join(d, "solver_seeds_runs.csv")):
            key = (r["scene"], r["stepper"], r["contender"])
            runs[key][int(r["seed"])] = r["failed"] == "1"
            contacts[key][int(r["seed"])] = float(r["contacts_per_step"])
            t = float(r["sleep_time"])
            sleep[key][int(r["seed"])] = t if t >= 0 else math.inf
            drift[key][int(r["seed"])] = float(r["drift"])
        for r in read_csv(os.path.join(d, "solver_seeds_summary.csv")):
            summary[(r["scene"], r["stepper"], r["contender"])] = r
    return runs, contacts, summary, sleep, drift


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--contenders", default="gdc,gdc:maxContacts=6,gdc:maxContacts=5,ode-box,ode-convex")
    parser.add_argument("--costs", help="a run whose identical-state costs replace RESULTS_DIRs'")
    parser.add_argument("--baseline", default="gdc",
                        help="the contender the variants are paired with and divided by (the budget in use)")
    args = parser.parse_args(argv)
    order = args.contenders.split(",")
    runs, contacts, summary, sleep, drift = load(args.dirs)
    whole_ms = {key: float(r["cost_whole_ms"]) for key, r in summary.items() if r["cost_whole_ms"]}
    if args.costs:
        whole_ms = {(r["scene"], r["stepper"], r["contender"]): float(r["cost_whole_ms"])
                    for r in read_csv(os.path.join(args.costs, "solver_seeds_summary.csv")) if r["cost_whole_ms"]}
    scenes = []
    for (scene, _, _) in runs:
        if scene not in scenes:
            scenes.append(scene)
    base = args.baseline
    variants = [c for c in order if c.startswith("gdc") and c != base]

    print("Cells: failed of n [Wilson 95 %] · contacts per step · whole step on identical states "
          f"÷ best ODE option (÷ {base}'s).\n")
    header = "| scene | stepper | best ODE | " + " | ".join(f"`{c}`" for c in order) + " |"
    print(header)
    print("|" + "---|" * (3 + len(order)))
    paired = []
    for scene in scenes:
        for stepper in STEPPERS:
            present = [c for c in order if (scene, stepper, c) in runs]
            if not present:
                continue
            best = next((summary[(scene, stepper, c)]["best_ode"] for c in present
                         if summary.get((scene, stepper, c), {}).get("best_ode")), "")
            default_whole = whole_ms.get((scene, stepper, base), math.nan)
            best_whole = whole_ms.get((scene, stepper, best), math.nan)
            cells = []
            for c in order:
                if (scene, stepper, c) not in runs:
                    cells.append("–")
                    continue
                seeds = runs[(scene, stepper, c)]
                n, k = len(seeds), sum(seeds.values())
                low, high = wilson(k, n)
                s = summary[(scene, stepper, c)]
                per_step = sum(contacts[(scene, stepper, c)].values()) / n
                whole = whole_ms.get((scene, stepper, c), math.nan)
                cell = f"{k}/{n} [{low * 100:.0f}–{high * 100:.0f} %] · {per_step:.1f}"
                if whole == whole and best_whole == best_whole:
                    cell += f" · {whole / best_whole:.2f}×"
                    if c in variants and default_whole == default_whole:
                        cell += f" ({whole / default_whole:.2f}×)"
                cells.append(cell)
            print(f"| {scene} | {STEPPER_LABEL[stepper]} | {best} | " + " | ".join(cells) + " |")
            for v in variants:
                if (scene, stepper, v) not in runs:
                    continue
                for other in [base, best]:
                    if not other or (scene, stepper, other) not in runs:
                        continue
                    a_runs, b_runs = runs[(scene, stepper, v)], runs[(scene, stepper, other)]
                    common = sorted(set(a_runs) & set(b_runs))
                    only_v = sum(a_runs[s] and not b_runs[s] for s in common)
                    only_o = sum(b_runs[s] and not a_runs[s] for s in common)
                    paired.append((scene, stepper, v, other, len(common), only_v, only_o, sign_test(only_v, only_o)))

    print("\nPaired by seed: seeds where the budget variant fails and the other stands / where the other "
          "fails and the variant stands, and the exact two-sided sign test's p over those seeds "
          "(p < 0.05: beyond seed noise). Rows with no discordant seed are left out.\n")
    print("| scene | stepper | variant | against | seeds | variant only | other only | p |")
    print("|---|---|---|---|---|---|---|---|")
    for scene, stepper, v, other, n, a, b, p in paired:
        if a or b:
            print(f"| {scene} | {STEPPER_LABEL[stepper]} | `{v}` | `{other}` | {n} | {a} | {b} | {p:.2g} |")
    sleep_and_drift(runs, sleep, drift, order, variants, base)


def sleep_and_drift(runs, sleep, drift, order, variants, base):
    print("\nDrift (the largest horizontal distance of a body from its start at the end, median over seeds, mm) "
          "and sleep (seeds where every body slept / n; for each budget variant against the default, paired "
          "by seed: slept later / sooner, a run that never slept counting as later than any, and the sign "
          "test's p). Scene and stepper rows where no contender's bodies all slept show drift only.\n")
    print("| scene | stepper | " + " | ".join(f"`{c}` drift · slept" for c in order) +
          " | " + " | ".join(f"`{v}` later / sooner (p)" for v in variants) + " |")
    print("|" + "---|" * (2 + len(order) + len(variants)))
    keys = []
    for (scene, stepper, _) in runs:
        if (scene, stepper) not in keys:
            keys.append((scene, stepper))
    scenes = list(dict.fromkeys(scene for scene, _ in keys))
    keys.sort(key=lambda k: (scenes.index(k[0]), STEPPERS.index(k[1])))
    for scene, stepper in keys:
        cells = []
        for c in order:
            key = (scene, stepper, c)
            if key not in runs:
                cells.append("–")
                continue
            slept = sum(t < math.inf for t in sleep[key].values())
            cells.append(f"{median(drift[key].values()) * 1000:.3g} · {slept}/{len(sleep[key])}")
        pairs = []
        for v in variants:
            a, b = sleep.get((scene, stepper, v)), sleep.get((scene, stepper, base))
            if not a or not b:
                pairs.append("–")
                continue
            common = sorted(set(a) & set(b))
            later = sum(a[s] > b[s] for s in common)
            sooner = sum(a[s] < b[s] for s in common)
            pairs.append(f"{later} / {sooner} ({sign_test(later, sooner):.2g})" if later + sooner else "same")
        print(f"| {scene} | {STEPPER_LABEL[stepper]} | " + " | ".join(cells) + " | " + " | ".join(pairs) + " |")

