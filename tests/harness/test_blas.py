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


def test_numpy_pin_names_follow_the_installed_numpy(monkeypatch):
    import importlib.metadata as md

    monkeypatch.setattr(md, "version", lambda name: "2.4.6")
    assert _blas.numpy_simd_disable() == "X86_V4 AVX512_ICL AVX512_SPR"
    monkeypatch.setattr(md, "version", lambda name: "1.26.4")
    assert "AVX512_SKX" in _blas.numpy_simd_disable().split()
    assert "X86_V4" not in _blas.numpy_simd_disable().split()


def _dispatched(env: dict[str, str]) -> list[str]:
    """NumPy's dispatch targets in use in a fresh interpreter that pins first, as the harness does."""
    code = ("from harness._blas import pin_blas; pin_blas(); "
            "from numpy._core._multiarray_umath import __cpu_dispatch__ as d, __cpu_features__ as f; "
            "print(' '.join(k for k in d if f.get(k)))")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_numpy_simd_pin_keeps_avx512_machines_on_the_avx2_loops():
    if not _blas._has_avx512():
        pytest.skip("no AVX-512: NumPy's loops are the reference ones already")
    pytest.importorskip("numpy._core._multiarray_umath")  # NumPy >= 2
    env = {k: v for k, v in os.environ.items() if k != "NPY_DISABLE_CPU_FEATURES"}
    pinned = _dispatched(env)
    assert "X86_V4" not in pinned and not any(k.startswith("AVX512") for k in pinned)
    native = _dispatched({**env, "NPY_DISABLE_CPU_FEATURES": ""})  # the user's setting wins
    assert len(native) > len(pinned)


def test_numpy_pin_in_force_for_the_test_session():
    if not _blas._has_avx512():
        pytest.skip("no AVX-512")
    assert os.environ.get("NPY_DISABLE_CPU_FEATURES")


def test_manifest_records_the_pins_and_the_loops_in_use():
    from harness._manifest import environment

    env = environment()
    assert set(env["blas"]) == {"OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", "OPENBLAS_NUM_THREADS"}
    assert env["blas"]["NPY_DISABLE_CPU_FEATURES"] == os.environ.get("NPY_DISABLE_CPU_FEATURES")
    simd = env["machine"]["numpy_simd"]
    if simd is not None and _blas._has_avx512() and os.environ.get("NPY_DISABLE_CPU_FEATURES"):
        assert "X86_V4" not in simd  # the pinned test session runs NumPy's AVX2 loops


def test_a_script_pins_through_the_public_name_as_user_problems_md_shows():
    """docs/user_problems.md: ``import harness; harness.pin_blas()`` before NumPy, in a plain
    interpreter (the pin variables removed from its environment), loads the harness's kernels."""
    if not _blas._has_avx2():
        pytest.skip("no AVX2: OpenBLAS keeps its native kernels")
    code = ("import os, harness; r = harness.pin_blas(); import numpy; "
            "print(r, os.environ['OPENBLAS_CORETYPE'], os.environ['OPENBLAS_NUM_THREADS'])")
    env = {k: v for k, v in os.environ.items() if k not in (*_blas.KERNEL_ENV, *_blas.THREAD_ENV)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.split() == [_blas.REFERENCE_CORETYPE, _blas.REFERENCE_CORETYPE, "1"]
