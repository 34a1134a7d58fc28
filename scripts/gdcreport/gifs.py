"""Animated GIFs for the reports: frames side by side under a label each, one shared palette.
Needs Pillow (Debian's python3-pil, which python3-matplotlib pulls in)."""
import os

from PIL import Image, ImageDraw, ImageFont

LABEL_HEIGHT = 22  # px of the label strip above the frames


def label_font(size=14):
    """DejaVu Sans (it ships with matplotlib, and in fonts-dejavu-core); Pillow's bitmap font when
    neither is found."""
    try:
        import matplotlib
        path = os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")
        return ImageFont.truetype(path, size)
    except (ImportError, OSError):
        return ImageFont.load_default()


def write_gif(frames, path, frame_ms, hold_last_ms=2000):
    """Writes RGB images as a looping GIF: each shown frame_ms, the last held hold_last_ms so that
    the end state can be read. One palette (the middle frame's) for all keeps the file small and
    stops the colours flickering."""
    palette = frames[len(frames) // 2].quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    quantized = [frame.quantize(palette=palette, dither=Image.Dither.NONE) for frame in frames]
    durations = [frame_ms] * (len(quantized) - 1) + [hold_last_ms]
    quantized[0].save(path, save_all=True, append_images=quantized[1:], duration=durations, loop=0, optimize=True)


def side_by_side_gif(panels, labels, times, path, frame_seconds):
    """panels: per panel a list of image paths (the shortest list sets the frame count); labels:
    per panel (text, RGB colour) written above it; times: the simulated time of each frame, shown
    at the top right. Writes the GIF to path, each frame shown frame_seconds."""
    font = label_font()
    count = min(len(p) for p in panels)
    with Image.open(panels[0][0]) as first:
        width, height = first.size
    frames = []
    for index in range(count):
        sheet = Image.new("RGB", (width * len(panels), height + LABEL_HEIGHT), "white")
        draw = ImageDraw.Draw(sheet)
        for column, (paths, (text, colour)) in enumerate(zip(panels, labels)):
            with Image.open(paths[index]) as frame:
                sheet.paste(frame.convert("RGB"), (column * width, LABEL_HEIGHT))
            draw.text((column * width + 6, 3), text, fill=colour, font=font)
            if column:
                draw.line([(column * width, 0), (column * width, height + LABEL_HEIGHT)], fill="white", width=2)
        clock = f"t = {times[index]:4.1f} s"
        draw.text((width * len(panels) - 6 - draw.textlength(clock, font=font), 3), clock, fill="black", font=font)
        frames.append(sheet)
    write_gif(frames, path, frame_seconds * 1000)
