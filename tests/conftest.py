"""Test-session set-up: the same BLAS kernels as the committed results and baselines.

OpenBLAS's kernels differ by CPU and rounding-sensitive runs (Wood, Manevich) change their
counts with them (harness/_blas.py); pinning them before NumPy loads keeps the baseline
and thesis-count tests about the code, not about the machine.
"""

import os

from harness._blas import pin_blas

pin_blas(threads=False)

# Property tests draw the same examples on every run (the project's rule: same inputs, same
# results; a CI run must not turn red on an example no earlier run drew).  To search afresh,
# as when developing: HYPOTHESIS_PROFILE=explore python -m pytest ...  Imported after the pin,
# like everything that may load NumPy.
from hypothesis import settings  # noqa: E402

settings.register_profile("deterministic", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))
