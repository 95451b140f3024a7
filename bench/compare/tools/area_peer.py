"""Polygon area by shapely, fresh process: read a WKT (one geometry per line) or GeoJSON file.

Usage: area_peer.py MODE FILE, MODE shapely (area, perimeter and centroid of every polygon,
vectorised shapely 2 calls) or shapely-valid (the same plus is_valid, GEOS's check for
self-intersecting and crossing rings, which `meshvol area` also does). Prints one JSON
object (area, perimeter, centroid, valid, kernel_s: the calls after parsing).
"""
import json
import sys
import time

import numpy as np
import shapely

mode, path = sys.argv[1], sys.argv[2]
with open(path) as fh:
    text = fh.read()
if path.endswith((".geojson", ".json")):
    geoms = shapely.get_parts(shapely.from_geojson(text))
else:
    geoms = shapely.from_wkt(np.array([ln for ln in text.splitlines() if ln.strip()]))
t0 = time.perf_counter()
areas = shapely.area(geoms)
perimeter = float(shapely.length(geoms).sum())
cent = shapely.get_coordinates(shapely.centroid(geoms))
area = float(areas.sum())
centroid = (areas[:, None] * cent).sum(axis=0) / area
valid = bool(shapely.is_valid(geoms).all()) if mode == "shapely-valid" else None
kernel = time.perf_counter() - t0
print(json.dumps({"area": area, "perimeter": perimeter, "centroid": centroid.tolist(),
                  "valid": valid, "polygons": int(len(geoms)), "kernel_s": kernel}))
