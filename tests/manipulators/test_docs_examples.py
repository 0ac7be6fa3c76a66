"""The Python examples of the manipulator pages run as written, and print what the page says.

A ```python block followed (after a line of prose at most) by a ```text block must print
exactly that text; a block without one must run without error."""

import contextlib
import io
import pathlib
import re

import pytest

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"
PAGES = ("manipulators.md", "rpr3.md", "cable.md", "spatial.md")
BLOCK = re.compile(r"```python\n(.*?)```\n(?:\n[^\n`]*\n)?\n?(?:```text\n(.*?)```)?", re.S)


def _examples():
    for page in PAGES:
        for k, m in enumerate(BLOCK.finditer((DOCS / page).read_text())):
            yield pytest.param(m.group(1), m.group(2), id=f"{page}-{k + 1}")


@pytest.mark.parametrize("code, expected", list(_examples()))
def test_example_runs_and_prints_what_the_page_says(code, expected):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "<docs example>", "exec"), {"__name__": "__docs__"})
    if expected is not None:
        assert out.getvalue() == expected


def test_the_pages_have_examples_with_printed_output():
    found = list(_examples())
    assert {p.id.split("-")[0] for p in found} == set(PAGES)
    assert sum(p.values[1] is not None for p in found) >= 2
