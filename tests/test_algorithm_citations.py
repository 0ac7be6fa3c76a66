"""Every citation of algorithms.md in the code and the docs names a section of docs/algorithms.md."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
SPEC = ROOT / "docs" / "algorithms.md"
# "algorithms.md section 1.2", "algorithms.md 1.3 step 9", "algorithms.md §1.6", "(algorithms.md 4.5)"
CITE = re.compile(r"algorithms\.md\)?\s*(?:section\s+|§\s*)?(\d+(?:\.\d+)?)")


def _sections() -> set[str]:
    heads = re.findall(r"^#{2,4}\s+(\d+(?:\.\d+)?)\.?\s", SPEC.read_text(encoding="utf-8"), flags=re.M)
    return set(heads)


def _citations() -> list[tuple[str, str]]:
    packages = ("solvers", "problems", "manipulators", "harness", "tests")
    files = [p for pkg in packages for p in (ROOT / pkg).rglob("*.py")]
    files += list((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]
    out = []
    for f in files:
        if f == SPEC:
            continue
        for m in CITE.finditer(f.read_text(encoding="utf-8")):
            out.append((f"{f.relative_to(ROOT)}", m.group(1)))
    return out


def test_spec_is_in_the_repository():
    assert SPEC.is_file() and {"1", "1.3", "1.6", "2", "4.5", "5.1"} <= _sections()


def test_every_citation_resolves():
    cites = _citations()
    assert len(cites) >= 20  # the solvers cite the spec throughout
    sections = _sections()
    missing = [f"{f}: algorithms.md {s}" for f, s in cites if s not in sections]
    assert not missing, "\n".join(missing)
