"""Test-session set-up: the same BLAS kernels as the committed results and baselines.

OpenBLAS's kernels differ by CPU and rounding-sensitive runs (Wood, Manevich) change their
counts with them (harness/_blas.py); pinning them before NumPy loads keeps the baseline
and thesis-count tests about the code, not about the machine.
"""

from harness._blas import pin_blas

pin_blas(threads=False)
