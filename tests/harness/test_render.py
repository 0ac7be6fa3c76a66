"""Table renderers: flagged cells are marked in every format, notes follow the table."""

import pandas as pd

from harness.tables import MARK, Table, to_csv, to_html, to_latex, to_markdown, write_tables


def table():
    frame = pd.DataFrame({"N^fg": [12, 97], "N^fg thesis": [12, 113]}, index=pd.Index(["a01", "a09"], name="Prob."))
    flags = pd.DataFrame({"N^fg": [False, True], "N^fg thesis": [False, False]}, index=frame.index)
    return Table(name="t", title="Table 2.1 & more_stuff", frame=frame, flags=flags, notes=["tolerance ±15%"])


def test_markdown_marks_flags_and_prints_notes():
    md = to_markdown(table())
    assert "| Prob. | N^fg | N^fg thesis |" in md
    assert f"| a09 | 97 {MARK} | 113 |" in md and "| a01 | 12 | 12 |" in md
    assert "- tolerance ±15%" in md and f"{MARK} marks a cell" in md


def test_latex_csv_html():
    tex = to_latex(table())
    assert r"\textbf{97}$^\dagger$" in tex and r"Table 2.1 \& more\_stuff" in tex and r"\toprule" in tex
    assert "97 ⚑" in to_csv(table())
    html = to_html(table())
    assert '<td class="flag">97 ⚑</td>' in html and "Table 2.1 &amp; more_stuff" in html


def test_unflagged_table_has_no_mark_note(tmp_path):
    t = table()
    t.flags = None
    assert MARK not in to_markdown(t)
    paths = write_tables([t], tmp_path)
    assert sorted(p.name for p in paths) == ["t.csv", "t.md", "t.tex"]
