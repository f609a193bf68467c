#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Checks the pictures viz/render_run.py wrote: RUN_DIR/pictures/NAME exists for every NAME
given, is a PNG of at least 400 × 300 pixels and at most 300 kB, and is not one flat colour.
    check_pictures.py RUN_DIR NAME.png [NAME.png ...]
"""
import os
import sys

from PIL import Image

MAX_BYTES = 300 * 1024


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
        print(f"check_pictures: {path}: {size // 1024} kB")
    for problem in problems:
        print(f"check_pictures: {problem}", file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
