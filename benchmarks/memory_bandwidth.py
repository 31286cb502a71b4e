#!/usr/bin/python3
"""One core's memory bandwidth (STREAM-like, numpy, best of 5 on arrays of
400 MB each, far beyond the caches): copy a = b (16 bytes per element
counted: read b, write a), add a = b + c (24), scale in place a *= s (16).
Write-allocate traffic is not counted, as in STREAM. The discrete layer's
explicit loop is compared with this in doc/performance.md ("What limits
it").

usage: benchmarks/memory_bandwidth.py"""
import os
import time

import numpy as np

from bench_common import help_requested

help_requested(__doc__)

n = 50_000_000
a = np.zeros(n)
b = np.ones(n)
c = np.ones(n)
kernels = [("copy", lambda: np.copyto(a, b), 16),
           ("add", lambda: np.add(b, c, out=a), 24),
           ("scale in place", lambda: np.multiply(a, 1.0000001, out=a), 16)]
print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}; "
      f"arrays of {n * 8 / 1e6:.0f} MB, one thread, best of 5")
for name, kernel, bytes_per_element in kernels:
    times = []
    for _ in range(5):
        start = time.perf_counter()
        kernel()
        times.append(time.perf_counter() - start)
    print(f"{name:>15}: {n * bytes_per_element / min(times) / 1e9:6.1f} GB/s")
