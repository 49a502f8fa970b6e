#!/usr/bin/python3
"""What this teaches: the notebook workflow in plain Python - load a force curve, fit it with
layerjkr, plot data, fit and residuals with matplotlib, print the report. Paste it into Jupyter
cell by cell.

How the data was made: data/curves/hydrogel_film_two_term.csv is synthetic (tools/
make_sample_curve.cpp): a 10 um colloidal probe on a 200 nm bonded hydrogel film, E = 50 kPa,
w = 1 mJ/m^2, approach and retract with 200 pN force noise, contact point delta0 = 2.5 um.

Run: PYTHONPATH=build/python examples/python/fit_and_plot.py [PLOT.png]
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # in Jupyter, drop this line to see the figure inline
import matplotlib.pyplot as plt
import numpy as np

import layerjkr

ROOT = pathlib.Path(__file__).resolve().parents[2]


def load_curve(path):
    """delta [m], P [N], segment (0 approach, 1 retract) from a layerjkr CSV with # comments."""
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=3)
    return data[:, 0], data[:, 1], data[:, 2].astype(int)


def main(plot_path="fit_and_plot.png"):
    delta, P, segment = load_curve(ROOT / "data/curves/hydrogel_film_two_term.csv")
    scene = layerjkr.scene(ROOT / "data/scenes/hydrogel_film_two_term.json")
    result = layerjkr.fit(delta, P, scene, free=["E", "w", "delta0", "P0"], segment=segment, branch="all")
    print(result.report())

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6, 6), gridspec_kw={"height_ratios": [3, 1]})
    nm, nN = 1e9, 1e9
    top.plot(result.delta * nm, result.P * nN, ".", ms=2, color="0.6", label="data")
    # In acquisition order: the approach, then the retract with its jump at pull-off.
    top.plot(result.delta * nm, result.P_fit * nN, "-", color="C3", lw=1, label="fit (%s)" % result.model)
    top.set_ylabel("force P [nN]")
    top.legend()
    bottom.plot(result.delta * nm, result.residuals * nN, ".", ms=2, color="C0")
    bottom.axhline(0, color="k", lw=0.8)
    bottom.set_xlabel("approach delta [nm]")
    bottom.set_ylabel("residual [nN]")
    values, errors = result.values, result.errors  # indexed by parameter name
    top.set_title("E = %.2f +- %.2f kPa, w = %.4g +- %.2g mJ/m^2"
                  % (values["E"] / 1e3, errors["E"] / 1e3, values["w"] * 1e3, errors["w"] * 1e3))
    fig.tight_layout()
    fig.savefig(plot_path, dpi=110)
    print("correlation of E and w: %.3f" % result.correlation["E", "w"])
    print("wrote", plot_path)
    return result


if __name__ == "__main__":
    main(*sys.argv[1:2])
