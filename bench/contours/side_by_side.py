#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Two SVG frames of the same size side by side, each cropped to the same region, as one SVG (the
# pictures of docs/contours.md and docs/strokes.md; rasterise it with rsvg-convert):
#
#   bench/contours/side_by_side.py LEFT.svg RIGHT.svg "X Y W H" PANEL_W PANEL_H OUT.svg
#
# The armadillo picture (docs/images/contour-armadillo-mesh-vs-smooth.png), with the turntable
# scene of bench/contours/modes.py (its --work folder keeps it as armadillo/scene.json):
#
#   for m in mesh smooth; do
#     build/cli/inkline render WORK/armadillo/scene.json --contour $m --frames 60:60 --svg /tmp/$m.svg -q
#   done
#   bench/contours/side_by_side.py /tmp/mesh.svg /tmp/smooth.svg "368 222 260 258" 328 325 /tmp/pair.svg
#   rsvg-convert /tmp/pair.svg -o docs/images/contour-armadillo-mesh-vs-smooth.png

import sys
from pathlib import Path


def content(svg):
    """What the SVG document holds inside its root element."""
    start = svg.index(">", svg.index("<svg")) + 1
    return svg[start:svg.rindex("</svg>")]


def main():
    if len(sys.argv) != 7:
        sys.exit("usage: side_by_side.py LEFT.svg RIGHT.svg \"X Y W H\" PANEL_W PANEL_H OUT.svg")
    left, right, view, width, height, out = sys.argv[1:]
    width, height = int(width), int(height)
    parts = [
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        'xmlns:inkline="https://inkline.invalid/ns/1" width="%d" height="%d">' % (2 * width, height),
        '<rect width="%d" height="%d" fill="white"/>' % (2 * width, height),
    ]
    for i, path in enumerate((left, right)):
        parts.append('<svg x="%d" y="0" width="%d" height="%d" viewBox="%s">%s</svg>'
                     % (i * width, width, height, view, content(Path(path).read_text())))
    parts.append("</svg>")
    Path(out).write_text("\n".join(parts) + "\n")


if __name__ == "__main__":
    main()
