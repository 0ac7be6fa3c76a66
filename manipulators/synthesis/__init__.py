"""Dimensional-synthesis suites (one module per manipulator, each defining ``SUITE``):
``rpr2_suite`` (Chapter 4), ``rpr3_suite`` (Chapter 5), ``tdpm_suite`` (Chapter 6)."""
