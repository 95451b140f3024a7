"""Computations release the GIL: other Python threads run meanwhile, and threads measure
in parallel with the answers they would get alone."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import meshvol
from solids import uv_sphere


def test_other_threads_run_while_meshvol_computes():
    # One fixed mesh (65 024 triangles), whatever the machine's speed: its check takes
    # milliseconds in a release build and more in a debug one, many times the ticker's
    # 1 ms sleep either way.
    mesh = meshvol.Mesh(*uv_sphere(rings=128, segments=256))

    done = threading.Event()
    ticks = []

    def ticker():
        while not done.is_set():
            time.sleep(0.001)
            ticks.append(time.perf_counter())

    thread = threading.Thread(target=ticker)
    thread.start()
    time.sleep(0.02)
    started = time.perf_counter()
    mesh.check()
    ended = time.perf_counter()
    done.set()
    thread.join()
    # Holding the GIL would keep the ticker from running at all during the call: no
    # count that depends on how fast the call is, only whether the ticker ran in it.
    during = [t for t in ticks if started < t < ended]
    assert len(during) >= 1, (len(during), ended - started)


def test_threads_measure_in_parallel_with_the_same_answers():
    meshes = [meshvol.Mesh(*uv_sphere(radius=r, rings=16, segments=32)) for r in (1.0, 2.0, 3.0, 4.0)]
    alone = [m.mass_properties().to_dict() for m in meshes]
    checks = [m.check().to_dict() for m in meshes]
    with ThreadPoolExecutor(max_workers=8) as pool:
        together = list(pool.map(lambda m: m.mass_properties().to_dict(), meshes * 4))
        checked = list(pool.map(lambda m: m.check().to_dict(), meshes * 2))
    assert together == alone * 4
    assert checked == checks * 2
    assert np.allclose([d["volume"] for d in alone], [4 / 3 * np.pi * r**3 for r in (1, 2, 3, 4)], rtol=3e-2)
