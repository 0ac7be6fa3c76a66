import pathlib

import pytest

TINY = str(pathlib.Path(__file__).with_name("tiny_suite.py"))


@pytest.fixture
def tiny_file():
    return TINY
