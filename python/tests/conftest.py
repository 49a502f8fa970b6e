"""Paths the binding tests compare against: the CLI built beside the module, the source tree
and the shared data (absent on a clean machine: those tests skip visibly)."""
import os
import pathlib
import warnings

import pytest

SOURCE = pathlib.Path(os.environ.get("LAYERJKR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("LAYERJKR_CLI", str(SOURCE / "build" / "bin" / "layerjkr"))
SHARED = SOURCE.parent / "shared"


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def quiet():
    """Silences warnings for a test (`pytestmark = pytest.mark.usefixtures("quiet")`): where a fit's
    ModelWarnings are part of what it reports, not of what the test checks."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


@pytest.fixture
def cli():
    if not os.path.exists(CLI):
        pytest.skip("the layerjkr CLI is not built at %s" % CLI)
    return CLI


@pytest.fixture
def instrument_dir():
    d = SHARED / "data" / "instrument"
    if not d.is_dir():
        pytest.skip("../shared/data/instrument is absent")
    return d
