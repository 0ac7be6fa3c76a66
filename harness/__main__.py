"""``python -m harness``: see `harness.cli`.

The BLAS kernels and thread count are pinned before NumPy loads (`harness._blas`), so that
counts reproduce across machines and parallel workers do not oversubscribe the cores.
"""

import sys

from ._blas import pin_blas

pin_blas()

from .cli import main  # noqa: E402 - after pin_blas(), before NumPy loads

sys.exit(main())
