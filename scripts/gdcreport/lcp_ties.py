"""ODE's Dantzig LCP ties over seeds, per contender: the tables of docs/benchmarks.md ("dWorldStep's
LCP ties, in double and single precision") and the figures docs/install.md quotes from them ("Single
precision: 8 points a face").

dWorldStep's Dantzig solver prints "LCP internal error, s <= 0" where a pivot's step comes out
zero — in a resting stack, a contact row that carries no force, left exactly on its bound, then
asked to move — and zeroes the rows after it for that step. bench_solver_seeds counts those
messages per run (solver_seeds_runs.csv, lcp_errors).

Input: one or more RESULTS_DIRs written by bench_solver_seeds --out. Output (stdout, Markdown), per
scene and stepper: each contender's seeds with at least one tie of n (the ties in all) and failed
seeds; a last row with each contender's seeds with a tie over the rows every contender ran (a
scene without boxes has no ode-box; --contenders narrows the list); with --pair A,B,
A against B paired by seed (seeds where only A / only B meets a tie, the exact two-sided sign test's
p).

Usage: python3 -m gdcreport lcp-ties RESULTS_DIR... [--contenders A,B,...] [--pair A,B]
"""
import argparse
import os
from collections import defaultdict

from gdcreport.data import read_csv
from gdcreport.stats import paired_by_seed
from gdcreport.steppers import stepper_label, steppers_in


def load(dirs):
    """(scene, stepper, contender) -> seed -> (ties, failed); the scenes and contenders in run order."""
    runs = defaultdict(dict)
    scenes, contenders = [], []
    for d in dirs:
        for r in read_csv(os.path.join(d, "solver_seeds_runs.csv")):
            if r["scene"] not in scenes:
                scenes.append(r["scene"])
            if r["contender"] not in contenders:
                contenders.append(r["contender"])
            runs[(r["scene"], r["stepper"], r["contender"])][int(r["seed"])] = (int(r["lcp_errors"]), r["failed"] == "1")
    return runs, scenes, contenders


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--contenders", help="comma-separated, in this order (default: all, in run order)")
    parser.add_argument("--pair", help="A,B: A paired by seed against B")
    args = parser.parse_args(argv)
    runs, scenes, found = load(args.dirs)
    contenders = args.contenders.split(",") if args.contenders else found
    pair = args.pair.split(",") if args.pair else None
    if pair and len(pair) != 2:
        parser.error("--pair takes two contenders, A,B")
    print("Cells: seeds with an \"LCP internal error\" of n (the errors in all) · failed seeds."
          + (f" Paired: seeds where only `{pair[0]}` / only `{pair[1]}` meets one (sign test's p)." if pair else "") + "\n")
    print("| scene | stepper | " + " | ".join(f"`{c}`" for c in contenders) + (" | paired |" if pair else " |"))
    print("|---|---|" + "---|" * len(contenders) + ("---|" if pair else ""))
    totals = defaultdict(lambda: [0, 0])  # contender -> [seeds with a tie, seeds]
    for scene in scenes:
        rows = [{"stepper": st} for (sc, st, _) in runs if sc == scene]
        for stepper in steppers_in(rows):
            cells = []
            everyone = all((scene, stepper, c) in runs for c in contenders)
            for c in contenders:
                seeds = runs.get((scene, stepper, c))
                if not seeds:
                    cells.append("–")
                    continue
                tied = sum(v[0] > 0 for v in seeds.values())
                if everyone:  # the totals compare like with like: the rows every contender ran
                    totals[c][0] += tied
                    totals[c][1] += len(seeds)
                cells.append(f"{tied} of {len(seeds)} ({sum(v[0] for v in seeds.values())}) · "
                             f"{sum(v[1] for v in seeds.values())}")
            line = f"| {scene} | {stepper_label(stepper)} | " + " | ".join(cells) + " |"
            if pair:
                a, b = (runs.get((scene, stepper, c)) for c in pair)
                tied = paired_by_seed(a, b, lambda result: result[0] > 0) if a and b else None
                line += (" {} / {} ({:.2g}) |".format(*tied) if tied else " – |")
            print(line)
    print("| the rows all ran | | " + " | ".join(f"{totals[c][0]} of {totals[c][1]}" for c in contenders) + " |"
          + (" |" if pair else ""))
    return 0
