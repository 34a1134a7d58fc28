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
# Further out, every 7.5° as well, so that a leader line can find a gap between placed labels.
_FAR_DIRECTIONS = _DIRECTIONS + [(math.cos(math.radians(a / 2)), math.sin(math.radians(a / 2)))
                                 for a in range(0, 720, 15)]
_NEAR_PT = [3, 8]  # beside the point: no leader line
_MID_PT = [14, 22, 32, 45, 60]  # with a short leader line
_FAR_PT = [80, 105, 135, 170, 210]  # with a long one, when moving other labels does not help
_FARTHEST_PT = [260, 320, 390, 470, 560]  # a last resort
_MOVES = 3  # how often one label may move the labels in its way


class _Label:
    """One label being placed: its point and text box size (pixels), and where it sits."""

    def __init__(self, pixel, size):
        self.pixel, self.size = pixel, size
        self.box, self.leader = None, None  # leader: (from, to) in pixels, when it has one


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


def _segments_cross(a, b):
    """Do the segments a and b ((p, q) each) cross at a point inside both (not where they meet at
    an end, as two leaders from one point do)?"""
    def side(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    (p1, q1), (p2, q2) = a, b
    return (side(p1, q1, p2) * side(p1, q1, q2) < 0) and (side(p2, q2, p1) * side(p2, q2, q1) < 0)


def _nearest_point(box, point):
    """The point of box nearest to point: where a leader line from point meets the label."""
    return (min(max(point[0], box[0]), box[2]), min(max(point[1], box[1]), box[3]))


def _candidates(label, distances_pt, half, to_px):
    """(box, leader or None) spots around the label's point, nearest first. A box touches the spot
    with its nearest side or corner, so a label never covers its own point."""
    (px, py), (width, height) = label.pixel, label.size
    for distance_pt in distances_pt:
        far = distance_pt > _NEAR_PT[-1]
        distance = half + distance_pt * to_px
        for dx, dy in (_FAR_DIRECTIONS if far else _DIRECTIONS):
            norm = math.hypot(dx, dy)
            sx, sy = px + distance * dx / norm, py + distance * dy / norm
            x0 = sx if dx > 1e-9 else sx - width if dx < -1e-9 else sx - width / 2
            y0 = sy if dy > 1e-9 else sy - height if dy < -1e-9 else sy - height / 2
            box = (x0, y0, x0 + width, y0 + height)
            yield box, ((px, py), _nearest_point(box, (px, py))) if far else None


def _blockers(box, leader, others, gap, leaders_may_cross=False, leader_over_labels=False):
    """The placed labels a label at box (with its leader) would clash with: box on box, its leader
    through their box, their leader through its box, or the two leaders crossing (a label's own leader meets its box only
    at the box's edge, which the clipping counts as crossing: compare with the grown box)."""
    grown = (box[0] - gap, box[1] - gap, box[2] + gap, box[3] + gap)
    return [other for other in others if other.box is not None and (
        _boxes_overlap(box, other.box, gap)
        or (leader is not None and not leader_over_labels and _segment_crosses_box(leader[0], leader[1], other.box))
        or (other.leader is not None and _segment_crosses_box(other.leader[0], other.leader[1], grown))
        or (not leaders_may_cross and leader is not None and other.leader is not None
            and _segments_cross(leader, other.leader)))]


def place_labels(ax, xs, ys, texts, fontsize=7, colours=None, marker_points=None, marker_size_pt=7.0,
                 gap_px=2.0, merge_px=2.0):
    """Labels the points (xs[i], ys[i]) in data coordinates with texts[i] (None: no label), so that
    no label overlaps another label, any marker, the legend or the axes' edge, and no leader line
    runs through a label. Call it after the figure's layout is final (tight_layout first; save with
    save_figure(..., tight=False)). Points closer than merge_px on screen share one label, their
    texts one per line. marker_points: every marker to keep clear, (xs, ys) in data coordinates
    (default: the labelled points); marker_size_pt: their size.

    How: first every label that fits right beside its point goes there, in the order given; the
    others then take the nearest free spot further out, with a leader line. A label that finds
    none within 60 pt takes a free spot within 210 pt or else moves the labels in its way (those
    that moved it only when nothing else helps; at most three times per label, so it ends), and
    they look again. Returns (annotations, texts that found no spot — only when the axes are full: left out
    rather than drawn over another)."""
    figure = ax.figure
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    to_px = figure.dpi / 72.0
    extent = ax.get_window_extent(renderer)
    frame = (extent.x0 + gap_px, extent.y0 + gap_px, extent.x1 - gap_px, extent.y1 - gap_px)
    half = 0.5 * marker_size_pt * to_px
    xs_m, ys_m = marker_points if marker_points is not None else (xs, ys)
    obstacles = [(x - half, y - half, x + half, y + half)
                 for x, y in (ax.transData.transform((mx, my)) for mx, my in zip(xs_m, ys_m)
                              if math.isfinite(mx) and math.isfinite(my))]
    obstacles += _legend_box(ax, renderer)
    # Group the labelled points that coincide on screen.
    groups = []  # [pixel point, data point, [texts], colour]
    for i, (x, y, text) in enumerate(zip(xs, ys, texts)):
        if text is None or not (math.isfinite(x) and math.isfinite(y)):
            continue
        pixel = tuple(ax.transData.transform((x, y)))
        for group in groups:
            if math.hypot(group[0][0] - pixel[0], group[0][1] - pixel[1]) <= merge_px:
                if text not in group[2]:
                    group[2].append(text)
                break
        else:
            groups.append([pixel, (x, y), [text], colours[i] if colours else "black"])
    labels = []
    for pixel, _, group_texts, _ in groups:
        probe = ax.text(0, 0, "\n".join(group_texts), fontsize=fontsize, transform=ax.transAxes)
        size = probe.get_window_extent(renderer)
        probe.remove()
        labels.append(_Label(pixel, (size.width, size.height)))

    def allowed(box, leader, leader_over_markers=False):
        """In the frame, off every marker and the legend, and its leader line across no marker but
        its own (a line through a row of markers would seem to join them; allowed as a last resort)."""
        return (frame[0] <= box[0] and box[2] <= frame[2] and frame[1] <= box[1] and box[3] <= frame[3]
                and not any(_boxes_overlap(box, other, gap_px) for other in obstacles)
                and (leader is None or leader_over_markers or not any(
                    _segment_crosses_box(leader[0], leader[1], other) for other in obstacles
                    if not (other[0] <= leader[0][0] <= other[2] and other[1] <= leader[0][1] <= other[3]))))

    def place(label, distances_pt, last_resort=0):
        """The nearest clear spot at these distances. As a last resort (1) its leader line may cross
        markers and other leader lines, (2) labels as well: better than leaving the label out. Its
        text never covers another's."""
        for box, leader in _candidates(label, distances_pt, half, to_px):
            if allowed(box, leader, last_resort >= 1) and not _blockers(box, leader, labels, gap_px, last_resort >= 1,
                                                                         last_resort >= 2):
                label.box, label.leader = box, leader
                return True
        return False

    for label in labels:
        place(label, _NEAR_PT)
    waiting = [label for label in labels if label.box is None]
    moves = {}  # how often a label has moved others: at most _MOVES times each, so the loop ends
    moved_by = {}  # a label → the labels that moved it (it moves them back only when nothing else helps)
    while waiting:
        label = waiting.pop(0)
        if place(label, _MID_PT):
            continue
        if moves.get(id(label), 0) < _MOVES:
            # The spot within reach that the fewest labels stand in, a free far one before moving
            # any, the labels that moved this one moved back last.
            options = []
            for rank, (box, leader) in enumerate(_candidates(label, _NEAR_PT + _MID_PT + _FAR_PT, half, to_px)):
                if allowed(box, leader):
                    blocking = _blockers(box, leader, labels, gap_px)
                    back = sum(id(other) in moved_by.get(id(label), ()) for other in blocking)
                    options.append((back, len(blocking), rank, box, leader, blocking))
            if options:
                _, _, _, box, leader, blocking = min(options, key=lambda option: option[:3])
                for other in blocking:
                    moved_by.setdefault(id(other), set()).add(id(label))
                    other.box, other.leader = None, None
                    waiting.append(other)
                label.box, label.leader = box, leader
                if blocking:
                    moves[id(label)] = moves.get(id(label), 0) + 1
                continue
        everywhere = _MID_PT + _FAR_PT + _FARTHEST_PT
        place(label, _FAR_PT) or place(label, _FARTHEST_PT) or place(label, everywhere, 1) or place(label, everywhere, 2)

    annotations, unplaced = [], []
    for label, (pixel, (x, y), group_texts, colour) in zip(labels, groups):
        text = "\n".join(group_texts)
        if label.box is None:
            unplaced.append(text)
            continue
        # The text's lower-left corner as an offset from the point, in points (so it survives a
        # different dpi in savefig).
        offset = ((label.box[0] - pixel[0]) / to_px, (label.box[1] - pixel[1]) / to_px)
        arrow = (dict(arrowstyle="-", color="0.45", linewidth=0.5, shrinkA=0, shrinkB=half / to_px)
                 if label.leader else None)
        annotations.append(ax.annotate(text, (x, y), xytext=offset, textcoords="offset points", fontsize=fontsize,
                                       ha="left", va="bottom", color=colour, arrowprops=arrow, zorder=5,
                                       annotation_clip=False))
    return annotations, unplaced


def _legend_box(ax, renderer):
    """The axes' legend as an obstacle box ([] without a legend)."""
    legend = ax.get_legend()
    if legend is None:
        return []
    extent = legend.get_window_extent(renderer)
    return [(extent.x0, extent.y0, extent.x1, extent.y1)]


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
    legend = _legend_box(ax, renderer)
    for i, (text_a, a) in enumerate(boxes):
        if any(_boxes_overlap(a, box, 0.0) for box in legend):
            problems.append(f"label {text_a!r} covers the legend")
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
