#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Checks the pictures viz/render_run.py wrote: RUN_DIR/pictures/NAME exists for every NAME
given, is a PNG of at least 400 × 300 pixels and at most 300 kB, is not one flat colour, and
its outermost FRAME pixels are background (a title or panel cut off at the edge is not).
    check_pictures.py RUN_DIR NAME.png [NAME.png ...]
"""
import os
import sys

from PIL import Image

MAX_BYTES = 300 * 1024
FRAME = 2  # pixels


def touches_edge(image):
    """True when a pixel of the image's outer frame is not near-white background."""
    grey = image.convert("L")
    width, height = grey.size
    boxes = [(0, 0, width, FRAME), (0, height - FRAME, width, height), (0, 0, FRAME, height),
             (width - FRAME, 0, width, height)]
    return any(grey.crop(box).getextrema()[0] < 235 for box in boxes)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    run_dir, names = sys.argv[1], sys.argv[2:]
    problems = []
    for name in names:
        path = os.path.join(run_dir, "pictures", name)
        if not os.path.isfile(path):
            problems.append(f"{path}: missing")
            continue
        size = os.path.getsize(path)
        if size > MAX_BYTES:
            problems.append(f"{path}: {size} bytes > {MAX_BYTES}")
        with Image.open(path) as image:
            if image.format != "PNG":
                problems.append(f"{path}: not a PNG ({image.format})")
            width, height = image.size
            if width < 400 or height < 300:
                problems.append(f"{path}: only {width} x {height} pixels")
            low, high = image.convert("L").getextrema()
            if low == high:
                problems.append(f"{path}: one flat colour")
            if touches_edge(image):
                problems.append(f"{path}: drawing at the edge of the picture (a clipped title?)")
        print(f"check_pictures: {path}: {size // 1024} kB")
    for problem in problems:
        print(f"check_pictures: {problem}", file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
