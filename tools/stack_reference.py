#!/usr/bin/python3
"""Reference values of a layered medium's surface compliance L(u), u = k h1, for
tests/models/test_stack_symbol.cpp, by a method that shares nothing with the library's
recursion (src/models/stack_symbol.cpp): Papkovich-Neuber potentials
psi, phi = (a e^{-kz} + b e^{kz}) J0(kr) in every layer, global z, all boundary and interface
conditions in one linear system, solved in mpmath at 60 + 0.87 k H digits (the classical
formulation, unstable in double because e^{+kz} grows).

Normalisation: w^ = 2 L(k h1) p^ / (E1* k), E1* of the top layer (L = 1 for its half-space).
Writes data/stack/symbol_reference.csv (case, u, L, q = 1 - L; 17 significant digits).
Run: /usr/bin/python3 tools/stack_reference.py  (about 10 s; needs mpmath).
"""
import os
import mpmath as mp

# name: (layers top first [(E, nu, h)], base 'bonded' | 'frictionless' | (Es, nus))
CASES = {
    "one_bonded_incompressible": ([(1.0, 0.5, 1.0)], "bonded"),
    "appendix_a_bilayer": ([(3e6, 0.3, 0.1e-3), (300e6, 0.3, 1.9e-3)], "bonded"),
    "three_frictionless": ([(1.0, 0.3, 1.0), (20.0, 0.5, 0.5), (0.1, 0.45, 2.0)], "frictionless"),
    "three_bonded_incompressible": ([(1.0, 0.5, 1.0), (5.0, 0.5, 0.5), (0.3, 0.5, 2.0)], "bonded"),
    "stiff_film_on_half_space": ([(100.0, 0.3, 1.0), (2.0, 0.5, 0.7)], (1.0, 0.49)),
    "soft_film_on_half_space": ([(0.05, 0.5, 1.0), (2.0, 0.2, 3.0)], (1.0, 0.5)),
    "layer_on_stiffer_half_space": ([(1.0, 0.4, 1.0)], (10.0, 0.3)),
}
U_VALUES = [1e-6, 1e-4, 1e-2, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 15.0, 24.0]


def pn_L(u, layers, base, dps):
    with mp.workdps(dps):
        E1, nu1, h1 = [mp.mpf(v) for v in layers[0]]
        k = mp.mpf(u) / h1
        mats = [(mp.mpf(E) / (2 * (1 + mp.mpf(nu))), mp.mpf(nu)) for (E, nu, h) in layers]
        zs = [mp.mpf(0)]
        for (_, _, h) in layers:
            zs.append(zs[-1] + mp.mpf(h))

        def rows(mu, nu, z):
            # (U, W, T, S) at depth z for the coefficients (a, b, c, d) of
            # Psi = a e^{-kz} + b e^{kz}, Phi = c e^{-kz} + d e^{kz};
            # 2 mu u = (kappa + 1) psi e_z - grad(z psi + phi)
            kappa = 3 - 4 * nu
            R = mp.zeros(4, 4)
            for j, (sign, which) in enumerate([(-1, "psi"), (1, "psi"), (-1, "phi"), (1, "phi")]):
                f = mp.exp(sign * k * z)
                fp, fpp = sign * k * f, k * k * f
                if which == "psi":
                    vals = (k * z * f / (2 * mu), (kappa * f - z * fp) / (2 * mu),
                            -k * ((1 - 2 * nu) * f - z * fp), 2 * (1 - nu) * fp - z * fpp)
                else:
                    vals = (k * f / (2 * mu), -fp / (2 * mu), k * fp, -fpp)
                for i in range(4):
                    R[i, j] = vals[i]
            return R

        n = len(layers)
        half_space = not isinstance(base, str)
        size = 4 * n + (2 if half_space else 0)
        A = mp.zeros(size, size)
        rhs = mp.zeros(size, 1)
        top = rows(mats[0][0], mats[0][1], zs[0])
        for j in range(4):
            A[0, j], A[1, j] = top[2, j], top[3, j]   # T(0) = 0, S(0) = -1
        rhs[1] = -1
        r = 2
        for i in range(n - 1):
            Ra = rows(mats[i][0], mats[i][1], zs[i + 1])
            Rb = rows(mats[i + 1][0], mats[i + 1][1], zs[i + 1])
            for q in range(4):
                for j in range(4):
                    A[r + q, 4 * i + j] = Ra[q, j]
                    A[r + q, 4 * (i + 1) + j] = -Rb[q, j]
            r += 4
        Rl = rows(mats[-1][0], mats[-1][1], zs[-1])
        c0 = 4 * (n - 1)
        if base == "bonded":
            for j in range(4):
                A[r, c0 + j], A[r + 1, c0 + j] = Rl[0, j], Rl[1, j]
        elif base == "frictionless":
            for j in range(4):
                A[r, c0 + j], A[r + 1, c0 + j] = Rl[2, j], Rl[1, j]
        else:
            Es, nus = mp.mpf(base[0]), mp.mpf(base[1])
            Rs = rows(Es / (2 * (1 + nus)), nus, zs[-1])
            for q in range(4):
                for j in range(4):
                    A[r + q, c0 + j] = Rl[q, j]
                A[r + q, 4 * n] = -Rs[q, 0]       # decaying terms only: a, c
                A[r + q, 4 * n + 1] = -Rs[q, 2]
        sol = mp.lu_solve(A, rhs)
        W0 = sum(top[1, j] * sol[j] for j in range(4))
        return E1 / (1 - nu1 ** 2) * k * W0 / 2


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "stack", "symbol_reference.csv")
    lines = ["# L(u) of layered media by Papkovich-Neuber potentials in mpmath (tools/stack_reference.py)",
             "case,u,L,q"]
    for name, (layers, base) in CASES.items():
        H = sum(h for (_, _, h) in layers) / layers[0][2]
        for u in U_VALUES:
            dps = int(80 + 0.87 * u * H)
            with mp.workdps(dps):
                L = pn_L(u, layers, base, dps)
                q = 1 - L
                lines.append(f"{name},{u!r},{mp.nstr(L, 17, min_fixed=-1, max_fixed=1)},{mp.nstr(q, 17, min_fixed=-1, max_fixed=1)}")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out}: {len(lines) - 2} rows")


if __name__ == "__main__":
    main()
