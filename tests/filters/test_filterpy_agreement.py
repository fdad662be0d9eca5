"""kfcourse's filters agree with filterpy 2.0's, step by step.

The linear Kalman filter on a 2-D constant-velocity tracker, and the EKF and the UKF on
a unicycle robot reading range and bearing to one landmark, run side by side in both
libraries from the same belief on the same readings; mean and covariance must agree at
every step, after each predict and after each update.  The problems and both libraries'
filters are set up in ``benchmarks/filterpy_pairs.py``, which the benchmark
``benchmarks/bench_filters.py`` times.
"""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.filterpy_pairs import (
    CONTROL,
    CV_MU0,
    CV_SIG0,
    SEED,
    UNI_MU0,
    UNI_SIG0,
    cv_readings,
    filterpy_ekf,
    filterpy_kf,
    filterpy_ukf,
    kfcourse_ekf_predict,
    kfcourse_ekf_update,
    kfcourse_kf_predict,
    kfcourse_kf_step,
    kfcourse_ukf_predict,
    kfcourse_ukf_update,
    unicycle_readings,
)

STEPS = 400  # filter steps compared (KF, EKF)
UKF_STEPS = 150  # filterpy's UKF is slow; the bearing crosses +-pi at steps 76-79


# ================================================================ properties (the only section: agreement)
def assert_same_step(t, ours, theirs):
    (m1, S1), (m2, S2) = ours, theirs
    np.testing.assert_allclose(m1, m2, rtol=1e-7, atol=1e-9, err_msg=f"mean at step {t}")
    np.testing.assert_allclose(S1, S2, rtol=1e-7, atol=1e-9, err_msg=f"covariance at step {t}")


@pytest.fixture(scope="module")
def cv_zs() -> list[np.ndarray]:
    return cv_readings(np.random.default_rng(SEED), STEPS)


@pytest.fixture(scope="module")
def unicycle_zs() -> list[np.ndarray]:
    return unicycle_readings(np.random.default_rng(SEED + 1), STEPS)


def test_readings_cross_the_bearing_seam(unicycle_zs):
    # the robot circles with the landmark behind it at times, so the residual hooks are exercised
    bearings = np.array([z[1] for z in unicycle_zs[:UKF_STEPS]])
    assert bearings.max() > 3.0 and bearings.min() < -3.0


def test_kf_step_agrees_with_filterpy(cv_zs):
    f = filterpy_kf()
    mu, Sig = CV_MU0, CV_SIG0
    for t, z in enumerate(cv_zs):
        f.predict()
        assert_same_step(t, kfcourse_kf_predict(mu, Sig), (f.x, f.P))
        mu, Sig = kfcourse_kf_step(mu, Sig, z)
        f.update(z)
        assert_same_step(t, (mu, Sig), (f.x, f.P))


def test_ekf_steps_agree_with_filterpy(unicycle_zs):
    f = filterpy_ekf()
    mu, Sig = UNI_MU0, UNI_SIG0
    for t, z in enumerate(unicycle_zs):
        mu, Sig = kfcourse_ekf_predict(mu, Sig)
        f.predict(CONTROL)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
        mu, Sig = kfcourse_ekf_update(mu, Sig, z)
        f.update(z)
        assert_same_step(t, (mu, Sig), (f.x, f.P))


@pytest.mark.parametrize("lam", [0.0, 1.0], ids=["lam=0", "lam=1"])
def test_ukf_steps_agree_with_filterpy(unicycle_zs, lam):
    f = filterpy_ukf(lam)
    mu, Sig = UNI_MU0, UNI_SIG0
    for t, z in enumerate(unicycle_zs[:UKF_STEPS]):
        mu, Sig = kfcourse_ukf_predict(mu, Sig, lam)
        f.predict(u=CONTROL)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
        mu, Sig = kfcourse_ukf_update(mu, Sig, z, lam)
        f.update(z)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
