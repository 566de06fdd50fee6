#!/usr/bin/env python3
"""Fraction of pixels on which two RGBA8 PNGs agree within each tolerance (max over R, G, B).

    compare_images.py A.png B.png  ->  {"size": [w, h], "within": {"0": 0.9996, "1": ..., ...}}
"""
import json
import sys

import numpy as np
from PIL import Image

a = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(int)
b = np.asarray(Image.open(sys.argv[2]).convert("RGB")).astype(int)
if a.shape != b.shape:
    sys.exit(f"sizes differ: {a.shape} vs {b.shape}")
d = np.abs(a - b).max(axis=2)
print(json.dumps({"size": [a.shape[1], a.shape[0]], "within": {str(t): float((d <= t).mean()) for t in [0, 1, 2, 4, 8]}}))
