"""The input checks' own paths (``kfcourse._validate``): a covariance is judged finite,
symmetric and positive semi-definite on its own scale, and a singular one (a
constant-velocity model's process noise) passes; the error names the argument and what
was expected.  (Each function's bad input is in its subject's file.)
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse import _validate as v
from tests.filters.strategies import I2, I3, INF, NAN

# ================================================================ worked numbers
# none: the checks have no lesson of their own


# ================================================================ closed forms
# none: what passes and what does not is below


# ================================================================ properties
def test_huge_finite_covariances_pass():
    big = 1e200 * np.diag([1.0, 2.0, 3.0])  # its sum of squares would overflow
    assert v.covariance(big, "Sig", 3)[2, 2] == 3e200


def test_semi_definite_and_rounding_asymmetric_covariances_pass():
    assert v.covariance(np.diag([1.0, 0.0]), "Sig", 2)[1, 1] == 0.0
    skewed = np.array([[2.0, 1.0], [1.0 + 1e-12, 2.0]])  # asymmetric by rounding only
    assert v.covariance(skewed, "R", 2)[1, 0] == 1.0 + 1e-12
    with pytest.raises(ValueError, match=r"^R must be a symmetric covariance matrix"):
        v.covariance(np.array([[2.0, 1.0], [1.1, 2.0]]), "R", 2)


def test_a_small_covariance_is_judged_on_its_own_scale():
    Gam = np.array([[0.5], [1.0]])
    assert v.covariance(Gam @ Gam.T, "R", 2)[1, 1] == 1.0  # white-noise acceleration: singular
    assert v.covariance(np.diag([1.0, -1e-10]), "R", 2)[1, 1] == -1e-10  # a negative eigenvalue of rounding size
    with pytest.raises(ValueError, match=r"^R must be positive semi-definite"):  # 1e-4 is no rounding error
        v.covariance(np.diag([1.0, -1e-4]), "R", 2)
    with pytest.raises(ValueError, match=r"^R must be positive semi-definite"):  # judged on R's scale, not Sig's
        kf.kf_step(np.zeros(2), 1e6 * I2, None, [1.0, 2.0], I2, None, I2, np.diag([1.0, -1e-4]), I2)


def test_usual_shapes_and_the_others():
    assert v.vector([1.0, 2.0], "x", 2).shape == (2,)
    assert v.vector(3.0, "x", 1).shape == (1,)  # a scalar becomes length 1
    assert v.matrix([1.0, 2.0], "A", 1, 2).shape == (1, 2)  # a 1-D array becomes one row
    assert v.covariance(0.5, "Q", 1).shape == (1, 1)  # a scalar variance becomes 1x1
    with pytest.raises(ValueError, match=r"^x must have length 3"):
        v.vector([1.0, 2.0], "x", 3)
    with pytest.raises(ValueError, match=r"^A must have shape \(2, 2\)"):
        v.matrix(I3, "A", 2, 2)
    with pytest.raises(ValueError, match=r"^Q must be a square covariance matrix"):
        v.covariance(np.ones((2, 3)), "Q")
    with pytest.raises(ValueError, match=r"^Q must be numeric"):
        v.covariance("big", "Q", 1)


# ================================================================ bad input
@pytest.mark.parametrize("bad", [NAN, INF, -INF])
@pytest.mark.parametrize("which", ["Sig", "R", "Q"])
def test_the_covariance_that_is_not_finite_is_named(which, bad):
    covs = {"Sig": I3.copy(), "R": 0.1 * I3, "Q": 0.5 * I2}
    covs[which][1, 1] = bad
    with pytest.raises(ValueError, match=rf"^{which} must be finite"):
        kf.kf_step(np.zeros(3), covs["Sig"], None, [1.0, 2.0], I3, None, np.eye(2, 3), covs["R"], covs["Q"])


def test_a_non_finite_entry_off_the_diagonal_is_found_too():
    R = 0.1 * I3
    R[0, 2] = R[2, 0] = NAN  # symmetric, so only the finiteness look can catch it
    with pytest.raises(ValueError, match=r"^R must be finite"):
        kf.kf_step(np.zeros(3), I3, None, [1.0, 2.0], I3, None, np.eye(2, 3), R, I2)


def test_a_reading_size_blames_the_one_input_that_disagrees_or_names_them_all():
    sizes = {"z": (3, v.LENGTH), "H": (2, v.ROWS), "Q": (2, v.SQUARE)}
    with pytest.raises(
        ValueError, match=r"^z must have length 2, as H has 2 rows and Q has shape \(2, 2\); got length 3"
    ):
        v.reading_size(**sizes)
    with pytest.raises(ValueError, match=r"^Q must have shape \(3, 3\), as z has length 3 and H has 3 rows"):
        v.reading_size(**{**sizes, "H": (3, v.ROWS)})
    with pytest.raises(ValueError, match=r"^z has length 3, H has 2 rows, Q has shape \(1, 1\): they must agree"):
        v.reading_size(**{**sizes, "Q": (1, v.SQUARE)})
    with pytest.raises(ValueError, match=r"^Q must have shape \(3, 3\), as z has length 3; got shape \(2, 2\)"):
        v.reading_size(z=(3, v.LENGTH), Q=(2, v.SQUARE))  # of two, the second against the first
    assert v.reading_size(z=(2, v.LENGTH), Q=(2, v.SQUARE)) == 2
