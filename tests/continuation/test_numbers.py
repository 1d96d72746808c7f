"""The numbers namespaces: floats as math, balls only when python-flint is there."""

import math
import subprocess
import sys

import pytest

from continuation.numbers import FLOATS, Jet, balls, jets, require_flint


def test_floats_are_math_with_nan_outside_the_domain():
    assert FLOATS.sin is math.sin and FLOATS.cos is math.cos and FLOATS.pi == math.pi
    assert math.isnan(FLOATS.sqrt(-1e-300)) and FLOATS.sqrt(4.0) == 2.0
    assert FLOATS.sinc(0.0) == 1.0 and FLOATS.sinc(1.0) == math.sin(1.0)
    assert FLOATS.analytic_error(None, ()) == 0.0 and not FLOATS.rigorous


def test_float_jets_differentiate():
    m = jets(FLOATS)
    y = m.cos(Jet(0.3, 1.0)) * 2.0
    assert y.v == 2.0 * math.cos(0.3) and y.d == -2.0 * math.sin(0.3) and y.dd is None


def test_without_python_flint_certification_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "flint", None)  # import flint now fails
    balls.cache_clear()
    try:
        with pytest.raises(ImportError, match=r"groove-continuation\[certify\]"):
            require_flint()
        with pytest.raises(ImportError, match="python-flint"):
            balls()
    finally:
        balls.cache_clear()


def test_the_package_imports_and_traces_without_python_flint():
    code = ("import sys; sys.modules['flint'] = None\n"
            "import continuation, groove_model\n"
            "from groove_model import trace_boundaries\n"
            "assert trace_boundaries(1.0).ok\n"
            "try:\n"
            "    trace_boundaries(1.0, certify=True)\n"
            "except ImportError as exc:\n"
            "    assert '[certify]' in str(exc)\n"
            "else:\n"
            "    raise AssertionError('no ImportError')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
