#!/usr/bin/env python3
"""The pose loop of issue 27: two 10k-triangle spheres read from files, their overlap
over N random overlapping rigid poses (default 1,000), through the Python API.

    cargo run --release -p meshvol-io --example sphere -- 10000 /tmp/a.stl
    python bench/poses/run.py /tmp/a.stl [--poses 1000] [--runs 3]

B is the same file, placed by each pose: a uniformly random rotation and a shift uniform
in the ball of radius 1.5 radii, so the spheres always overlap. Timed, each the best of
R runs:

- a plain loop of meshvol.intersection(a, b, pose_b=pose), one pose at a time (the
  median per pose, and the quartiles);
- meshvol.intersections(a, b, poses_b=poses), all poses in one call, in parallel (the
  call's seconds divided by N).

Both give the whole report (interval, moments, contact), and the script checks that
they agree bit for bit. Set RAYON_NUM_THREADS (and taskset) for the cores: the issue's
figure is on 2. Needs meshvol built in release (`maturin develop --release` in
crates/meshvol-py), numpy.
"""

import argparse
import os
import time

import numpy as np

import meshvol


def random_poses(count, radius, seed=27):
    """`count` 4×4 rigid transforms: Shoemake's uniform rotation, a shift in the ball."""
    rng = np.random.default_rng(seed)
    poses = np.repeat(np.eye(4)[None], count, axis=0)
    for pose in poses:
        u1, u2, u3 = rng.random(3)
        a, b = np.sqrt(1.0 - u1), np.sqrt(u1)
        w, x = a * np.sin(2 * np.pi * u2), a * np.cos(2 * np.pi * u2)
        y, z = b * np.sin(2 * np.pi * u3), b * np.cos(2 * np.pi * u3)
        pose[:3, :3] = [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
        while True:
            shift = rng.uniform(-1.0, 1.0, 3)
            if shift @ shift <= 1.0:
                break
        pose[:3, 3] = 1.5 * radius * shift
    return poses


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", help="a sphere STL (the sphere example's)")
    parser.add_argument("--poses", type=int, default=1000)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    a = meshvol.load(args.mesh)
    b = meshvol.load(args.mesh)
    vertices = np.asarray(a.vertices)
    radius = 0.5 * (vertices[:, 0].max() - vertices[:, 0].min())
    poses = random_poses(args.poses, radius)
    meshvol.intersection(a, b)  # each Mesh checks itself once, here

    loop, batch = [], []
    for _ in range(args.runs):
        seconds, singles = [], []
        for pose in poses:
            start = time.perf_counter()
            singles.append(meshvol.intersection(a, b, pose_b=pose))
            seconds.append(time.perf_counter() - start)
        loop.append(np.array(seconds))
        start = time.perf_counter()
        many = meshvol.intersections(a, b, poses_b=poses)
        batch.append(time.perf_counter() - start)
        assert [r.to_dict() | {"seconds": 0} for r in many] == [
            r.to_dict() | {"seconds": 0} for r in singles
        ], "the batch differs from the loop"
    best = min(loop, key=np.median)
    q1, median, q3 = np.percentile(best, [25, 50, 75]) * 1e3
    threads = os.environ.get("RAYON_NUM_THREADS", "all")
    print(f"{args.mesh}: {a.face_count} triangles each, {args.poses} random overlapping poses,"
          f" RAYON_NUM_THREADS={threads}, best of {args.runs} runs")
    print(f"  loop of meshvol.intersection: median {median:.2f} ms per pose"
          f" (quartiles {q1:.2f}, {q3:.2f} ms)")
    print(f"  meshvol.intersections (batch): {min(batch) / args.poses * 1e3:.2f} ms per pose")


if __name__ == "__main__":
    main()
