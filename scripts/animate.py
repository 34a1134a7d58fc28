#!/usr/bin/env python3
"""Makes one animated GIF per paper scene for results/report.md, the methods side by side.

For every scene run that scripts/run made (SCENE_METHOD_BOXES.json in the results directory), the
viewer replays the same scene headless (`--scripted`, the same scripted user as the headless run)
and writes every K-th frame as PNG (`--record-every K --record-dir DIR`); the frames of the three
methods are put side by side under a label (method, the run's own PASS/FAIL, time) and written as
SCENE_animation.gif. Needs an X server in DISPLAY (scripts/run starts this script under xvfb-run)
and Pillow (Debian's python3-pil, which python3-matplotlib pulls in).

Usage: scripts/animate.py RESULTS_DIR --viewer PATH [--frames 40] [--size 480x270] [--jobs 2] [--keep-frames]
"""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import time

from PIL import Image, ImageDraw, ImageFont

METHODS = ["gdc", "tracking", "ode"]
METHOD_LABEL = {"gdc": "gdcontact", "tracking": "contact tracking", "ode": "ODE native"}
# Which run of each scene to show: the one where the methods differ most. The brick wall with
# dConvex bricks is the one ODE's own convex collider fails; with dBox bricks all three stand.
ANIMATIONS = [("box_drop", "box"), ("tower", "box"), ("brick_wall", "convex"), ("composites", "box")]
FRAME_RATE = 60.0  # the viewer's headless frames advance 1/60 s of simulated time each
LABEL_HEIGHT = 22


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


def label_font():
    # DejaVu ships with matplotlib (and in fonts-dejavu-core); Pillow's bitmap font is the fallback.
    try:
        import matplotlib
        path = os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")
        return ImageFont.truetype(path, 14)
    except (ImportError, OSError):
        return ImageFont.load_default()


def compose(panels, labels, times, out_path, frame_seconds):
    """panels: per method a list of PNG paths (same count); writes the side-by-side GIF."""
    font = label_font()
    count = min(len(p) for p in panels)
    first = Image.open(panels[0][0])
    width, height = first.size
    frames = []
    for index in range(count):
        sheet = Image.new("RGB", (width * len(panels), height + LABEL_HEIGHT), "white")
        draw = ImageDraw.Draw(sheet)
        for column, (paths, (text, colour)) in enumerate(zip(panels, labels)):
            sheet.paste(Image.open(paths[index]).convert("RGB"), (column * width, LABEL_HEIGHT))
            draw.text((column * width + 6, 3), text, fill=colour, font=font)
            if column:
                draw.line([(column * width, 0), (column * width, height + LABEL_HEIGHT)], fill="white", width=2)
        clock = f"t = {times[index]:4.1f} s"
        draw.text((width * len(panels) - 6 - draw.textlength(clock, font=font), 3), clock, fill="black", font=font)
        # One shared palette for the whole animation keeps the file small and stops flicker.
        frames.append(sheet)
    palette = frames[len(frames) // 2].quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    quantized = [f.quantize(palette=palette, dither=Image.Dither.NONE) for f in frames]
    # Show each frame for its share of the scene (sped up so the whole scene takes a few seconds),
    # and hold the last one so the end state can be read.
    durations = [frame_seconds * 1000] * (len(quantized) - 1) + [2000]
    quantized[0].save(out_path, save_all=True, append_images=quantized[1:], duration=durations, loop=0,
                      optimize=True)


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
                with open(path) as f:
                    runs[method] = json.load(f)
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
        compose(panels, labels, times, out, arguments.playback_seconds / max(len(times), 1))
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
