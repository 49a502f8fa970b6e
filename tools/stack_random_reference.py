#!/usr/bin/python3
"""Reference flat-punch factors P/(2 E1* a delta) of a seeded random matrix of stacks, for
tests/models/test_stack_matrix.cpp: 2-5 layers whose neighbours' thickness ratios span
1e-3..1e3 and modulus ratios 1e-4..1e4 in any order, nu in [0, 0.5], on bonded, frictionless
or elastic half-space bases - and the hand-picked stacks the issues named.

The method shares nothing with the library's (src/models/stack_symbol.cpp, layer_kernel.cpp,
exact_layer_solver.cpp): the symbol q = 1 - L from Papkovich-Neuber potentials in one global
linear system in mpmath (tools/stack_reference.py's pn_L), the kernel F(s) = int_0^U q(u)
cos(u s) du by composite Gauss-Legendre in u on geometric panels from u = 1e-4 h1/H up to 1
and panels of 0.25 beyond, and the Fredholm equation
    phi(x) - (1/pi) int_0^alpha phi(t) [F(x - t) + F(x + t)] dt = 1,   factor = int phi / alpha
by Nystrom on one Gauss-Legendre rule over [0, alpha] (n = 64; n = 48 and a u-rule of half
the panels give the reference's own error, written beside each value).

A layer deeper than 60 h1 / u cannot reach the surface at that u (its reflection is damped by
e^{-2 u z / h1} < e^{-120}): pn_L is given the stack cut there, the cut layer continued as a
half-space of its own material, so the mpmath precision stays bounded (80 + 0.87 u H_cut
digits) for stacks a million top layers thick.

Writes data/stack/random_matrix_reference.csv: one row per (stack, a/h1) with the stack
spelled as E:nu:h layers joined by '|' and the base ('bonded', 'frictionless' or
'half_space:Es:nus'), all in units of the top layer (E1 = h1 = 1).
Run: /usr/bin/python3 tools/stack_random_reference.py  (a few minutes; needs numpy and mpmath).
"""
import math
import os
import random
import sys

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stack_reference import pn_L  # noqa: E402
from stack_flat_punch_reference import factor, gauss_panels  # noqa: E402

SEED = 20261126
RANDOM_STACKS = 24
ALPHAS = [0.3, 1.0, 4.0]
U_MAX = 40.0

# The issues' hand-picked stacks (units of the top layer: E1 = h1 = 1).
NAMED = {
    # issue 35: 5 um at 2 MPa over 20 um at 20 MPa over 10 um at 0.5 MPa, bonded
    "coating_primer_substrate": ([(1.0, 0.45, 1.0), (10.0, 0.3, 4.0), (0.25, 0.49, 2.0)], "bonded"),
    # issue 35: a 3.7 um layer over a 40 nm layer 36x stiffer, on a softer half-space
    "thin_stiff_interlayer_on_soft_half_space": ([(1.0, 0.45, 1.0), (36.0, 0.3, 0.04 / 3.7)], (0.3, 0.49)),
    # a 100 nm coating on a 10 um film (100x), and 1000x
    "coating_100x": ([(1.0, 0.3, 1.0), (0.05, 0.49, 100.0)], "bonded"),
    "coating_1000x_on_half_space": ([(20.0, 0.3, 1.0), (1.0, 0.5, 1000.0)], (50.0, 0.25)),
}


def random_stack(rng):
    n = rng.randint(2, 5)
    layers = [(1.0, round(rng.uniform(0.0, 0.5), 3), 1.0)]
    for _ in range(n - 1):
        E, _, h = layers[-1]
        layers.append((E * 10 ** rng.uniform(-4, 4), round(rng.choice([0.5, rng.uniform(0.0, 0.5)]), 3),
                       h * 10 ** rng.uniform(-3, 3)))
    kind = rng.choice(["bonded", "frictionless", "half_space"])
    if kind == "half_space":
        return layers, (layers[-1][0] * 10 ** rng.uniform(-4, 4), round(rng.uniform(0.0, 0.5), 3))
    return layers, kind


def cut_stack(layers, base, u):
    """The stack as the surface sees it at u: layers below depth 60/u dropped, the cut layer
    continued as a half-space of its own material."""
    depth_limit = 60.0 / u
    z = 0.0
    for i, (E, nu, h) in enumerate(layers):
        if z + h > depth_limit and i > 0:
            return layers[:i], (E, nu)
        if z + h > depth_limit:  # the top layer itself is deeper than the limit: its half-space
            return [(E, nu, h)], (E, nu)
        z += h
    return layers, base


def q_of(u, layers, base):
    kept, b = cut_stack(layers, base, u)
    H = sum(h for (_, _, h) in kept)
    dps = int(80 + 0.87 * u * H)
    with mp.workdps(dps):
        return float(1 - pn_L(u, kept, b, dps))


def u_rule(H, panels_per_decade, width, p=24):
    u_min = 1e-4 * min(1.0, 1.0 / H)
    decades = math.log10(1.0 / u_min)
    geo = list(np.geomspace(u_min, 1.0, int(math.ceil(decades * panels_per_decade)) + 1))
    edges = [0.0] + geo + list(np.arange(1.0 + width, U_MAX + 1e-9, width))
    return gauss_panels(edges, p)


def spell(layers, base):
    text = "|".join(f"{E!r}:{nu!r}:{h!r}" for (E, nu, h) in layers)
    if isinstance(base, str):
        return text, base
    return text, f"half_space:{base[0]!r}:{base[1]!r}"


def main():
    rng = random.Random(SEED)
    cases = dict(NAMED)
    for k in range(RANDOM_STACKS):
        cases[f"random_{k:02d}"] = random_stack(rng)
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "stack", "random_matrix_reference.csv")
    lines = ["# flat-punch factor P/(2 E1* a delta) of random and named stacks by Nystrom on the Papkovich-Neuber "
             "symbol (tools/stack_random_reference.py, seed %d); error = the larger change with n 48 or half the "
             "u panels" % SEED,
             "case,layers,base,a_over_h1,factor,error"]
    for name, (layers, base) in cases.items():
        H = sum(h for (_, _, h) in layers)
        u, w = u_rule(H, 6, 0.25)
        q = np.array([q_of(v, layers, base) for v in u])
        u2, w2 = u_rule(H, 3, 0.5)
        q2 = np.array([q_of(v, layers, base) for v in u2])
        text, b = spell(layers, base)
        for alpha in ALPHAS:
            f = factor(u, w * q, alpha, 64)
            err = max(abs(f - factor(u, w * q, alpha, 48)), abs(f - factor(u2, w2 * q2, alpha, 64)))
            lines.append(f"{name},{text},{b},{alpha!r},{f:.15e},{err:.1e}")
            print(lines[-1], flush=True)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
