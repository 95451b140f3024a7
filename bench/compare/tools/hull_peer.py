"""Convex hull by qhull (scipy.spatial.ConvexHull), fresh process: read an .xyz file, hull it.

Usage: hull_peer.py FILE. Prints one JSON object (volume, area, kernel_s: ConvexHull alone).
"""
import json
import sys
import time

import numpy as np
from scipy.spatial import ConvexHull

pts = np.loadtxt(sys.argv[1])
t0 = time.perf_counter()
hull = ConvexHull(pts)
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(hull.volume), "area": float(hull.area), "kernel_s": kernel,
                  "points": int(len(pts)), "hull_vertices": int(len(hull.vertices))}))
