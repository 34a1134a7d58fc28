#!/usr/bin/env python3
"""Instructions per call of every per-pair case, from callgrind (used by scripts/bench).

Runs bench_instructions under `valgrind --tool=callgrind --collect-atstart=no`: the driver switches
collection on only around each contender's cycled calls and dumps the counts after each
(CALLGRIND_DUMP_STATS_AT, named family/case/contender). This script reads those dumps, subtracts
the cost of the driver's own loop (an empty query, measured the same way) and writes

    family,case,contender,calls,contacts_per_call,instructions_per_call

Usage: callgrind_counts.py --driver BUILD/bench/bench_instructions --out instructions.csv
                           [--work DIR] [driver options: --cycles N --big-cycles N FILTER...]
"""
import argparse
import csv
import glob
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from gdcreport import data  # noqa: E402


def read_dumps(directory):
    """{dump name: instructions} from the callgrind.out.N files of one run."""
    counts = {}
    for path in glob.glob(os.path.join(directory, "callgrind.out.*")):
        name, total = None, None
        with open(path) as f:
            for line in f:
                if line.startswith("desc: Trigger: Client Request: "):
                    name = line.split("Client Request: ", 1)[1].strip()
                elif line.startswith("totals:") or (total is None and line.startswith("summary:")):
                    total = int(line.split(":", 1)[1].split()[0])
                elif line.startswith("fl=") or line.startswith("fn="):
                    break  # the header is over (totals come first in callgrind's format)
        if name is not None and total is not None:
            counts[name] = total
    return counts


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--driver", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--work", help="directory for callgrind's dumps (default: a temporary one, removed)")
    args, driver_args = parser.parse_known_args()

    work = args.work or tempfile.mkdtemp(prefix="callgrind-")
    os.makedirs(work, exist_ok=True)
    for old in glob.glob(os.path.join(work, "callgrind.out*")):
        os.remove(old)
    manifest = os.path.join(work, "manifest.csv")
    command = ["valgrind", "--tool=callgrind", "--collect-atstart=no",
               f"--callgrind-out-file={os.path.join(work, 'callgrind.out')}",
               args.driver, "--manifest", manifest] + driver_args
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    counts = read_dumps(work)
    rows = data.read_csv(manifest)
    overhead = 0.0
    for r in rows:
        if r["family"] == "loop":
            overhead = counts["loop/overhead/empty"] / int(r["calls"])
    with open(args.out, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["family", "case", "contender", "calls", "contacts_per_call", "instructions_per_call"])
        for r in rows:
            if r["family"] == "loop":
                continue
            name = f"{r['family']}/{r['case']}/{r['contender']}"
            if name not in counts:
                print(f"callgrind_counts.py: no dump for {name}", file=sys.stderr)
                continue
            per_call = counts[name] / int(r["calls"]) - overhead
            out.writerow([r["family"], r["case"], r["contender"], r["calls"], r["contacts_per_call"], f"{per_call:.1f}"])
    if not args.work:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
