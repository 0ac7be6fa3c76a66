"""The BLAS kernel pin (harness/_blas.py) that makes counts machine-independent."""

import os
import subprocess
import sys

import pytest

from harness import _blas


def test_pin_is_in_force_for_the_test_session():
    if not _blas._has_avx2():
        pytest.skip("no AVX2: OpenBLAS keeps its native kernels")
    assert os.environ.get("OPENBLAS_CORETYPE")


def test_pin_after_numpy_loaded_warns_and_changes_nothing(monkeypatch):
    import numpy  # noqa: F401  (loaded: too late to pin)

    monkeypatch.delenv("OPENBLAS_CORETYPE", raising=False)
    monkeypatch.setattr(_blas, "_has_avx2", lambda: True)
    with pytest.warns(RuntimeWarning, match="already loaded"):
        assert _blas.pin_blas(threads=False) is None
    assert "OPENBLAS_CORETYPE" not in os.environ


def test_user_setting_wins_and_harness_entry_point_pins_before_numpy():
    code = ("import os, sys; from harness._blas import pin_blas; r = pin_blas(); "
            "import numpy; print(r, os.environ['OPENBLAS_NUM_THREADS'])")
    env = {**os.environ, "OPENBLAS_CORETYPE": "Sandybridge", "OPENBLAS_NUM_THREADS": "3"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["Sandybridge", "3"]
