"""A job's log lines (vcor.io.joblog)."""

import numpy as np

from vcor.io.joblog import brief


def test_brief_rounds_numbers_and_keeps_the_structure():
    settings = {"model": "prony", "lam": 48.69675251658631, "n": np.int64(3), "ok": True, "start": None,
                "smoothing": {"mu": {"E_stor": np.float64(3.1622776601683795)}}, "components": [1.0, 0.25]}
    assert brief(settings) == ("{model: prony, lam: 48.7, n: 3, ok: True, start: None, "
                               "smoothing: {mu: {E_stor: 3.162}}, components: [1, 0.25]}")
    assert brief(1.23456789e-7, digits=3) == "1.23e-07"
