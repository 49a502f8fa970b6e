#!/usr/bin/python3
"""Reference Maugis-Dugdale half-space pull-off and fixed-grips points for
tests/adhesion/test_maugis_half_space.cpp, solved in mpmath at 50 digits in a way that shares
nothing with the library (src/adhesion/maugis_equations.hpp, src/adhesion/maugis_dugdale.cpp).

The published equations (Maugis 1992, JCIS 150:243, in Johnson & Greenwood 1997, JCIS 192:326
notation; A = a (K/(pi w R^2))^(1/3), Pbar = P/(pi w R), Deltabar = delta (K^2/(pi^2 w^2 R))^(1/3),
K = 4 E*/3, m = c/a):

  (lambda A^2/2) [sqrt(m^2-1) + (m^2-2) arccos(1/m)]
      + (4 lambda^2 A/3) [sqrt(m^2-1) arccos(1/m) - m + 1] = 1
  Pbar     = A^3 - lambda A^2 [sqrt(m^2-1) + m^2 arccos(1/m)]
  Deltabar = A^2 - (4/3) A lambda sqrt(m^2-1)

The library solves the first equation for m at given A. Here it is read the other way: at
given m it is a quadratic in A, so every point of the curve is explicit in m; the extrema are
the roots of dPbar/dm and dDeltabar/dm (mpmath's numerical derivative at 50 digits), bracketed
on a log grid of m - 1 and refined by mpmath's Anderson-Bjorck root finder. A = 0 is m -> inf
with C = m A finite: lambda pi C^2/4 + (4/3) lambda^2 (pi/2 - 1) C = 1, Pbar = -lambda pi C^2/2.
Load control: the minimum of Pbar over A >= 0, at A = 0 when Pbar(m) has no interior minimum
below Pbar(A = 0). Fixed grips: the interior minimum of Deltabar(A), empty when there is none.

Writes data/adhesion/maugis_pull_off.csv (lambda on a log grid 0.01..100, 33 values, plus
18 more from 1e-4 to 1e4; 17 significant digits) and, as a comment line, the lambda below which
there is no fixed-grips instability.
Run: /usr/bin/python3 tools/maugis_reference.py  (about 1 min; needs mpmath).
"""
import os
import mpmath as mp

mp.mp.dps = 50


def point(lam, m):
    s = mp.sqrt(m * m - 1)
    t = mp.acos(1 / m)
    a2 = lam * (s + (m * m - 2) * t) / 2
    a1 = 4 * lam * lam * (s * t - m + 1) / 3
    A = 2 / (a1 + mp.sqrt(a1 * a1 + 4 * a2))
    P = A ** 3 - lam * A * A * (s + m * m * t)
    D = A * A - 4 * A * lam * s / 3
    return A, P, D


def zero_contact(lam):
    al = lam * mp.pi / 4
    b = 4 * lam * lam * (mp.pi / 2 - 1) / 3
    C = 2 / (b + mp.sqrt(b * b + 4 * al))
    return C, -lam * mp.pi * C * C / 2, -4 * lam * C / 3


def interior_minima(lam, which):
    """Local minima of Pbar (which=1) or Deltabar (which=2) over m in (1, inf), by x = log(m-1)."""
    f = lambda x: point(lam, 1 + mp.exp(x))[which]
    xs = [mp.mpf(-40) + mp.mpf(i) / 8 for i in range(0, 8 * 80 + 1)]  # m - 1 from 4e-18 to 2e17
    vals = [f(x) for x in xs]
    found = []
    for i in range(1, len(xs) - 1):
        if vals[i] < vals[i - 1] and vals[i] <= vals[i + 1]:
            df = lambda x: mp.diff(f, x)
            x = mp.findroot(df, (xs[i - 1], xs[i + 1]), solver="anderson", tol=mp.mpf(10) ** -40)
            found.append(1 + mp.exp(x))
    return found


def row(lam):
    lam = mp.mpf(lam)
    C0, P0, D0 = zero_contact(lam)
    # Load control
    cands = [(point(lam, m)[1], m) for m in interior_minima(lam, 1)]
    best = min(cands, key=lambda c: c[0]) if cands else None
    if best is None or best[0] >= P0:
        lc = (mp.mpf(0), mp.inf, C0, P0, D0)
    else:
        m = best[1]
        A, P, D = point(lam, m)
        lc = (A, m, m * A, P, D)
    # Fixed grips: the interior minimum of Deltabar (there is at most one)
    fm = interior_minima(lam, 2)
    if fm:
        m = fm[0]
        A, P, D = point(lam, m)
        fg = (A, m, m * A, P, D)
    else:
        fg = None
    return lc, fg


def fixed_grips_threshold():
    """The lambda below which Deltabar(A) has no minimum: where (Deltabar(A) - Deltabar(0))/A^2
    at A -> 0 (m = 1e20, 100 digits; m = 1e15 already agrees to 3e-16) changes sign."""
    with mp.workdps(100):
        def curvature(lam):
            A, P, D = point(lam, mp.mpf(10) ** 20)
            return (D - zero_contact(lam)[2]) / A ** 2
        return mp.findroot(curvature, (mp.mpf("0.9"), mp.mpf("1.0")), solver="anderson")


def fmt(x):
    if x is None:
        return "nan"
    if x == mp.inf:
        return "inf"
    return mp.nstr(x, 17, min_fixed=-4, max_fixed=4)


def main():
    lams = [mp.mpf(10) ** (mp.mpf(-2) + mp.mpf(4) * i / 32) for i in range(33)]
    lams += [mp.mpf(v) for v in ("1e-4", "1e-3", "0.3", "0.5", "0.7", "0.9", "0.94", "0.95", "0.97", "1.0",
                                 "1.1", "1.2", "1.5", "2.0", "3.0", "5.0", "1e3", "1e4")]
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "adhesion", "maugis_pull_off.csv")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    lines = [
        "# Maugis-Dugdale half-space, load-control pull-off (lc) and fixed-grips instability (fg), "
        "dimensionless (Johnson-Greenwood 1997): A, m = c/a, C = c in A's units, Pbar, Deltabar; "
        "by tools/maugis_reference.py (mpmath, 50 digits, explicit in m, roots of dPbar/dm and "
        "dDeltabar/dm). lc at A = 0 has m = inf; fg = nan where Deltabar(A) has no minimum.",
        "# fixed-grips threshold lambda = " + mp.nstr(fixed_grips_threshold(), 20),
        "lambda,lc_A,lc_m,lc_C,lc_P,lc_Delta,fg_A,fg_m,fg_C,fg_P,fg_Delta",
    ]
    for lam in sorted(set(lams)):
        lc, fg = row(lam)
        fgv = fg if fg is not None else (None,) * 5
        lines.append(",".join([fmt(lam)] + [fmt(v) for v in lc] + [fmt(v) for v in fgv]))
        print(lines[-1], flush=True)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
