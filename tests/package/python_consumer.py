# SPDX-License-Identifier: MIT
"""The installed Python module, from outside: python_consumer.py SITE SCENE FRAME OUT.json
draws FRAME of SCENE (ray-cast visibility) with the inkline package found under SITE only."""
import sys

import inkline

site, scene, frame, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
assert inkline.__file__.startswith(site), f"inkline imported from {inkline.__file__}, not from {site}"
inkline.open(scene, frames=(frame, frame), visibility="raycast").render(frame).write_json(out)
