"""Bad leg limits and positions of the 2-RPR get errors that name them (not NumPy's)."""

import numpy as np
import pytest

from manipulators import RPR2


def test_rpr2_leg_limits_of_the_wrong_length_are_named():
    with pytest.raises(ValueError, match="one per leg"):
        RPR2(-4, -0.1, 4, l_min=(4, 4, 4), l_max=(7, 7))


def test_rpr2_nan_position_is_refused():
    m = RPR2(-4, -0.1, 4, l_min=(4, 4), l_max=(7, 7))
    with pytest.raises(ValueError, match=r"NaN or inf at row\(s\) \[0\]"):
        m.inverse_condition([np.nan, 1.0])
    assert np.isfinite(m.inverse_condition([[0.0, 5.0], [1.0, 5.5]])).all()


# ---------------------------------------------------------------- synthesis problems' arguments
@pytest.mark.parametrize("chord", [0, -0.1, float("nan"), float("inf"), True, "0.1"])
@pytest.mark.parametrize("make", ["o_problem", "e_problem", "p_problem"])
def test_synthesis_problems_refuse_a_bad_chord(make, chord):
    """A chord the method cannot use used to count every design as an empty workspace (a flat
    objective), and chord=0 silently became the thesis's default."""
    from manipulators.synthesis import rpr2_suite

    with pytest.raises(ValueError, match=f"{make}: chord must be a finite length > 0"):
        getattr(rpr2_suite, make)(chord=chord)


def test_synthesis_arguments_name_what_is_valid():
    from manipulators.synthesis import rpr2_suite as r2

    with pytest.raises(ValueError, match=r"unknown start \(Table 4.2\) 'SP9'; valid: SP1, SP2, SP3, SP4"):
        r2.o_problem("SP9")
    with pytest.raises(ValueError, match="unknown prescribed workspace 'P4'; valid: P1, P2, P3"):
        r2.p_problem("P4")
    with pytest.raises(ValueError, match=r"must have shape \(5,\)"):
        r2.o_problem().objective([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"must have shape \(3,\)"):
        r2.evaluate("p", [1.0, 2.0, 3.0, 4.0, 5.0])
    with pytest.raises(ValueError, match="evaluate: chord"):
        r2.evaluate("o", r2.STARTS["SP1"], chord=-1)
    assert r2.o_problem("SP1", "P2").meta["prescribed"] == "P2"  # a name, as p_problem takes
    assert r2.o_problem(chord=0.25).meta["chord"] == 0.25


def test_forward_kinematics_refuses_negative_lengths_and_mismatched_shapes():
    m = RPR2(-5.0, 0.0, 5.0)
    assert np.all(np.isnan(m.forward(-6.0, -6.0)))  # squared, it would be the pose of (6, 6)
    assert np.allclose(m.forward(6.0, 6.0), [0.0, np.sqrt(11.0)])
    with pytest.raises(ValueError, match="do not broadcast"):
        m.forward([5.0, 6.0, 7.0], [5.0, 6.0])
    with pytest.raises(ValueError, match="RPR2: xA must be one number, got 'a'"):
        RPR2("a", 0.0, 5.0)
