"""Reading the result files the benchmark and scene programs write, and writing a generated
section between two marker lines of a hand-kept page (docs/benchmarks.md)."""
import argparse
import csv
import json
import os


# The marker lines (begin, end) of the sections of docs/benchmarks.md that bench.py keeps when it
# rewrites the page: those that commands of their own write (big.py, solver_seeds.py) and the one
# kept by hand (the contact set's tables over seeds, each naming its command). A begin marker is
# matched up to ": begin", so a page whose marker names an older writer is still spliced in place.
BIG_WORLDS = ("<!-- big-worlds: begin (written by scripts/bench --big, python3 -m gdcreport big) -->",
              "<!-- big-worlds: end -->")
SOLVER_SEEDS = ("<!-- solver-seeds: begin (written by scripts/solver_seeds, python3 -m gdcreport solver-seeds) -->",
                "<!-- solver-seeds: end -->")
CONTACT_SET = ("<!-- contact-set: begin (kept by hand: scripts/bench keeps this block; each table names its command) -->",
               "<!-- contact-set: end -->")
KEPT_SECTIONS = [BIG_WORLDS, SOLVER_SEEDS, CONTACT_SET]


def results_and_docs_arguments(description, argv=None):
    """The command line of the docs/benchmarks.md generators: --results DIR (the benchmark's
    output) and --docs DIR (where benchmarks.md and images/ go)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--results", required=True)
    parser.add_argument("--docs", required=True)
    return parser.parse_args(argv)


def read_csv(path):
    """The rows of a CSV file with a header line, as dicts of text."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_columns(path):
    """A CSV file of numbers as {column: [float, ...]} (a scene program's --csv per-step series)."""
    columns = {}
    for row in read_csv(path):
        for column, text in row.items():
            columns.setdefault(column, []).append(float(text))
    return columns


def read_json(path):
    with open(path) as f:
        return json.load(f)


def read_key_values(path):
    """KEY=VALUE lines (machine.txt, big_machine.txt) as a dict; {} when the file is absent."""
    values = {}
    if not os.path.exists(path):
        return values
    with open(path) as f:
        for line in f:
            if "=" in line:
                key, value = line.rstrip("\n").split("=", 1)
                values[key] = value
    return values


def load_scene_runs(results, with_series=True):
    """{(scene, method, boxes): (summary, series)} from every SCENE_METHOD_BOXES.json a scene
    program wrote with --summary, and its .csv (--csv) beside it when present: series is
    {column: [float]} ({} without the CSV or with with_series=False). A run with a contacts
    column gets summary["mean_contacts"]."""
    runs = {}
    for name in sorted(os.listdir(results)):
        if not name.endswith(".json"):
            continue
        summary = read_json(os.path.join(results, name))
        series = {}
        csv_path = os.path.join(results, name[:-5] + ".csv")
        if with_series and os.path.exists(csv_path):
            series = read_columns(csv_path)
        if series.get("contacts"):
            summary["mean_contacts"] = sum(series["contacts"]) / len(series["contacts"])
        runs[(summary["scene"], summary["method"], summary["boxes"])] = (summary, series)
    return runs


def _begin_key(begin):
    """What of a begin marker identifies it: up to ": begin" (the rest names its writer)."""
    return begin[:begin.index(": begin") + len(": begin")] if ": begin" in begin else begin


def marked_block(text, begin, end):
    """The block from the line starting with `begin` (matched up to ": begin") to the `end` marker,
    both included; None when the text lacks either."""
    begin = _begin_key(begin)
    if begin not in text or end not in text:
        return None
    return text[text.index(begin):text.index(end) + len(end)]


def splice(doc_path, begin, end, section):
    """The page at doc_path (or a bare "# Benchmarks" page) with `section` between the marker lines
    begin and end: replacing the block there, or appended after a blank line. The section is
    followed by a blank line before whatever came after the old block."""
    block = f"{begin}\n{section.rstrip()}\n{end}\n"
    existing = "# Benchmarks\n"
    if os.path.exists(doc_path):
        with open(doc_path) as f:
            existing = f.read()
    if marked_block(existing, begin, end) is None:
        return existing.rstrip("\n") + "\n\n" + block
    before = existing[:existing.index(_begin_key(begin))]
    after = existing[existing.index(end) + len(end):].lstrip("\n")
    return before + block + ("\n" + after if after else "")
