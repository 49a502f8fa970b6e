#!/usr/bin/python3
"""Reference flat-punch factors P/(2 E1* a delta) of layered media for
tests/models/test_exact_stack.cpp, by a solution that shares no code or numerics with the
library's: the symbol q = 1 - L from Papkovich-Neuber potentials in mpmath
(tools/stack_reference.py), the kernel F(s) = int_0^30 q(u) cos(u s) du by composite
Gauss-Legendre in u (geometric panels near 0), and the Fredholm equation of the second kind
(docs/theory.md s.4, in units of h1)
    phi(x) - (1/pi) int_0^alpha phi(t) [F(x - t) + F(x + t)] dt = 1,   factor = int phi / alpha
by Nystrom on ONE Gauss-Legendre rule over [0, alpha] (the library uses panels, Chebyshev
tables, an asymptotic tail and Cholesky). The difference between n = 48 and n = 64 nodes is
written as the reference's own error.

Writes data/stack/flat_punch_reference.csv. Run: /usr/bin/python3 tools/stack_flat_punch_reference.py
(about a minute; needs numpy and mpmath).
"""
import os
import numpy as np
import mpmath as mp
from stack_reference import pn_L

# name: (layers top first [(E, nu, h)], base)
CASES = {
    "three_frictionless": ([(1.0, 0.3, 1.0), (20.0, 0.5, 0.5), (0.1, 0.45, 2.0)], "frictionless"),
    "three_bonded": ([(1.0, 0.45, 1.0), (0.2, 0.3, 2.0), (5.0, 0.49, 1.0)], "bonded"),
    "layer_on_stiffer_half_space": ([(1.0, 0.4, 1.0)], (10.0, 0.3)),
    "stiff_layer_on_soft_half_space": ([(10.0, 0.3, 1.0)], (1.0, 0.45)),
}
ALPHAS = [1.0, 4.0]


def gauss_panels(edges, p):
    """A p-point Gauss-Legendre rule on each panel [edges[k], edges[k + 1]]: nodes and weights."""
    x, w = np.polynomial.legendre.leggauss(p)
    U, W = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        U.append(0.5 * (b - a) * x + 0.5 * (a + b))
        W.append(0.5 * (b - a) * w)
    return np.concatenate(U), np.concatenate(W)


def u_rule(u_max=30.0, width=0.25, p=24):
    edges = [0.0] + list(np.geomspace(1e-4, 1.0, 17)) + list(np.arange(1.0 + width, u_max + 1e-9, width))
    return gauss_panels(edges, p)


def factor(u, wq, alpha, n):
    x, w = np.polynomial.legendre.leggauss(n)
    t = 0.5 * alpha * (x + 1)
    wt = 0.5 * alpha * w

    def F(s):
        return (np.cos(np.outer(s.ravel(), u)) @ wq).reshape(s.shape)

    K = (F(t[:, None] - t[None, :]) + F(t[:, None] + t[None, :])) * wt[None, :] / np.pi
    phi = np.linalg.solve(np.eye(n) - K, np.ones(n))
    return wt @ phi / alpha


def main():
    u, w = u_rule()
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "stack", "flat_punch_reference.csv")
    lines = ["# flat-punch factor P/(2 E1* a delta) at a/h1 by Nystrom on the Papkovich-Neuber symbol "
             "(tools/stack_flat_punch_reference.py); error = |n 64 - n 48|",
             "case,a_over_h1,factor,error"]
    for name, (layers, base) in CASES.items():
        H = sum(h for (_, _, h) in layers) / layers[0][2]
        q = np.array([float(1 - pn_L(v, layers, base, int(60 + 0.87 * v * H))) for v in u])
        wq = w * q
        for alpha in ALPHAS:
            f64, f48 = factor(u, wq, alpha, 64), factor(u, wq, alpha, 48)
            lines.append(f"{name},{alpha!r},{f64:.15e},{abs(f64 - f48):.1e}")
            print(lines[-1], flush=True)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
