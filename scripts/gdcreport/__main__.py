"""python3 -m gdcreport COMMAND [ARGUMENTS...] (with the repository's scripts/ on PYTHONPATH):
every report of gdcontact from the files its programs wrote. `python3 -m gdcreport COMMAND --help`
for a command's arguments.

  scenes        results/report.md and its plots from the scene runs of scripts/run
  check         checks the summary of results/report.md against the scene runs (exit 1 if wrong)
  solver-seeds  the "Solver over seeds" section (scripts/run, scripts/solver_seeds)
  bench         docs/benchmarks.md and docs/images/bench_*.png from scripts/bench's results
  big           the "Big worlds" section of docs/benchmarks.md (scripts/bench --big)
  budget        the contact budget tables of docs/algorithm.md from solver-seeds runs (stdout)
  order         a contact order against the default and ODE's options, paired by seed (stdout)
  lcp-ties      dWorldStep's "LCP internal error"s per contender over seeds (stdout)
  mesh-cost     docs/images/mesh_cost.png and docs/meshes.md's cost table from bench_mesh_cost --csv
"""
import importlib
import sys

# command → module of this package; each module's main(argv) reads its own arguments.
COMMANDS = {"scenes": "scenes", "check": "check", "solver-seeds": "solver_seeds", "bench": "bench", "big": "big",
            "budget": "budget", "order": "order", "lcp-ties": "lcp_ties", "mesh-cost": "mesh_cost"}


def main(argv):
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in COMMANDS:
        print(__doc__.strip(), file=sys.stdout if argv and argv[0] in ("-h", "--help") else sys.stderr)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    module = importlib.import_module(f"gdcreport.{COMMANDS[argv[0]]}")
    sys.argv[0] = f"python3 -m gdcreport {argv[0]}"  # argparse's usage line names the command
    return module.main(argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
