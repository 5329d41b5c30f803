"""tests/c/golden_values.h is exactly what the independent reference computes."""

import contextlib
import io
from pathlib import Path

import make_golden


def test_golden_header_matches_reference():
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        make_golden.main()
    committed = (Path(__file__).parent.parent / "c" / "golden_values.h").read_text()
    assert buf.getvalue() == committed
