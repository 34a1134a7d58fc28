"""matplotlib for files (no display), saving figures, plain log-scale ticks, and point labels that
overlap neither each other nor the markers: `place_labels` puts each label at the nearest free
spot around its point, with a thin leader line when that spot is not right beside it. (adjustText
would do this but is not in Debian; this placer is greedy and small, and `label_overlaps` checks
its result.)"""
import math

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
from matplotlib.text import Text  # noqa: E402

DPI = 110  # the reports' resolution


def save_figure(figure, path, dpi=DPI, tight=True):
    """Writes the figure to path and closes it. tight=False keeps the layout as it is (after
    place_labels, which placed the labels for this layout)."""
    if tight:
        figure.tight_layout()
    figure.savefig(path, dpi=dpi)
    plt.close(figure)
    return path


def plain_log_ticks(axis, subs=(1.0, 2.0, 5.0)):
    """Major ticks at 1, 2 and 5 of each decade, labelled plainly (0.02, not 2×10⁻²); no labels on
    the minor ticks, whose labels overlapped."""
    axis.set_major_locator(ticker.LogLocator(base=10, subs=subs))
    axis.set_major_formatter(ticker.FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(ticker.NullFormatter())


# ---- labels beside points --------------------------------------------------------------------------

# Where a label may go, as (dx, dy) directions from its point, tried in this order at each distance:
# right, above, left, below, then the diagonals. At each distance every direction is tried before
# going further out, so a label stays as close to its point as the others allow.
_DIRECTIONS = [(1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (-1, 1), (-1, -1), (1, -1),
               (2, 1), (-2, 1), (-2, -1), (2, -1), (1, 2), (-1, 2), (-1, -2), (1, -2)]
_DISTANCES_PT = [3, 8, 14, 22, 32, 45, 60, 80, 105, 135, 170, 210, 260, 320]
_LEADER_FROM_PT = 10  # labels further than this from their point get a leader line


def _boxes_overlap(a, b, gap):
    return a[0] < b[2] + gap and b[0] < a[2] + gap and a[1] < b[3] + gap and b[1] < a[3] + gap


def _segment_crosses_box(p, q, box):
    """Does the segment p–q pass through the rectangle box (x0, y0, x1, y1)? Liang–Barsky clipping."""
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for edge_p, edge_q in ((-dx, p[0] - box[0]), (dx, box[2] - p[0]), (-dy, p[1] - box[1]), (dy, box[3] - p[1])):
        if edge_p == 0:
            if edge_q < 0:
                return False
            continue
        t = edge_q / edge_p
        if edge_p < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return False
    return True


def _candidate_box(point, direction, distance, size):
    """The label's box (x0, y0, x1, y1) in pixels when placed `distance` px from point in
    `direction`: the box's nearest side or corner at that spot, so the label never covers its point."""
    (px, py), (dx, dy), (width, height) = point, direction, size
    norm = math.hypot(dx, dy)
    ax_, ay_ = px + distance * dx / norm, py + distance * dy / norm
    x0 = ax_ if dx > 0 else ax_ - width if dx < 0 else ax_ - width / 2
    y0 = ay_ if dy > 0 else ay_ - height if dy < 0 else ay_ - height / 2
    return (x0, y0, x0 + width, y0 + height)


def place_labels(ax, xs, ys, texts, fontsize=7, colours=None, marker_points=None, marker_size_pt=7.0,
                 gap_px=2.0, merge_px=2.0):
    """Labels the points (xs[i], ys[i]) in data coordinates with texts[i] (None: no label), so that
    no label overlaps another label, any marker or the axes' edge, and no leader line runs through
    another label. Call it after the figure's layout is final (tight_layout first; save with
    save_figure(..., tight=False)). Points closer than merge_px on screen share one label, their
    texts one per line. marker_points: every marker to keep clear, (xs, ys) in data coordinates
    (default: the labelled points); marker_size_pt: their size. Labels are placed in the order
    given, each at the nearest free spot; returns (annotations, unplaced texts) — a text finds no
    spot only when the axes are full, and is then left out rather than drawn over another."""
    figure = ax.figure
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    to_px = figure.dpi / 72.0
    frame = ax.get_window_extent(renderer)
    frame = (frame.x0, frame.y0, frame.x1, frame.y1)
    half = 0.5 * marker_size_pt * to_px
    xs_m, ys_m = marker_points if marker_points is not None else (xs, ys)
    markers = [(x - half, y - half, x + half, y + half)
               for x, y in (ax.transData.transform((mx, my)) for mx, my in zip(xs_m, ys_m)
                            if math.isfinite(mx) and math.isfinite(my))]
    # Group the labelled points that coincide on screen.
    groups = []  # [pixel point, data point, [texts], colour]
    for i, (x, y, text) in enumerate(zip(xs, ys, texts)):
        if text is None or not (math.isfinite(x) and math.isfinite(y)):
            continue
        pixel = tuple(ax.transData.transform((x, y)))
        colour = colours[i] if colours else "black"
        for group in groups:
            if math.hypot(group[0][0] - pixel[0], group[0][1] - pixel[1]) <= merge_px:
                if text not in group[2]:
                    group[2].append(text)
                break
        else:
            groups.append([pixel, (x, y), [text], colour])
    placed, annotations, unplaced = [], [], []
    for pixel, (x, y), group_texts, colour in groups:
        text = "\n".join(group_texts)
        probe = ax.text(0, 0, text, fontsize=fontsize, transform=ax.transAxes)
        extent = probe.get_window_extent(renderer)
        probe.remove()
        size = (extent.width, extent.height)
        spot = None
        for distance_pt in _DISTANCES_PT:
            for direction in _DIRECTIONS:
                box = _candidate_box(pixel, direction, half + distance_pt * to_px, size)
                if not (box[0] >= frame[0] + gap_px and box[2] <= frame[2] - gap_px
                        and box[1] >= frame[1] + gap_px and box[3] <= frame[3] - gap_px):
                    continue
                if any(_boxes_overlap(box, other, gap_px) for other in placed + markers):
                    continue
                far = distance_pt > _LEADER_FROM_PT
                anchor = (min(max(pixel[0], box[0]), box[2]), min(max(pixel[1], box[1]), box[3]))
                if far and any(_segment_crosses_box(pixel, anchor, other) for other in placed):
                    continue
                spot = (box, far)
                break
            if spot:
                break
        if spot is None:
            unplaced.append(text)
            continue
        box, far = spot
        placed.append(box)
        # The text's lower-left corner as an offset from the point, in points (so it survives a
        # different dpi in savefig).
        offset = ((box[0] - pixel[0]) / to_px, (box[1] - pixel[1]) / to_px)
        arrow = dict(arrowstyle="-", color="0.45", linewidth=0.5, shrinkA=0, shrinkB=half / to_px) if far else None
        annotations.append(ax.annotate(text, (x, y), xytext=offset, textcoords="offset points", fontsize=fontsize,
                                       ha="left", va="bottom", color=colour, arrowprops=arrow, zorder=5,
                                       annotation_clip=False))
    return annotations, unplaced


def label_overlaps(ax, annotations, marker_points, marker_size_pt=7.0):
    """What a reader would see wrong with the labels as drawn: pairs of labels whose boxes overlap,
    labels over a marker, labels crossing the axes' edge (descriptions; empty when all are clear)."""
    figure = ax.figure
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    half = 0.5 * marker_size_pt * figure.dpi / 72.0
    frame = ax.get_window_extent(renderer)
    boxes = []
    for annotation in annotations:
        extent = Text.get_window_extent(annotation, renderer)  # the text alone, not its leader line
        boxes.append((annotation.get_text(), (extent.x0, extent.y0, extent.x1, extent.y1)))
    problems = []
    for i, (text_a, a) in enumerate(boxes):
        for text_b, b in boxes[i + 1:]:
            if _boxes_overlap(a, b, 0.0):
                problems.append(f"label {text_a!r} overlaps label {text_b!r}")
        for mx, my in zip(*marker_points):
            x, y = ax.transData.transform((mx, my))
            if _boxes_overlap(a, (x - half, y - half, x + half, y + half), 0.0):
                problems.append(f"label {text_a!r} covers the marker at ({mx:g}, {my:g})")
        if a[0] < frame.x0 or a[2] > frame.x1 or a[1] < frame.y0 or a[3] > frame.y1:
            problems.append(f"label {text_a!r} crosses the axes' edge")
    return problems
