"""Checks the summary at the top of results/report.md against the runs it summarises.

The summary must have exactly one line per scene run (scene and box shape, as found in the
SCENE_METHOD_BOXES.json files), every scene of --scenes among them, a column per method, and in
each cell the verdict that method's run gave (PASS/FAIL, its "success"). Reads the Markdown table
as a reader would, so it fails when the scenes report drops, repeats or mislabels a line. Exit status 1
with the reasons on stderr; scripts/run and CTest (tests/report) run it.

Usage: python3 -m gdcreport check RESULTS_DIR [--scenes box_drop,tower,brick_wall,composites]
"""
import argparse
import os
import sys

from gdcreport import data
from gdcreport.scenes import BOXES_LABEL, METHOD_LABEL, SCENE_TITLE, SCENES, SUMMARY_HEADING
from gdcreport.tables import parse_table


def summary_table(report_text):
    """The rows (lists of cell texts) of the first table under the summary heading, header first."""
    lines = report_text.splitlines()
    try:
        start = lines.index(SUMMARY_HEADING)
    except ValueError:
        raise SystemExit(f"no '{SUMMARY_HEADING}' section in the report")
    section = []
    for line in lines[start + 1:]:
        if line.startswith("## "):
            break
        section.append(line)
    rows = parse_table(section)  # without the |---| line
    if not rows:
        raise SystemExit("the summary has no table")
    return rows


def check(results, scenes):
    problems = []
    runs = {key: summary["success"] for key, (summary, _) in data.load_scene_runs(results, with_series=False).items()}
    if not runs:
        return [f"no runs (*.json) in {results}"]
    with open(os.path.join(results, "report.md")) as f:
        table = summary_table(f.read())
    header, rows = table[0], table[1:]

    methods = sorted({m for (_, m, _) in runs})
    columns = {}
    for method in methods:
        label = METHOD_LABEL.get(method, method)
        if header.count(label) != 1:
            problems.append(f"summary header {header} has {header.count(label)} columns for method '{label}'")
        else:
            columns[method] = header.index(label)

    shapes = {}
    for scene, _, boxes in runs:
        shapes.setdefault(scene, set()).add(boxes)
    for scene in scenes:
        if scene not in shapes:
            problems.append(f"no run of scene '{scene}' in {results}")

    for scene, boxes in sorted({(s, b) for (s, _, b) in runs}):
        title = SCENE_TITLE.get(scene, scene)
        label = f"{title}, {BOXES_LABEL.get(boxes, boxes)}" if len(shapes[scene]) > 1 else title
        matching = [row for row in rows if row[0] == label]
        if len(matching) != 1:
            problems.append(f"summary has {len(matching)} lines for '{label}', wants exactly one")
            continue
        row = matching[0]
        for method, column in columns.items():
            cell = row[column] if column < len(row) else ""
            words = cell.split()
            given = words[0] if words else ""
            if (scene, method, boxes) not in runs:
                if given in ("PASS", "FAIL"):
                    problems.append(f"'{label}': {method} has verdict {given} but no run")
                continue
            wanted = "PASS" if runs[(scene, method, boxes)] else "FAIL"
            if given != wanted:
                problems.append(f"'{label}': {METHOD_LABEL.get(method, method)} says '{cell}', the run says {wanted}")
    expected_rows = len({(s, b) for (s, _, b) in runs})
    if len(rows) != expected_rows:
        problems.append(f"summary has {len(rows)} lines, the runs make {expected_rows} (scene, box shape) pairs")
    return problems


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--scenes", default=",".join(SCENES), help="scenes that must be in the summary (comma list)")
    arguments = parser.parse_args(argv)
    scenes = [s for s in arguments.scenes.split(",") if s]
    problems = check(arguments.results, scenes)
    if problems:
        print("report summary check FAILED:\n  " + "\n  ".join(problems), file=sys.stderr)
        sys.exit(1)
    print(f"report summary check: one line per scene run, one verdict per method, matching the runs "
          f"({arguments.results}/report.md)")

