"""gdcreport: every report of gdcontact, one package — run as `python3 -m gdcreport COMMAND` with the
repository's scripts/ on PYTHONPATH (__main__.py lists the commands):

  scenes.py        results/report.md of scripts/run (the paper's scenes)
  check.py         the check of that report's summary against the runs
  solver_seeds.py  the "Solver over seeds" section (results/report.md, docs/benchmarks.md)
  bench.py         docs/benchmarks.md (scripts/bench)
  big.py           its "Big worlds" section (scripts/bench --big)
  budget.py        the contact budget tables of docs/algorithm.md (from solver-seeds runs)
  order.py         a contact order against the default and ODE's options, paired by seed (from solver-seeds runs)

and what they share: numbers as text (numbers), statistics — medians, the Wilson interval, the
exact sign test (stats), Markdown tables (tables), reading the result files and splicing a section
between marker lines (data), matplotlib plots with labels that do not overlap (plots), and animated
GIFs (gifs). scripts/animate.py and bench/callgrind_counts.py, which run programs, use it too.
Plain Python 3 with Debian's python3-matplotlib (plots) and python3-pil (GIFs); each module imports
only what it needs, so reading, formatting and statistics work without either.
"""
