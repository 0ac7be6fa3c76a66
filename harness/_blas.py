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

Must run before NumPy is imported: this module imports nothing numerical.
"""

from __future__ import annotations

import os
import platform
import sys

__all__ = ["pin_blas", "REFERENCE_CORETYPE"]

REFERENCE_CORETYPE = "Haswell"  # the kernels of the committed results (results/*/manifest.json)


def _has_avx2() -> bool:
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return False
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="ignore") as fh:
            for line in fh:
                if line.startswith("flags"):
                    return " avx2 " in f" {line.split(':', 1)[-1].strip()} "
    except OSError:
        pass
    return False


def pin_blas(threads: bool = True) -> str | None:
    """Set ``OPENBLAS_CORETYPE`` (x86-64 with AVX2 only) and, if ``threads``, one BLAS
    thread per process, unless already set.  Returns the core type in force (None: native).
    Warns if NumPy is already loaded, since OpenBLAS then ignores the setting."""
    if threads:
        for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            os.environ.setdefault(var, "1")
    if "OPENBLAS_CORETYPE" not in os.environ and _has_avx2():
        if "numpy" in sys.modules:
            import warnings

            warnings.warn("pin_blas(): NumPy is already loaded, OpenBLAS keeps its native kernels; "
                          "counts of rounding-sensitive runs may differ from the committed results",
                          RuntimeWarning, stacklevel=2)
            return None
        os.environ["OPENBLAS_CORETYPE"] = REFERENCE_CORETYPE
    return os.environ.get("OPENBLAS_CORETYPE")
