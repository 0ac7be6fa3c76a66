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
