import pathlib

import pytest

TINY = str(pathlib.Path(__file__).with_name("tiny_suite.py"))


@pytest.fixture
def tiny_file():
    return TINY


MINE = ("import numpy as np\nfrom problems import Problem\n"
        "PROBLEMS = [Problem(name='bowl', x0=[1.0, 2.0], objective=lambda x: float(x @ x),"
        " gradient=lambda x: 2 * x, f_ref=0.0)]\n")


@pytest.fixture
def mine_file(tmp_path):
    """A user's suite file defining PROBLEMS only (no SOLVERS, no tables)."""
    f = tmp_path / "mine.py"
    f.write_text(MINE)
    return f


@pytest.fixture
def builtin_solvers_only():
    """The solver registry as a fresh process has it: the solvers other tests registered in
    this process (bad_solvers.py's, one of which never returns) are taken out for the test
    and put back after it."""
    from solvers import get_solver_class, register, solver_names, unregister
    from solvers._registry import REGISTRY

    user = [get_solver_class(n) for n in solver_names() if not REGISTRY.is_builtin(n)]
    for cls in user:
        unregister(cls.name)
    yield
    for cls in user:
        register(cls)


@pytest.fixture
def cli_error(capsys):
    """``cli_error(argv, code=2)``: run the CLI on ``argv``, check it exits ``code`` with a message
    and no traceback, and return the message's last line."""
    from harness.cli import main

    def run(argv, code=2):
        got = main(argv)
        err = capsys.readouterr().err.strip().splitlines()
        assert got == code, err
        assert err and "Traceback" not in "\n".join(err)
        return err[-1]

    return run
