"""A Hertz fit with the contact point given, from Python: layerjkr.fit against scipy's
least_squares on the same arrays, interleaved in one process (issue 40's per-curve target:
layerjkr >= 3x faster). Prints a Markdown table of medians.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/fit_vs_scipy.py [REPEATS]

The curve: an approach of 500 samples, 100 before contact, a 20 nm paraboloid on a 2 kPa
half-space (nu 0.5) to 1 um, 5 pN of force noise, the data shifted so that the contact point is
0 and the baseline 0 (what "given" means): E is the only free parameter, from a start 3x high.
scipy minimises the same residuals, (P_Hertz(E; delta) - P) / noise, with its defaults
(trust-region reflective, a two-point Jacobian) from the same start; both must agree to 1e-6.
"""
import statistics
import sys
import time

import numpy as np
from scipy.optimize import least_squares

import layerjkr

R, NU, E_TRUE = 20e-9, 0.5, 2e3


def hertz(E, delta):
    d = np.clip(delta, 0.0, None)
    return 4.0 / 3.0 * E / (1.0 - NU * NU) * np.sqrt(R) * d ** 1.5


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    rng = np.random.default_rng(7)
    delta = np.linspace(-0.25e-6, 1e-6, 500)
    P = hertz(E_TRUE, delta) + 5e-12 * rng.standard_normal(delta.size)
    scene = layerjkr.scene({"indenter": {"shape": "paraboloid", "R": R},
                            "medium": {"type": "half_space", "E": 3 * E_TRUE, "nu": NU}})
    segment = np.zeros(delta.size, dtype=int)

    def ours():
        return layerjkr.fit(delta, P, scene, free="E", segment=segment).values["E"]

    def theirs():
        # Residuals in units of the noise, as a careful user writes them: in newtons (1e-11)
        # scipy's tolerances stop it at the start.
        return least_squares(lambda x: (hertz(x[0], delta) - P) / 5e-12, [3 * E_TRUE]).x[0]

    E_ours, E_theirs = ours(), theirs()
    if abs(E_ours / E_theirs - 1.0) > 1e-6:
        raise SystemExit("the fits disagree: layerjkr %r, scipy %r" % (E_ours, E_theirs))
    times = {"layerjkr": [], "scipy": []}
    for _ in range(repeats):  # interleaved, so that the machine's load falls on both alike
        for name, f in (("layerjkr", ours), ("scipy", theirs)):
            t0 = time.perf_counter()
            f()
            times[name].append(time.perf_counter() - t0)
    ours_ms = 1e3 * statistics.median(times["layerjkr"])
    theirs_ms = 1e3 * statistics.median(times["scipy"])
    print("| fit (Hertz, E free, contact point given; 500 samples) | median ms | E [Pa] |")
    print("|---|---:|---:|")
    print("| layerjkr.fit | %.3f | %.6g |" % (ours_ms, E_ours))
    print("| scipy.optimize.least_squares | %.3f | %.6g |" % (theirs_ms, E_theirs))
    print("| ratio scipy / layerjkr | %.2f | |" % (theirs_ms / ours_ms))


if __name__ == "__main__":
    main()
