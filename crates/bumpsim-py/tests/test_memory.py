"""Memory: 100 identifications in a loop do not grow resident memory by
more than 10 MB (issue #18): results, cases and numpy arrays handed to
Python are all released."""

import gc

import psutil

import bumpsim

LIMIT = 10 * 1024 * 1024


def test_100_identifications_do_not_grow_resident_memory(root):
    study = root / "examples" / "identify" / "study.toml"
    process = psutil.Process()

    def one():
        result = bumpsim.identify(study, dof=2, starts=2, seed=1)
        predictions = result.predict()
        assert predictions and result.to_json()
        return result.objective

    for _ in range(5):  # warm up: thread pool, allocator arenas, imports
        one()
    gc.collect()
    before = process.memory_info().rss
    objectives = {one() for _ in range(100)}
    gc.collect()
    growth = process.memory_info().rss - before
    assert len(objectives) == 1, "the same seed gives the same result every time"
    assert growth < LIMIT, f"resident memory grew by {growth / 2**20:.1f} MB over 100 identifications"
