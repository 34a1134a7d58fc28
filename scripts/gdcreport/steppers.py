"""The solver benchmark's steppers (bench_solver_seeds --stepper): their order and labels, for
every report of its runs (solver_seeds, order). Standard library only."""

STEPPER_ORDER = ["quick10", "quick20", "quick50", "world"]
STEPPER_LABEL = {"quick10": "QuickStep 10 it.", "quick20": "QuickStep 20 it.", "quick50": "QuickStep 50 it.",
                 "world": "dWorldStep"}


def stepper_label(name):
    """A stepper's label; a solver variant (bench_solver_seeds' "quick20/cfm=1e-5/mu=0.8/maxc=4") keeps its suffix."""
    base, _, variant = name.partition("/")
    return STEPPER_LABEL.get(base, base) + (f" ({variant.replace('/', ', ')})" if variant else "")


def steppers_in(rows):
    """The steppers present, the plain ones in STEPPER_ORDER, then their variants by name."""
    names = {r["stepper"] for r in rows}
    return sorted(names, key=lambda n: (STEPPER_ORDER.index(n.partition("/")[0]) if n.partition("/")[0] in STEPPER_ORDER else 9, n))
