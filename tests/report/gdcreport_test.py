#!/usr/bin/env python3
"""scripts/gdcreport, the report package: number formats, statistics, Markdown tables, the
marker splice, GIF writing, and the label placer, whose labels must not overlap one another, a
marker, the legend or the axes' edge — on a crowded made-up cluster and on the speed/accuracy
(Pareto) plot of gdcreport.bench drawn from a real `bench_tradeoff --quick` output
(data/tradeoff_quick.csv). Overlap is measured as a reader sees it: the labels' text boxes from
matplotlib's renderer.
"""
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(REPO, "scripts"))
from gdcreport import data, numbers, plots, stats, tables  # noqa: E402
from gdcreport import bench as bench_report  # noqa: E402
from gdcreport.plots import plt  # noqa: E402


class Numbers(unittest.TestCase):
    def test_fmt(self):
        self.assertEqual(numbers.fmt(None), "–")
        self.assertEqual(numbers.fmt(math.nan), "–")
        self.assertEqual(numbers.fmt(0.0), "0")
        self.assertEqual(numbers.fmt(0.0123456), "0.0123")
        self.assertEqual(numbers.fmt(1234.5), "1.23e+03")
        self.assertEqual(numbers.fmt(1234.5, whole_from=100), "1234")
        self.assertEqual(numbers.fmt(99.94, whole_from=100), "99.9")
        self.assertEqual(numbers.fmt(0.123456, 2), "0.12")

    def test_units(self):
        self.assertEqual(numbers.fmt_ns(512.4), "512 ns")
        self.assertEqual(numbers.fmt_ns(1234.0), "1.23 µs")
        self.assertEqual(numbers.fmt_ns(12345.0), "12 µs")
        self.assertEqual(numbers.fmt_ns(2.5e6), "2.50 ms")
        self.assertEqual(numbers.fmt_ns(math.nan), "–")
        self.assertEqual([numbers.fmt_ms(x) for x in (123.4, 12.34, 1.234, 0.1234)], ["123", "12.3", "1.23", "0.123"])
        self.assertEqual(numbers.fmt_ms("0.5"), "0.500")
        self.assertEqual(numbers.fmt_instructions(12345.0), "12.3 k")
        self.assertEqual(numbers.fmt_instructions(999.4), "999")
        self.assertEqual(numbers.fmt_count(4.0004), "4")
        self.assertEqual(numbers.fmt_count(4.25), "4.25")
        self.assertEqual(numbers.fmt_percent(0.256), "26 %")

    def test_median_ratio_number(self):
        self.assertEqual(stats.median([3, 1, 2]), 2)
        self.assertEqual(stats.median([4, 1, 2, 3]), 2.5)
        self.assertTrue(math.isnan(stats.median([])))
        self.assertEqual(numbers.ratio(3.0, 2.0), 1.5)
        self.assertEqual(numbers.ratio(1.0, 0.0), math.inf)
        self.assertTrue(math.isnan(numbers.ratio(0.0, 0.0)))
        self.assertEqual(numbers.number("2.5"), 2.5)
        self.assertTrue(math.isnan(numbers.number("")))
        self.assertTrue(math.isnan(numbers.number(None)))


class Tables(unittest.TestCase):
    def test_table_and_its_reading(self):
        text = tables.table(["a", "b"], [[1, "x"], ["–", 2.5]])
        self.assertEqual(text, "| a | b |\n|---|---|\n| 1 | x |\n| – | 2.5 |")
        self.assertEqual(tables.parse_table(["text before", ""] + text.splitlines() + ["", "| other |"]),
                         [["a", "b"], ["1", "x"], ["–", "2.5"]])


class Splice(unittest.TestCase):
    def setUp(self):
        self.directory = tempfile.mkdtemp(prefix="gdcreport_test_")
        self.path = os.path.join(self.directory, "page.md")

    def tearDown(self):
        shutil.rmtree(self.directory, ignore_errors=True)

    def test_appends_then_replaces_between_the_markers(self):
        begin, end = "<!-- x: begin -->", "<!-- x: end -->"
        with open(self.path, "w") as f:
            f.write("# Page\n\nhand-kept text\n")
        first = data.splice(self.path, begin, end, "## X\n\nold\n")
        self.assertEqual(first, "# Page\n\nhand-kept text\n\n<!-- x: begin -->\n## X\n\nold\n<!-- x: end -->\n")
        with open(self.path, "w") as f:
            f.write(first + "\n## After\n")
        second = data.splice(self.path, begin, end, "## X\n\nnew")
        self.assertEqual(second, "# Page\n\nhand-kept text\n\n<!-- x: begin -->\n## X\n\nnew\n<!-- x: end -->\n"
                                 "\n## After\n")
        self.assertEqual(data.marked_block(second, begin, end), "<!-- x: begin -->\n## X\n\nnew\n<!-- x: end -->")
        self.assertIsNone(data.marked_block("no markers", begin, end))

    def test_a_marker_naming_another_writer_is_replaced_in_place(self):
        with open(self.path, "w") as f:
            f.write("# Page\n\n<!-- x: begin (written by old.py) -->\nold\n<!-- x: end -->\n\n## After\n")
        text = data.splice(self.path, "<!-- x: begin (written by new.py) -->", "<!-- x: end -->", "new")
        self.assertEqual(text, "# Page\n\n<!-- x: begin (written by new.py) -->\nnew\n<!-- x: end -->\n\n## After\n")

    def test_key_values(self):
        with open(self.path, "w") as f:
            f.write("cpu=Some CPU = fast\nnot a pair\ncores=2\n")
        self.assertEqual(data.read_key_values(self.path), {"cpu": "Some CPU = fast", "cores": "2"})
        self.assertEqual(data.read_key_values(self.path + ".absent"), {})


class KeptSections(unittest.TestCase):
    def test_every_marked_block_of_the_benchmarks_page_is_kept(self):
        """scripts/bench rewrites docs/benchmarks.md and keeps only data.KEPT_SECTIONS: a marked
        block of the committed page that is not among them would be lost by the next run."""
        with open(os.path.join(REPO, "docs", "benchmarks.md")) as f:
            page = f.read()
        begins = [line for line in page.splitlines() if line.startswith("<!-- ") and ": begin" in line]
        self.assertGreaterEqual(len(begins), 3)
        kept = [data.marked_block(page, begin, end) for begin, end in data.KEPT_SECTIONS]
        for begin in begins:
            self.assertTrue(any(block is not None and block.startswith(begin) for block in kept), begin)


class Stats(unittest.TestCase):
    def test_sign_test(self):
        self.assertEqual(stats.sign_test(0, 0), 1.0)
        self.assertEqual(stats.sign_test(3, 3), 1.0)
        self.assertAlmostEqual(stats.sign_test(0, 5), 2 / 32)  # both tails of 5 fair coins all alike
        self.assertAlmostEqual(stats.sign_test(6, 1), 2 * 8 / 128)  # P(k <= 1 of 7) = 8/128, twice
        self.assertEqual(stats.sign_test(1, 6), stats.sign_test(6, 1))

    def test_wilson(self):
        self.assertEqual(stats.wilson(0, 0), (0.0, 1.0))
        low, high = stats.wilson(0, 10)
        self.assertEqual(low, 0.0)
        self.assertAlmostEqual(high, 0.2775, places=4)  # z² / (n + z²) for no successes
        low, high = stats.wilson(5, 10)
        self.assertAlmostEqual(low + high, 1.0)  # symmetric about one half
        self.assertLess(low, 0.5)


class Commands(unittest.TestCase):
    """python3 -m gdcreport as the callers run it (scripts/ on PYTHONPATH)."""

    def run_command(self, *arguments):
        environment = dict(os.environ, PYTHONPATH=os.path.join(REPO, "scripts"))
        return subprocess.run([sys.executable, "-m", "gdcreport", *arguments], env=environment,
                              capture_output=True, text=True)

    def test_an_unknown_command_fails_and_lists_the_commands(self):
        result = self.run_command("no-such-report")
        self.assertEqual(result.returncode, 2)
        for command in ("scenes", "check", "solver-seeds", "bench", "big", "budget", "lcp-ties", "mesh-cost"):
            self.assertIn(command, result.stderr)

    def runs_directory(self, prefix, header, lines):
        """A temporary results directory whose solver_seeds_runs.csv has `header` and `lines`."""
        directory = tempfile.mkdtemp(prefix=prefix)
        self.addCleanup(shutil.rmtree, directory, ignore_errors=True)
        with open(os.path.join(directory, "solver_seeds_runs.csv"), "w") as f:
            f.write(header + "\n" + "".join(line + "\n" for line in lines))
        return directory

    def test_budget_pairs_seeds_with_the_sign_test(self):
        # Made-up runs of one scene: the variant fails seeds 0-5, the default none of them.
        directory = self.runs_directory(
            "gdcreport_budget_", "scene,stepper,contender,seed,failed,contacts_per_step,sleep_time,drift",
            [line for seed in range(10) for line in (f"pile,quick20,gdc,{seed},0,8,1.5,0.001",
                                                     f"pile,quick20,gdc:maxContacts=4,{seed},{int(seed < 6)},4,-1,0.002")])
        with open(os.path.join(directory, "solver_seeds_summary.csv"), "w") as f:
            f.write("scene,stepper,contender,best_ode,cost_whole_ms\n")
            f.write("pile,quick20,gdc,,2.0\npile,quick20,gdc:maxContacts=4,,1.0\n")
        result = self.run_command("budget", directory, "--contenders", "gdc,gdc:maxContacts=4")
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line for line in result.stdout.splitlines() if line.startswith("| pile | QuickStep 20 | `gdc:")]
        self.assertEqual(len(rows), 1)  # the paired row: 6 seeds only the variant fails, none the other
        self.assertEqual(rows[0].split("|")[5:9], [" 10 ", " 6 ", " 0 ", f" {stats.sign_test(6, 0):.2g} "])
        self.assertIn("6/10 [", result.stdout)

    def test_lcp_ties_counts_seeds_pairs_them_and_totals_the_rows_all_ran(self):
        # Made-up runs: in "plates", A meets ties in seeds 0-4 (two each), B in seed 9 only;
        # "hulls" has no B, so the totals leave it out.
        directory = self.runs_directory(
            "gdcreport_lcp_ties_", "scene,stepper,contender,seed,failed,lcp_errors",
            [line for seed in range(10) for line in (f"plates,world,A,{seed},0,{2 if seed < 5 else 0}",
                                                     f"plates,world,B,{seed},{int(seed == 9)},{int(seed == 9)}",
                                                     f"hulls,world,A,{seed},0,1")])
        result = self.run_command("lcp-ties", directory, "--pair", "A,B")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn(f"| plates | dWorldStep | 5 of 10 (10) · 0 | 1 of 10 (1) · 1 | 5 / 1 ({stats.sign_test(5, 1):.2g}) |",
                      result.stdout)
        self.assertIn("| hulls | dWorldStep | 10 of 10 (10) · 0 | – | – |", result.stdout)
        self.assertIn("| the rows all ran | | 5 of 10 | 1 of 10 | |", result.stdout)

    def test_mesh_cost_plots_and_tabulates_every_row(self):
        directory = tempfile.mkdtemp(prefix="gdcreport_mesh_cost_")
        self.addCleanup(shutil.rmtree, directory, ignore_errors=True)
        source = os.path.join(directory, "mesh_cost.csv")
        # Made-up rows in bench_mesh_cost --csv's layout: the ratios are 600/400 and 300/400.
        with open(source, "w") as f:
            f.write("triangles,body,ode_ns,adapter_ns,core_ns,ode_contacts,adapter_contacts,core_contacts\n")
            for triangles in (32, 512, 8192):
                f.write(f"{triangles},box,400,600,300,18,4,4\n{triangles},hull8,200,100,50,1,1,1\n")
        image = os.path.join(directory, "mesh_cost.png")
        result = self.run_command("mesh-cost", source, "--plot", image)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line for line in result.stdout.splitlines() if line.startswith("| ") and line[2].isdigit()]
        self.assertEqual(len(rows), 6)
        self.assertIn("| 512 | box | 400 | 600 | 300 | 1.50 / 0.75 | 18 / 4 (core 4) |", rows)
        self.assertIn("| 8192 | 8-vertex hull | 200 | 100 | 50 | 0.50 / 0.25 | 1 / 1 (core 1) |", rows)
        with open(image, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        empty = os.path.join(directory, "empty.csv")
        with open(empty, "w") as f:
            f.write("triangles,body,ode_ns,adapter_ns,core_ns,ode_contacts,adapter_contacts,core_contacts\n")
        self.assertNotEqual(self.run_command("mesh-cost", empty, "--plot", image).returncode, 0)


class Gifs(unittest.TestCase):
    def test_side_by_side(self):
        from PIL import Image
        from gdcreport.gifs import LABEL_HEIGHT, side_by_side_gif
        directory = tempfile.mkdtemp(prefix="gdcreport_gif_")
        try:
            panels = []
            for panel, colour in enumerate(("red", "blue")):
                paths = []
                for frame in range(3):
                    path = os.path.join(directory, f"p{panel}_{frame}.png")
                    Image.new("RGB", (40, 30), colour).save(path)
                    paths.append(path)
                panels.append(paths)
            out = os.path.join(directory, "out.gif")
            side_by_side_gif(panels, [("a: PASS", (0, 110, 0)), ("b: FAIL", (190, 0, 0))], [0.5, 1.0, 1.5], out, 0.1)
            with Image.open(out) as gif:
                self.assertEqual(gif.size, (80, 30 + LABEL_HEIGHT))
                self.assertEqual(gif.n_frames, 3)
        finally:
            shutil.rmtree(directory, ignore_errors=True)


class Labels(unittest.TestCase):
    def test_a_crowded_cluster_gets_every_label_clear(self):
        generator = random.Random(7)
        xs = [10 ** generator.uniform(2.0, 2.6) for _ in range(40)] + [300.0] * 3  # three on one spot
        ys = [10 ** generator.uniform(1.9, 2.3) for _ in range(40)] + [150.0] * 3
        texts = [f"setting{i}={generator.choice(['0.001', '16', 'true', '1e-08'])}" for i in range(len(xs))]
        figure, ax = plt.subplots(figsize=(8, 6), dpi=plots.DPI)
        ax.scatter(xs, ys, s=25)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(1, 1e3)
        ax.plot([], [], label="a legend")
        ax.legend(loc="lower right")
        figure.tight_layout()
        annotations, unplaced = plots.place_labels(ax, xs, ys, texts)
        self.assertEqual(unplaced, [])
        self.assertEqual(plots.label_overlaps(ax, annotations, (xs, ys)), [])
        shown = "\n".join(a.get_text() for a in annotations)
        for text in texts:
            self.assertIn(text, shown)
        self.assertEqual(len(annotations), 41)  # the three on one spot share a label
        plt.close(figure)

    def test_the_check_sees_overlapping_labels(self):
        # What the Pareto plot did before: every label at the same small offset from its point.
        figure, ax = plt.subplots(figsize=(4, 3), dpi=plots.DPI)
        xs, ys = [1.0, 1.02, 3.0], [1.0, 1.0, 3.0]
        ax.scatter(xs, ys)
        annotations = [ax.annotate(f"a long label {i}", (x, y), xytext=(3, 2), textcoords="offset points", fontsize=6)
                       for i, (x, y) in enumerate(zip(xs, ys))]
        problems = plots.label_overlaps(ax, annotations, (xs, ys))
        self.assertTrue(any("overlaps label" in p for p in problems), problems)
        self.assertTrue(any("covers the marker" in p for p in problems), problems)
        plt.close(figure)

    def test_pareto_plot_labels_are_readable(self):
        rows = data.read_csv(os.path.join(HERE, "data", "tradeoff_quick.csv"))
        figure, labelled, unplaced = bench_report.pareto_figure(rows)
        self.assertEqual(unplaced, [])
        for ax, annotations, points in labelled:
            self.assertGreater(len(annotations), 5)
            self.assertEqual(plots.label_overlaps(ax, annotations, points), [], ax.get_title())
        left = "\n".join(a.get_text() for a in labelled[0][1])
        for row in rows:
            if row["table"] == "manifold":  # every manifold row is labelled on the left
                label = "defaults" if row["parameter"] == "defaults" else row["value"]
                self.assertIn(label, left)
        path = os.path.join(tempfile.mkdtemp(prefix="gdcreport_pareto_"), "pareto.png")
        plots.save_figure(figure, path, tight=False)
        self.assertGreater(os.path.getsize(path), 0)
        shutil.rmtree(os.path.dirname(path), ignore_errors=True)


if __name__ == "__main__":
    unittest.main()
