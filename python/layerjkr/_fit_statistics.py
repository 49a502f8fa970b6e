"""Goodness of fit under lmfit's names, for comparing models of one curve (issue 42)."""
from __future__ import annotations

import math
from typing import Any, Dict

#: The library's fields behind the statistics (read with the rest of a FitResult's fields).
STATISTICS_FIELDS = ("samples_fitted", "chi_square", "reduced_chi_square", "aic", "bic", "function_evaluations")


def statistics_dict(fields: Dict[str, Any]) -> Dict[str, Any]:
    """The ``statistics`` object of ``layerjkr fit --out``'s JSON (NaN as None)."""
    out: Dict[str, Any] = {"samples_fitted": int(fields["samples_fitted"])}
    for key in STATISTICS_FIELDS[1:-1]:
        out[key] = fields[key] if math.isfinite(fields[key]) else None
    out["function_evaluations"] = int(fields["function_evaluations"])
    return out


class FitStatistics:
    """lmfit's goodness-of-fit attributes, from the unweighted force residuals r of the fitted
    samples: ``chisqr`` = sum r^2 [N^2], ``redchi`` = chisqr / (ndata - nvarys) [N^2], ``aic`` =
    ndata ln(chisqr / ndata) + 2 nvarys, ``bic`` = ndata ln(chisqr / ndata) + nvarys ln(ndata).
    Compare AIC and BIC only between fits of the same samples (lower is better); NaN where ndata
    <= nvarys."""

    __slots__ = ()

    def _field(self, name: str) -> Any:  # supplied by FitResult
        raise NotImplementedError

    @property
    def rms_residual(self) -> float:
        """Root-mean-square force residual [N] over the fitted samples."""
        return float(self._field("rms_residual"))

    @property
    def ndata(self) -> int:
        """The samples the fit minimised (weight > 0)."""
        return int(self._field("samples_fitted"))

    @property
    def nfev(self) -> int:
        """Evaluations of the residuals (with or without the Jacobian) the solves made, as Ceres
        counts them."""
        return int(self._field("function_evaluations"))

    @property
    def nvarys(self) -> int:
        """The free parameters."""
        return len(self.parameters)  # type: ignore[attr-defined]

    @property
    def chisqr(self) -> float:
        """Sum of the squared force residuals over the fitted samples [N^2]."""
        return float(self._field("chi_square"))

    @property
    def redchi(self) -> float:
        """chisqr / (ndata - nvarys) [N^2]."""
        return float(self._field("reduced_chi_square"))

    @property
    def aic(self) -> float:
        """Akaike's information criterion, ndata ln(chisqr / ndata) + 2 nvarys."""
        return float(self._field("aic"))

    @property
    def bic(self) -> float:
        """Bayesian information criterion, ndata ln(chisqr / ndata) + nvarys ln(ndata)."""
        return float(self._field("bic"))
