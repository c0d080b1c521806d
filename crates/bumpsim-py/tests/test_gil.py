"""Long calls release the GIL: Python threads keep running while the
library works."""

import threading

import bumpsim


def test_identification_releases_the_gil(root):
    study = root / "examples" / "identify" / "study.toml"
    done = threading.Event()
    worker = threading.Thread(
        target=lambda: (bumpsim.identify(study, dof=3, starts=32, seed=1), done.set())
    )
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1  # runs only while the worker does not hold the GIL
    worker.join()
    # with the GIL held for the whole identification (~0.3 s and more) this
    # loop would run a handful of times at most
    assert ticks > 10_000, f"the main thread ran {ticks} times during identify"
