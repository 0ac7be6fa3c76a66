"""Pin the numerical kernels so that evaluation counts are the same on every machine.

OpenBLAS chooses its kernels by CPU at load time (``DYNAMIC_ARCH``).  Its AVX-512
(``SkylakeX``) dot products round differently from its AVX2 (``Haswell``) ones, and the
runs that sit at rounding level follow different trajectories: SQSD on Wood's function
(Appendix A, problem 11) needs N^fg = 514 with Haswell kernels and 970 with SkylakeX
ones, Polak-Ribiere on Manevich n = 20 needs 450 against 10545.  So that the committed
results and baselines reproduce on any x86-64 machine with AVX2, the harness and the test
suite load OpenBLAS with ``OPENBLAS_CORETYPE=Haswell`` unless the user has set it (set it
to your CPU's own core type, e.g. ``SkylakeX``, to use the native kernels).  Runs go in
parallel over processes, so each process uses one BLAS thread unless the user says
otherwise (on a loaded machine, multi-threaded BLAS in every worker makes vector
operations of n = 50000 ten times slower).

NumPy's own loops (sums, dot products of small vectors, exp and log ...) are chosen by CPU
too, at import: on an AVX-512 machine NumPy 2.4 dispatches its ``X86_V4`` and
``AVX512_ICL``/``AVX512_SPR`` kernels, whose reductions round differently from the AVX2
(``X86_V3``) ones the committed results were made with.  The manipulator syntheses, whose
objectives are workspace areas differentiated by forward differences, follow the last
digits: re-run on an AVX-512 machine, 10 of the 22 dynamic-q and dynamic-q-plus rows of
rpr2 changed path; with the AVX-512 targets disabled (``NPY_DISABLE_CPU_FEATURES``, read
by NumPy at import) all 11 dynamic-q-plus rows came out bitwise as committed.  So the pin
also disables NumPy's dispatch targets above AVX2 on machines that have them, unless the
user has set ``NPY_DISABLE_CPU_FEATURES`` (set it to an empty string for the native loops).

Must run before NumPy is imported: this module imports nothing numerical.
"""

from __future__ import annotations

import functools
import os
import platform
import sys

__all__ = ["pin_blas", "REFERENCE_CORETYPE", "numpy_simd_disable", "KERNEL_ENV", "THREAD_ENV"]

# the variables the pin sets, in one place: the Dask executor hands them to its workers'
# children and the manifest records them
KERNEL_ENV = ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")
THREAD_ENV = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

REFERENCE_CORETYPE = "Haswell"  # the kernels of the committed results (results/*/manifest.json)
# NumPy's x86 dispatch targets above AVX2 (the committed results: ``numpy_simd`` X86_V3).
# NumPy >= 2.4 groups them by microarchitecture level; earlier releases name each feature
# (NumPy only warns, with an ImportWarning ignored by default, about names it did not build).
_ABOVE_AVX2 = {
    True: "X86_V4 AVX512_ICL AVX512_SPR",
    False: "AVX512F AVX512CD AVX512_KNL AVX512_KNM AVX512_SKX AVX512_CLX AVX512_CNL AVX512_ICL AVX512_SPR",
}


@functools.cache
def _cpu_flags() -> frozenset[str]:
    """The x86-64 CPU's feature flags from /proc/cpuinfo (empty elsewhere)."""
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return frozenset()
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="ignore") as fh:
            for line in fh:
                if line.startswith("flags"):
                    return frozenset(line.split(":", 1)[-1].split())
    except OSError:
        pass
    return frozenset()


def _has_avx2() -> bool:
    return "avx2" in _cpu_flags()


def _has_avx512() -> bool:
    return "avx512f" in _cpu_flags()


def numpy_simd_disable() -> str:
    """The value of ``NPY_DISABLE_CPU_FEATURES`` that keeps the installed NumPy at its AVX2
    loops, by its version (read from the package metadata: NumPy is not imported)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        major, minor = (int(p) for p in version("numpy").split(".")[:2])
    except (PackageNotFoundError, ValueError):
        major, minor = 2, 4
    return _ABOVE_AVX2[(major, minor) >= (2, 4)]


def pin_blas(threads: bool = True) -> str | None:
    """Set ``OPENBLAS_CORETYPE`` (x86-64 with AVX2 only), ``NPY_DISABLE_CPU_FEATURES``
    (x86-64 with AVX-512 only) and, if ``threads``, one BLAS thread per process, unless
    already set.  Returns the core type in force (None: native).  Warns if NumPy is already
    loaded, since OpenBLAS and NumPy then ignore the settings."""
    if threads:
        for var in THREAD_ENV:
            os.environ.setdefault(var, "1")
    loaded = "numpy" in sys.modules  # then OpenBLAS and NumPy have chosen their kernels already
    if "NPY_DISABLE_CPU_FEATURES" not in os.environ and _has_avx512() and not loaded:
        os.environ["NPY_DISABLE_CPU_FEATURES"] = numpy_simd_disable()
    if "OPENBLAS_CORETYPE" not in os.environ and _has_avx2():
        if loaded:
            import warnings

            warnings.warn("pin_blas(): NumPy is already loaded, OpenBLAS and NumPy keep their native kernels; "
                          "counts of rounding-sensitive runs may differ from the committed results",
                          RuntimeWarning, stacklevel=2)
            return None
        os.environ["OPENBLAS_CORETYPE"] = REFERENCE_CORETYPE
    return os.environ.get("OPENBLAS_CORETYPE")
