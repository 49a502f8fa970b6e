"""Stacks of layers from Python (issue 24), through the scene dict only: the paper's Appendix A
bi-layer against its FEM, and a bad stack refused naming the layer and the key."""
import pytest

import layerjkr

APPENDIX_A = {"indenter": {"shape": "sphere", "R": 0.01},
              "medium": {"type": "layers", "base": "bonded",
                         "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-4}, {"E": 3e8, "nu": 0.3, "h": 1.9e-3}]},
              "model": "exact", "w": 0.05}


def test_appendix_a_bilayer_matches_the_papers_fem():
    c = layerjkr.curve(APPENDIX_A, [4e-4])
    assert c.model == "exact"
    assert abs(c.S[0] / 20276.4 - 1) < 1e-3          # the paper's FEM S*
    assert abs(c.delta_H[0] / 8.7702e-6 - 1) < 0.01   # delta*
    assert abs(c.P_H[0] / 0.090009 - 1) < 0.01        # P*


def test_a_bad_stack_names_the_layer_and_the_key():
    bad = {**APPENDIX_A, "medium": {"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-4},
                                                                  {"E": 3e8, "nu": 0.3, "h": 0.0}]}}
    with pytest.raises(layerjkr.InputError, match=r"medium\.layers\[1\]\.h = 0"):
        layerjkr.curve(bad, [4e-4])
