"""Times bumpsim.simulate (the Python package) on a 1e6-sample force from
numpy: the same model, force and calls as the criterion benchmark
`simulate/3dof_response_from_times/1000000` of bumpsim-core
(crates/bumpsim-core/benches/simulation.rs), so the two times compare the
binding's cost (argument conversion, one copy in, numpy arrays out) with the
Rust API. Results: docs/benchmarks.md, "Python package (issue 18)".

Run (after `pip install ./crates/bumpsim-py`):  python bench/python_simulate_timing.py
"""

import statistics
import time

import numpy as np

import bumpsim

SAMPLES = 1_000_000
REPEATS = 15

car = bumpsim.Car([150.0, 250.0, 350.0], [2e3, 2e3], [5e5, 5e5])
t = np.arange(SAMPLES) * 1e-4
force = 4e4 * np.maximum(np.sin(np.arange(SAMPLES) * 0.005), 0.0)

bumpsim.simulate(car, t, force)  # warm up (page faults, allocator)
times = []
for _ in range(REPEATS):
    start = time.perf_counter()
    response = bumpsim.simulate(car, t, force)
    times.append(time.perf_counter() - start)
    del response
print(
    f"bumpsim.simulate, 3 DOF, {SAMPLES} samples from numpy: median "
    f"{statistics.median(times) * 1e3:.1f} ms, min {min(times) * 1e3:.1f} ms "
    f"over {REPEATS} runs (numpy {np.__version__})"
)
