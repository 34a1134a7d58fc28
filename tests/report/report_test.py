#!/usr/bin/env python3
"""The scenes report and its check (python3 -m gdcreport scenes / check) on made-up runs of the four scenes.

The runs are written in the formats the scene programs write (--summary JSON, --csv), with
verdicts chosen so that every method passes some and fails some; the report's summary must then
have one line per scene run, the right verdict per method, and the check must accept it —
and reject the same report with a line dropped, a line repeated or a verdict flipped.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
from gdcreport import check as check_report  # noqa: E402

METHODS = ["gdc", "tracking", "ode"]
# (scene, boxes, {method: success}): every method fails somewhere, two scenes with both shapes.
RUNS = [("box_drop", "box", {"gdc": True, "tracking": True, "ode": True}),
        ("box_drop", "convex", {"gdc": True, "tracking": False, "ode": True}),
        ("tower", "box", {"gdc": True, "tracking": False, "ode": False}),
        ("brick_wall", "convex", {"gdc": True, "tracking": True, "ode": False}),
        ("brick_wall", "box", {"gdc": False, "tracking": True, "ode": True}),
        ("composites", "box", {"gdc": True, "tracking": True, "ode": True})]
COLUMNS = ["time", "penetration", "contact_penetration", "alignment", "drift", "twist", "sag", "speed", "contacts",
           "invalid_contacts", "collision_seconds", "solver_seconds"]
EXTRA = {"tower": ["placed", "stacked", "top_tilt", "lean_change", "push_force"],
         "brick_wall": ["removed", "max_displacement"], "composites": ["released", "stacked", "stack_height"]}


def write_run(directory, scene, method, boxes, success, seed):
    values = {"box_drop": {"final_speed": 1e-15 * seed},
              "tower": {"stacked_before_push": 11, "stacked_now": 11 if success else 3,
                        "max_top_tilt_during_push": 1e-8 * seed, "max_lean_change_during_push": 1e-9 * seed},
              "brick_wall": dict({f"after_removal_{k}": 1e-4 * k * seed for k in range(1, 11)},
                                 max_displacement=1e-3 * seed),
              "composites": {"stacked": 5, "final_speed": 1e-10 * seed}}[scene]
    summary = {"scene": scene, "method": method, "boxes": boxes, "stepper": "world", "iterations": 20, "dt": 0.01,
               "steps": 300, "exploded": False, "samples": 100, "max_penetration": 1e-9 * seed,
               "mean_penetration": 1e-10 * seed, "max_contact_penetration": 1e-9, "max_alignment": 1e-12 * seed,
               "mean_alignment": 1e-13, "max_drift": 1e-9, "max_twist": 1e-10, "max_sag": 1e-10,
               "oscillation": 1e-12 * seed, "collision_ms": 0.1 * seed, "solver_ms": 0.5 * seed, "success": success,
               "outcome": ("made-up run that passes" if success else "made-up run that fails"), "values": values}
    name = os.path.join(directory, f"{scene}_{method}_{boxes}")
    with open(name + ".json", "w") as f:
        json.dump(summary, f)
    columns = COLUMNS + EXTRA.get(scene, [])
    with open(name + ".csv", "w") as f:
        f.write(",".join(columns) + "\n")
        for step in range(1, 301):
            time = step * 0.01
            at_rest = time >= 2.0
            row = {c: abs(math.sin(step * 0.1 + seed)) * 1e-6 for c in columns}
            row.update(time=time, contacts=4 * seed, push_force=100.0 if 2.2 <= time <= 2.6 else 0.0)
            for column in ("drift", "twist", "sag"):
                row[column] = row[column] if at_rest else float("nan")
            f.write(",".join(repr(row[c]) for c in columns) + "\n")


class ReportSummary(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.directory = tempfile.mkdtemp(prefix="gdcontact_report_test_")
        seed = 1
        for scene, boxes, verdicts in RUNS:
            for method in METHODS:
                write_run(cls.directory, scene, method, boxes, verdicts[method], seed)
                seed += 1
        # As scripts/run runs it: the package as a command, scripts/ on PYTHONPATH.
        environment = dict(os.environ, PYTHONPATH=SCRIPTS)
        subprocess.run([sys.executable, "-m", "gdcreport", "scenes", cls.directory], check=True, env=environment)
        with open(os.path.join(cls.directory, "report.md")) as f:
            cls.report = f.read()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.directory, ignore_errors=True)

    def rewrite(self, change):
        """The check's verdict on the report after change(text) (restored afterwards)."""
        path = os.path.join(self.directory, "report.md")
        with open(path, "w") as f:
            f.write(change(self.report))
        try:
            return check_report.check(self.directory, check_report.SCENES)
        finally:
            with open(path, "w") as f:
                f.write(self.report)

    def test_summary_comes_first_with_a_line_per_scene_run(self):
        self.assertLess(self.report.index("## Summary"), self.report.index("## Box drop"))
        table = check_report.summary_table(self.report)
        self.assertEqual(len(table) - 1, len(RUNS))
        for row in table[1:]:
            verdicts = [cell.split()[0] for cell in row if cell.split() and cell.split()[0] in ("PASS", "FAIL")]
            self.assertEqual(len(verdicts), len(METHODS), row)

    def test_verdicts_match_the_runs(self):
        table = check_report.summary_table(self.report)
        header = table[0]
        rows = {row[0]: row for row in table[1:]}
        tower = rows["Tower"]
        self.assertTrue(tower[header.index("gdcontact")].startswith("PASS"))
        self.assertTrue(tower[header.index("contact tracking")].startswith("FAIL"))
        self.assertTrue(rows["Brick wall, dBox"][header.index("gdcontact")].startswith("FAIL"))
        self.assertEqual(check_report.check(self.directory, check_report.SCENES), [])

    def test_check_catches_a_dropped_line(self):
        problems = self.rewrite(lambda text: "\n".join(line for line in text.splitlines()
                                                       if not line.startswith("| Composites |")))
        self.assertTrue(any("Composites" in p for p in problems), problems)

    def test_check_catches_a_repeated_line(self):
        def repeat(text):
            lines = text.splitlines()
            row = next(i for i, line in enumerate(lines) if line.startswith("| Tower |"))
            return "\n".join(lines[:row + 1] + [lines[row]] + lines[row + 1:])
        self.assertTrue(self.rewrite(repeat))

    def test_check_catches_a_flipped_verdict(self):
        def flip(text):
            lines = text.splitlines()
            row = next(i for i, line in enumerate(lines) if line.startswith("| Brick wall, dBox |"))
            lines[row] = lines[row].replace("| FAIL", "| PASS", 1)
            return "\n".join(lines)
        problems = self.rewrite(flip)
        self.assertTrue(any("Brick wall, dBox" in p for p in problems), problems)

    def test_check_wants_every_scene(self):
        problems = check_report.check(self.directory, check_report.SCENES + ["pyramid"])
        self.assertEqual(problems, ["no run of scene 'pyramid' in " + self.directory])

    def test_check_catches_a_verdict_without_a_run(self):
        path = os.path.join(self.directory, "tower_gdc_box.json")
        os.rename(path, path + ".off")
        try:
            problems = check_report.check(self.directory, check_report.SCENES)
        finally:
            os.rename(path + ".off", path)
        self.assertTrue(any("no run" in p for p in problems), problems)

    def test_plots_are_written(self):
        for name in ("box_drop_errors.png", "tower_tilt.png", "brick_wall_displacement.png", "composites_rest.png"):
            self.assertTrue(os.path.getsize(os.path.join(self.directory, name)) > 0, name)


if __name__ == "__main__":
    unittest.main()
