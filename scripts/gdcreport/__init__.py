"""gdcreport: what the report scripts share — numbers as text, Markdown tables, reading the result
files, matplotlib plots with labels that do not overlap, and animated GIFs.

Used by scripts/report.py (results/report.md of scripts/run), scripts/solver_seeds_report.py (the
"Solver over seeds" section), scripts/check_report.py, scripts/animate.py, bench/report.py
(docs/benchmarks.md), bench/big_report.py (its "Big worlds" section) and bench/callgrind_counts.py.
Plain Python 3 with Debian's python3-matplotlib (plots) and python3-pil (GIFs); each module imports
only what it needs, so reading and formatting work without either.

A script outside scripts/ finds the package with `sys.path.insert(0, <repo>/scripts)`.
"""
