#!/usr/bin/env python3
"""Makes one animated GIF per paper scene for results/report.md, the methods side by side.

For every scene run that scripts/run made (SCENE_METHOD_BOXES.json in the results directory), the
viewer replays the same scene headless (`--scripted`, the same scripted user as the headless run)
and writes every K-th frame as PNG (`--record-every K --record-dir DIR`); the frames of the three
methods are put side by side under a label (method, the run's own PASS/FAIL, time) and written as
SCENE_animation.gif (scripts/gdcreport/gifs.py). Needs an X server in DISPLAY (scripts/run starts
this script under xvfb-run) and Pillow (Debian's python3-pil, which python3-matplotlib pulls in).

Usage: scripts/animate.py RESULTS_DIR --viewer PATH [--frames 40] [--size 480x270] [--jobs 2] [--keep-frames]
"""
import argparse
import concurrent.futures
import glob
import math
import os
import shutil
import subprocess
import sys
import time

from gdcreport import data
from gdcreport.gifs import side_by_side_gif

METHODS = ["gdc", "tracking", "ode"]
METHOD_LABEL = {"gdc": "gdcontact", "tracking": "contact tracking", "ode": "ODE native"}
# Which run of each scene to show: the one where the methods differ most. The brick wall with
# dConvex bricks is the one ODE's own convex collider fails; with dBox bricks all three stand.
ANIMATIONS = [("box_drop", "box"), ("tower", "box"), ("brick_wall", "convex"), ("composites", "box"),
              ("barrels", "box"), ("terrain", "box")]
FRAME_RATE = 60.0  # the viewer's headless frames advance 1/60 s of simulated time each


def run_viewer(viewer, results, scene, method, boxes, frames, every, size):
    """Records one run's frames; returns (directory, seconds, error or None)."""
    directory = os.path.join(results, "frames", f"{scene}_{method}_{boxes}")
    shutil.rmtree(directory, ignore_errors=True)
    command = [viewer, "--scene", scene, "--method", method, "--scripted", "--no-panel", "--no-contacts",
               "--hidden", "--size", size, "--frames", str(frames), "--record-every", str(every),
               "--record-dir", directory]
    if boxes == "convex":
        command.append("--convex")
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if done.returncode != 0:
        return directory, seconds, f"{' '.join(command)} exited with {done.returncode}: {done.stderr.strip()[-300:]}"
    return directory, seconds, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--viewer", required=True)
    parser.add_argument("--frames", type=int, default=40, help="frames per animation (about)")
    parser.add_argument("--size", default="480x270", help="one method's frame, WxH pixels")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--playback-seconds", type=float, default=6.0, help="how long one pass of an animation takes")
    parser.add_argument("--keep-frames", action="store_true", help="keep the PNG frames (RESULTS_DIR/frames/)")
    arguments = parser.parse_args()
    if "DISPLAY" not in os.environ:
        sys.exit("animate.py: no DISPLAY (run it under xvfb-run)")

    jobs = []
    for scene, boxes in ANIMATIONS:
        runs = {}
        for method in METHODS:
            path = os.path.join(arguments.results, f"{scene}_{method}_{boxes}.json")
            if os.path.exists(path):
                runs[method] = data.read_json(path)
        if not runs:
            continue
        # As long as the headless run: its steps × dt, in 1/60 s viewer frames.
        summary = next(iter(runs.values()))
        total = int(round(summary["steps"] * summary["dt"] * FRAME_RATE))
        every = max(1, math.ceil(total / arguments.frames))
        jobs.append((scene, boxes, runs, total, every))

    start = time.monotonic()
    failures = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=arguments.jobs) as pool:
        futures = {}
        # Longest first, by the headless run's own time (steps × ms per step), so that the two
        # workers finish together rather than one waiting on a long recording started last.
        queue = [(summary["steps"] * (summary["collision_ms"] + summary["solver_ms"]), scene, boxes, method, total, every)
                 for scene, boxes, runs, total, every in jobs for method, summary in runs.items()]
        for _, scene, boxes, method, total, every in sorted(queue, reverse=True):
            futures[(scene, method)] = pool.submit(run_viewer, arguments.viewer, arguments.results, scene, method,
                                                   boxes, total, every, arguments.size)
        recorded = {key: future.result() for key, future in futures.items()}

    for scene, boxes, runs, total, every in jobs:
        panels, labels = [], []
        for method in runs:
            directory, seconds, error = recorded[(scene, method)]
            if error:
                failures.append(error)
                continue
            panels.append(sorted(glob.glob(os.path.join(directory, "frame_*.png"))))
            verdict = "PASS" if runs[method]["success"] else "FAIL"
            labels.append((f"{METHOD_LABEL[method]}: {verdict}", (0, 110, 0) if runs[method]["success"] else (190, 0, 0)))
        if not panels or min(len(p) for p in panels) == 0:
            continue
        # Recorded frames are 0, every, 2·every, ... and the last (total − 1); frame f ends at (f + 1)/60 s.
        indices = list(range(0, total, every))
        if indices[-1] != total - 1:
            indices.append(total - 1)
        times = [(f + 1) / FRAME_RATE for f in indices]
        out = os.path.join(arguments.results, f"{scene}_animation.gif")
        side_by_side_gif(panels, labels, times, out, arguments.playback_seconds / max(len(times), 1))
        if not arguments.keep_frames:
            for method in runs:
                shutil.rmtree(recorded[(scene, method)][0], ignore_errors=True)
        slowest = max(recorded[(scene, method)][1] for method in runs)
        print(f"{out}: {len(times)} frames of {len(panels)} method(s), every {every / FRAME_RATE:.2f} s of the "
              f"scene; the slowest recording took {slowest:.0f} s")
    if not arguments.keep_frames:
        try:
            os.rmdir(os.path.join(arguments.results, "frames"))
        except OSError:
            pass  # frames of a failed recording are kept for a look
    print(f"animations made in {time.monotonic() - start:.0f} s")
    if failures:
        print("\n".join(failures), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
