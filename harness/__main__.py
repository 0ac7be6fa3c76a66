"""``python -m harness``: see `harness.cli`.

The BLAS kernels and thread count are pinned before NumPy loads (`harness._blas`), so that
counts reproduce across machines and parallel workers do not oversubscribe the cores.
"""

import sys

from ._blas import pin_blas

pin_blas()

try:
    from .cli import main  # after pin_blas(), before NumPy loads

    status = main()
except KeyboardInterrupt:  # Ctrl-C while pandas & co. still import: one line, not their traceback
    print("interrupted: finished runs are stored; run again to resume", file=sys.stderr)
    status = 130  # cli.EXIT_INTERRUPTED (cli itself may be what was interrupted)
sys.exit(status)
