"""Tables: the `Table` type, per-suite plug-ins (``harness.tables.<suite>``) and renderers."""

from ._base import Table as Table
from ._render import MARK as MARK
from ._render import NoTablePlugin as NoTablePlugin
from ._render import build_tables as build_tables
from ._render import to_csv as to_csv
from ._render import to_html as to_html
from ._render import to_latex as to_latex
from ._render import to_markdown as to_markdown
from ._render import write_tables as write_tables
