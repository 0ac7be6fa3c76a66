"""``python -m harness``: see `harness.cli`.

Runs go in parallel over processes (``--jobs``), so each process uses one BLAS thread
unless the user says otherwise: on a loaded machine, multi-threaded BLAS in every
worker makes vector operations of n = 50000 ten times slower.  Set before NumPy loads.
"""

import os
import sys

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from .cli import main  # noqa: E402

sys.exit(main())
