"""The thesis's published tables (vendored CSV, see thesis_tables/README.md) and ERRATA.md."""

from __future__ import annotations

from importlib import resources

import pandas as pd

__all__ = ["thesis_table", "reference_path"]


def reference_path(name: str):
    """Path-like to a vendored reference file, e.g. ``thesis_tables/table_3_1_dynamic_q_vs_sqp.csv``."""
    return resources.files(__package__).joinpath(name)


def thesis_table(stem: str) -> pd.DataFrame:
    """A thesis table as printed (all cells as strings), e.g. ``thesis_table("table_4_9_P_synthesis")``."""
    with reference_path(f"thesis_tables/{stem}.csv").open("r", encoding="utf-8") as fh:
        return pd.read_csv(fh, dtype=str, keep_default_na=False)
