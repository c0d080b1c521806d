"""Would a coarse-to-fine single start be cheaper? A prototype.

The same bounded LM as `crates/bumpsim-ident/src/lm.rs` (through
lm_geodesic.py, plain step) on the peer benchmark's 3-DOF problem
(scipy_identify.py: three synthetic pendulum cases, 500 samples at 5 kHz)
from bumpsim's default start, run first on the data decimated by q (every
q-th displacement sample; the force averaged over each block of q samples
and held over q steps by the same exact zoh model), then on the full data
from the coarse optimum. A coarse iteration costs about 1/q of a full
one in the sample loop (bumpsim's per-iteration eigen-decomposition does
not shrink); the question is whether the coarse and fine iterations
together cost less than the 76 full ones.

Usage: python3 bench/peers/lm_coarse.py [path/to/bumpsim]
(the binary reports its default start; default target/release/bumpsim).
About two minutes.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lm_geodesic as lm  # noqa: E402
import scipy_identify as peer  # noqa: E402


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/bumpsim"
    data = peer.cases()
    start, iterations, objective = lm.default_start(binary, data)
    print(f"bumpsim identify from its default start: {iterations} iterations, objective {objective:.6e} m^2")
    print("q | coarse iterations | fine iterations after | full-iteration equivalents (sample loop) | final objective m^2")
    for q in (1, 2, 4, 5):
        coarse = [(t[::q], f.reshape(-1, q).mean(axis=1), x[::q]) for t, f, x in data]
        lm.STEP = peer.STEP * q
        its_coarse, _, _, _, p = lm.minimise(coarse, start.copy())
        lm.STEP = peer.STEP
        its_fine, _, cost, _, _ = lm.minimise(data, p.copy())
        cost_units = its_coarse / q + its_fine
        print(f"{q} | {its_coarse} | {its_fine} | {cost_units:.1f} | {cost:.6e}")


if __name__ == "__main__":
    main()
