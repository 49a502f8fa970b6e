"""examples/python/fit_and_plot.py runs, recovers the sample's truth and writes its plot."""
import importlib.util


def test_fit_and_plot(source, tmp_path):
    spec = importlib.util.spec_from_file_location("fit_and_plot", source / "examples/python/fit_and_plot.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    plot = tmp_path / "fit.png"
    result = example.main(str(plot))
    # The sample's truth (tools/make_sample_curve.cpp): E = 50 kPa, w = 1 mJ/m^2.
    assert abs(result.values["E"] - 50e3) < 4 * result.errors["E"]
    assert abs(result.values["w"] - 1e-3) < 4 * result.errors["w"]
    assert plot.stat().st_size > 10000
