#!/usr/bin/python3
"""Peer for bench/poisson_bench.cpp: scipy.stats.qmc.PoissonDisk (Debian's python3-scipy).

Usage: scipy_poisson.py [POINTS] [SEED]  (default 100000 points)
Prints one JSON line: points, seconds, points_per_second, rho, mean_nn (both over the
hexagonal spacing sqrt(2 A / (sqrt(3) N))), nn_spread (std / mean of NN distances).
"""
import json
import math
import sys
import time

import numpy as np
from scipy.spatial import cKDTree
from scipy.stats import qmc


def main():
    target = int(sys.argv[1]) if len(sys.argv) > 1 else 100000
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    # PoissonDisk fills the unit square up to saturation for a given radius; a maximal Poisson
    # disk set holds about 0.7 / r^2 points per unit area, so pick r for ~target points.
    radius = math.sqrt(0.7 / target)
    engine = qmc.PoissonDisk(d=2, radius=radius, seed=seed)
    start = time.perf_counter()
    points = engine.fill_space()
    seconds = time.perf_counter() - start
    n = len(points)
    dist, _ = cKDTree(points).query(points, k=2)
    nn = dist[:, 1]
    spacing = math.sqrt(2.0 / (math.sqrt(3.0) * n))
    # NN statistics away from the square's border (as the C++ metrics do).
    border = np.minimum.reduce([points[:, 0], 1 - points[:, 0], points[:, 1], 1 - points[:, 1]])
    inner = nn[nn <= border]
    print(json.dumps({
        "peer": "scipy.stats.qmc.PoissonDisk",
        "points": n,
        "seconds": seconds,
        "points_per_second": n / seconds,
        "rho": float(nn.min() / spacing),
        "mean_nn": float(inner.mean() / spacing),
        "nn_spread": float(inner.std() / inner.mean()),
    }))


if __name__ == "__main__":
    main()
