"""Bad input gets a ValueError that names the offending argument (DESIGN.md, error policy).

One case per (function, argument, kind of badness).  The message must *start* by
naming the argument as a whole word ("Sig_bar must be ...", "the result of g must
...", "kernel[1] must ..."), so "Sig" does not pass for "Sig_bar" and the "a" of
"must be a scalar" does not pass for the coefficient ``a``.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np
import pytest

import kfcourse as kf
from kfcourse import models

NAN, INF = float("nan"), float("inf")

# small valid inputs to spoil one at a time
MU2 = np.array([0.0, 1.0])
I2 = np.eye(2)
F2 = np.array([[1.0, 1.0], [0.0, 1.0]])
B2 = np.zeros((2, 1))
H12 = np.array([[1.0, 0.0]])
Q11 = np.array([[0.5]])
NONSYM = np.array([[1.0, 0.5], [0.0, 1.0]])
INDEFINITE = np.array([[1.0, 2.0], [2.0, 1.0]])  # eigenvalues 3 and -1
NEGVAR = np.diag([-1.0, 1.0])
POSE = np.array([1.0, 2.0, 0.0])
LM = np.array([4.0, 6.0])
I3 = np.eye(3)
Q_RB = np.diag([0.04, 0.01])
MAP = np.array([[4.0, 6.0], [-3.0, 0.0]])
ASSOC_OK = {
    "z": [4.6, 0.95],
    "mu_bar": POSE,
    "Sig_bar": 0.1 * I3,
    "landmarks": MAP,
    "h": kf.range_bearing,
    "H": kf.range_bearing_jacobian,
    "Q": Q_RB,
}


def g_ok(x, u):
    return np.asarray(x, dtype=float)


def G_ok(x, u):
    return np.eye(np.size(x))


def h_rb(x):
    return kf.range_bearing(x, LM)


def H_rb(x):
    return kf.range_bearing_jacobian(x, LM)


def lin(x):
    return np.asarray(x, dtype=float)


CASES: list[tuple[str, Callable[[], object], str]] = [
    # ------------------------------------------------------------ bayes_predict
    ("bayes_predict/belief 2-D", lambda: kf.bayes_predict([[0.5, 0.5]], {0: 1.0}), "belief"),
    ("bayes_predict/belief NaN", lambda: kf.bayes_predict([NAN, 1.0], {0: 1.0}), "belief"),
    ("bayes_predict/belief inf", lambda: kf.bayes_predict([INF, 0.0], {0: 1.0}), "belief"),
    ("bayes_predict/belief sums to 0.9", lambda: kf.bayes_predict([0.5, 0.4], {0: 1.0}), "belief"),
    ("bayes_predict/belief negative", lambda: kf.bayes_predict([1.5, -0.5], {0: 1.0}), "belief"),
    ("bayes_predict/belief empty", lambda: kf.bayes_predict([], {0: 1.0}), "belief"),
    ("bayes_predict/kernel sums to 0.5", lambda: kf.bayes_predict([0.5, 0.5], {1: 0.5}), "kernel"),
    ("bayes_predict/kernel sums to 1.2", lambda: kf.bayes_predict([0.5, 0.5], {1: 0.8, 0: 0.4}), "kernel"),
    ("bayes_predict/kernel negative", lambda: kf.bayes_predict([0.5, 0.5], {1: 1.2, 0: -0.2}), "kernel"),
    ("bayes_predict/kernel NaN", lambda: kf.bayes_predict([0.5, 0.5], {1: NAN}), "kernel"),
    ("bayes_predict/kernel not a mapping", lambda: kf.bayes_predict([0.5, 0.5], [0.8, 0.2]), "kernel"),
    ("bayes_predict/kernel empty", lambda: kf.bayes_predict([0.5, 0.5], {}), "kernel"),
    ("bayes_predict/kernel half-cell offset", lambda: kf.bayes_predict([0.5, 0.5], {0.5: 1.0}), "kernel"),
    ("bayes_predict/boundary unknown", lambda: kf.bayes_predict([0.5, 0.5], {0: 1.0}, boundary="bounce"), "boundary"),
    ("bayes_predict/boundary wrong case", lambda: kf.bayes_predict([0.5, 0.5], {0: 1.0}, boundary="Wall"), "boundary"),
    # ------------------------------------------------------------ bayes_update
    ("bayes_update/likelihood negative", lambda: kf.bayes_update([0.5, 0.5], [0.5, -0.1]), "likelihood"),
    ("bayes_update/likelihood wrong length", lambda: kf.bayes_update([0.5, 0.5], [0.5, 0.1, 0.2]), "likelihood"),
    ("bayes_update/likelihood NaN", lambda: kf.bayes_update([0.5, 0.5], [NAN, 0.1]), "likelihood"),
    ("bayes_update/likelihood inf", lambda: kf.bayes_update([0.5, 0.5], [INF, 0.1]), "likelihood"),
    ("bayes_update/likelihood impossible", lambda: kf.bayes_update([1.0, 0.0], [0.0, 1.0]), "likelihood"),
    ("bayes_update/belief sums to 1.1", lambda: kf.bayes_update([0.6, 0.5], [0.5, 0.5]), "belief"),
    ("bayes_update/belief negative", lambda: kf.bayes_update([1.1, -0.1], [0.5, 0.5]), "belief"),
    # ------------------------------------------------------------ scalar KF
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, kw=kw: fn(**{**dict(mu=2.0, var=0.4, u=1.0, z=3.6), **kw})), arg)
        for fn in (kf.kf_1d_step, kf.kf_1d_cycle)
        for label, kw, arg in [
            ("var negative", {"var": -0.4}, "var"),
            ("var NaN", {"var": NAN}, "var"),
            ("R negative", {"R": -0.2}, "R"),
            ("Q negative", {"Q": -0.1}, "Q"),
            ("Q inf", {"Q": INF}, "Q"),
            ("Q zero with exact prediction", {"var": 0.0, "R": 0.0, "Q": 0.0}, "Q"),
            ("mu NaN", {"mu": NAN}, "mu"),
            ("z inf", {"z": INF}, "z"),
            ("u vector", {"u": [1.0, 2.0]}, "u"),
            ("a NaN", {"a": NAN}, "a"),
            ("c not a number", {"c": "one"}, "c"),
        ]
    ],
    ("kf_1d_predict/var negative", lambda: kf.kf_1d_predict(2.0, -0.4, 1.0), "var"),
    ("kf_1d_predict/mu NaN", lambda: kf.kf_1d_predict(NAN, 0.4, 1.0), "mu"),
    ("kf_1d_predict/u vector", lambda: kf.kf_1d_predict(2.0, 0.4, [1.0, 2.0]), "u"),
    ("kf_1d_predict/a inf", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, a=INF), "a"),
    ("kf_1d_predict/b not a number", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, b="one"), "b"),
    ("kf_1d_predict/R negative", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, R=-0.2), "R"),
    ("kf_1d_gain/var_bar negative", lambda: kf.kf_1d_gain(-0.6), "var_bar"),
    ("kf_1d_gain/var_bar NaN", lambda: kf.kf_1d_gain(NAN), "var_bar"),
    ("kf_1d_gain/c inf", lambda: kf.kf_1d_gain(0.6, c=INF), "c"),
    ("kf_1d_gain/Q negative", lambda: kf.kf_1d_gain(0.6, Q=-0.1), "Q"),
    ("kf_1d_gain/Q zero with exact prediction", lambda: kf.kf_1d_gain(0.0, Q=0.0), "Q"),
    ("kf_1d_update/mu_bar inf", lambda: kf.kf_1d_update(INF, 0.6, 3.6), "mu_bar"),
    ("kf_1d_update/var_bar negative", lambda: kf.kf_1d_update(3.0, -0.6, 3.6), "var_bar"),
    ("kf_1d_update/z NaN", lambda: kf.kf_1d_update(3.0, 0.6, NAN), "z"),
    ("kf_1d_update/z None", lambda: kf.kf_1d_update(3.0, 0.6, None), "z"),
    ("kf_1d_update/c vector", lambda: kf.kf_1d_update(3.0, 0.6, 3.6, c=[1.0, 1.0]), "c"),
    ("kf_1d_update/Q NaN", lambda: kf.kf_1d_update(3.0, 0.6, 3.6, Q=NAN), "Q"),
    ("steady_state_1d/R negative", lambda: kf.steady_state_1d(-0.04, 0.25), "R"),
    ("steady_state_1d/Q NaN", lambda: kf.steady_state_1d(0.04, NAN), "Q"),
    ("steady_state_1d/R and Q zero", lambda: kf.steady_state_1d(0.0, 0.0), "R"),
    ("steady_state_1d/c zero, a unstable", lambda: kf.steady_state_1d(0.04, 0.25, a=1.0, c=0.0), "c"),
    ("steady_state_1d/a inf", lambda: kf.steady_state_1d(0.04, 0.25, a=INF), "a"),
    # ------------------------------------------------------------ gaussians
    ("fuse/var1 negative", lambda: kf.fuse(1.0, -0.5, 2.0, 0.5), "var1"),
    ("fuse/var2 NaN", lambda: kf.fuse(1.0, 0.5, 2.0, NAN), "var2"),
    ("fuse/var2 indefinite", lambda: kf.fuse(MU2, I2, MU2, INDEFINITE), "var2"),
    ("fuse/var1 non-symmetric", lambda: kf.fuse(MU2, NONSYM, MU2, I2), "var1"),
    ("fuse/mu2 wrong length", lambda: kf.fuse(MU2, I2, [1.0, 2.0, 3.0], I2), "mu2"),
    ("fuse/mu1 inf", lambda: kf.fuse([INF, 0.0], I2, MU2, I2), "mu1"),
    ("fuse/both exact", lambda: kf.fuse(1.0, 0.0, 2.0, 0.0), "var1"),
    ("affine_gaussian/Sig negative", lambda: kf.affine_gaussian(2.0, -0.5, 1.0, 3.0), "Sig"),
    ("affine_gaussian/Sig non-symmetric", lambda: kf.affine_gaussian(MU2, NONSYM, F2), "Sig"),
    ("affine_gaussian/A wrong shape", lambda: kf.affine_gaussian(MU2, I2, np.ones((2, 3))), "A"),
    ("affine_gaussian/b wrong length", lambda: kf.affine_gaussian(MU2, I2, F2, [1.0, 2.0, 3.0]), "b"),
    ("affine_gaussian/mu NaN", lambda: kf.affine_gaussian(NAN, 0.5, 1.0), "mu"),
    ("add_gaussians/Sig2 negative", lambda: kf.add_gaussians(1.0, 0.5, 2.0, -0.1), "Sig2"),
    ("add_gaussians/Sig1 indefinite", lambda: kf.add_gaussians(MU2, INDEFINITE, MU2, I2), "Sig1"),
    ("add_gaussians/mu2 wrong length", lambda: kf.add_gaussians(MU2, I2, [1.0], I2), "mu2"),
    ("gaussian_pdf/var zero", lambda: kf.gaussian_pdf(0.0, 0.0, 0.0), "var"),
    ("gaussian_pdf/var negative", lambda: kf.gaussian_pdf(0.0, 0.0, -1.0), "var"),
    ("gaussian_pdf/x NaN", lambda: kf.gaussian_pdf([0.0, NAN], 0.0, 1.0), "x"),
    ("gaussian_pdf/mu inf", lambda: kf.gaussian_pdf(0.0, INF, 1.0), "mu"),
    ("mvn_pdf/x wrong last dimension", lambda: kf.mvn_pdf([0.0, 1.0, 2.0], MU2, I2), "x"),
    ("mvn_pdf/Sig non-symmetric", lambda: kf.mvn_pdf(MU2, MU2, NONSYM), "Sig"),
    ("mvn_pdf/Sig indefinite", lambda: kf.mvn_pdf(MU2, MU2, INDEFINITE), "Sig"),
    ("mvn_pdf/Sig singular", lambda: kf.mvn_pdf(MU2, MU2, np.diag([1.0, 0.0])), "Sig"),
    ("ellipse_axes/Sig 3x3", lambda: kf.ellipse_axes(I3), "Sig"),
    ("ellipse_axes/Sig indefinite", lambda: kf.ellipse_axes(INDEFINITE), "Sig"),
    ("ellipse_axes/nsig negative", lambda: kf.ellipse_axes(I2, nsig=-1.0), "nsig"),
    ("mass_inside/nsig negative", lambda: kf.mass_inside(-1.0), "nsig"),
    ("mass_inside/nsig NaN", lambda: kf.mass_inside(NAN), "nsig"),
    ("mass_inside/dim 3", lambda: kf.mass_inside(1.0, dim=3), "dim"),
    # ------------------------------------------------------------ matrix KF
    ("kf_predict/mu NaN", lambda: kf.kf_predict([NAN, 1.0], I2, [0.0], F2, B2, 0.01 * I2), "mu"),
    ("kf_predict/mu 2-D", lambda: kf.kf_predict([[0.0, 1.0]], I2, [0.0], F2, B2, 0.01 * I2), "mu"),
    ("kf_predict/Sig wrong shape", lambda: kf.kf_predict(MU2, I3, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/Sig non-symmetric", lambda: kf.kf_predict(MU2, NONSYM, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/Sig indefinite", lambda: kf.kf_predict(MU2, INDEFINITE, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/F wrong shape", lambda: kf.kf_predict(MU2, I2, [0.0], np.eye(3), B2, 0.01 * I2), "F"),
    ("kf_predict/F inf", lambda: kf.kf_predict(MU2, I2, [0.0], [[1.0, INF], [0.0, 1.0]], B2, 0.01 * I2), "F"),
    ("kf_predict/B wrong shape", lambda: kf.kf_predict(MU2, I2, [0.0], F2, np.zeros((3, 1)), 0.01 * I2), "B"),
    ("kf_predict/R negative variance", lambda: kf.kf_predict(MU2, I2, [0.0], F2, B2, NEGVAR), "R"),
    ("kf_predict/R non-symmetric", lambda: kf.kf_predict(MU2, I2, [0.0], F2, B2, NONSYM), "R"),
    ("kf_predict/u without B", lambda: kf.kf_predict(MU2, I2, [0.0], F2, None, 0.01 * I2), "u"),
    ("kf_predict/u NaN", lambda: kf.kf_predict(MU2, I2, [NAN], F2, B2, 0.01 * I2), "u"),
    ("kf_update/mu_bar NaN", lambda: kf.kf_update([NAN, 1.0], I2, [1.2], H12, Q11), "mu_bar"),
    ("kf_update/Sig_bar indefinite", lambda: kf.kf_update(MU2, INDEFINITE, [1.2], H12, Q11), "Sig_bar"),
    ("kf_update/Sig_bar non-symmetric", lambda: kf.kf_update(MU2, NONSYM, [1.2], H12, Q11), "Sig_bar"),
    ("kf_update/z NaN", lambda: kf.kf_update(MU2, I2, [NAN], H12, Q11), "z"),
    ("kf_update/H wrong shape", lambda: kf.kf_update(MU2, I2, [1.2], [[1.0, 0.0, 0.0]], Q11), "H"),
    ("kf_update/Q negative", lambda: kf.kf_update(MU2, I2, [1.2], H12, [[-0.5]]), "Q"),
    ("kf_update/Q wrong shape", lambda: kf.kf_update(MU2, I2, [1.2], H12, I2), "Q"),
    ("kf_step/R indefinite", lambda: kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, H12, INDEFINITE, Q11), "R"),
    ("kf_step/Q non-symmetric", lambda: kf.kf_step(MU2, I2, None, [1.0, 2.0], F2, None, I2, 0.01 * I2, NONSYM), "Q"),
    ("kf_step/H wrong shape", lambda: kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, [[1.0]], 0.01 * I2, Q11), "H"),
    ("kf_step/z inf", lambda: kf.kf_step(MU2, I2, [0.0], [INF], F2, B2, H12, 0.01 * I2, Q11), "z"),
    (
        "kf_step/Sig negative variance",
        lambda: kf.kf_step(MU2, NEGVAR, [0.0], [1.2], F2, B2, H12, 0.01 * I2, Q11),
        "Sig",
    ),
    ("kf_gain/Sig_bar non-symmetric", lambda: kf.kf_gain(NONSYM, H12, Q11), "Sig_bar"),
    ("kf_gain/H wrong columns", lambda: kf.kf_gain(I2, [[1.0, 0.0, 0.0]], Q11), "H"),
    ("kf_gain/Q wrong shape", lambda: kf.kf_gain(I2, H12, I2), "Q"),
    # ------------------------------------------------------------ models
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, s=s, m=m: fn(s, m)), arg)
        for fn in (kf.range_bearing, kf.range_bearing_jacobian)
        for label, s, m, arg in [
            ("state wrong length", [1.0, 2.0], LM, "state"),
            ("state NaN", [1.0, NAN, 0.0], LM, "state"),
            ("landmark wrong length", POSE, [4.0, 6.0, 0.0], "landmark"),
            ("landmark inf", POSE, [INF, 6.0], "landmark"),
            ("landmark at robot position", POSE, [1.0, 2.0], "landmark"),
        ]
    ],
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, s=s, u=u, dt=dt: fn(s, u, dt)), arg)
        for fn in (kf.unicycle, kf.unicycle_jacobian, kf.unicycle_control_jacobian)
        for label, s, u, dt, arg in [
            ("state wrong length", [0.0, 0.0], [0.5, 0.0], 1.0, "state"),
            ("u wrong length", POSE, [0.5], 1.0, "u"),
            ("u NaN", POSE, [0.5, NAN], 1.0, "u"),
            ("dt zero", POSE, [0.5, 0.0], 0.0, "dt"),
            ("dt negative", POSE, [0.5, 0.0], -0.1, "dt"),
        ]
    ],
    ("wrap_angle/a NaN", lambda: kf.wrap_angle(NAN), "a"),
    ("wrap_angle/a inf", lambda: kf.wrap_angle([0.0, -INF]), "a"),
    ("wrap_angle/a not a number", lambda: kf.wrap_angle("north"), "a"),
    ("numeric_jacobian/f not callable", lambda: kf.numeric_jacobian(3.0, [1.0]), "f"),
    ("numeric_jacobian/eps zero", lambda: kf.numeric_jacobian(lin, [1.0], eps=0.0), "eps"),
    ("numeric_jacobian/eps negative", lambda: kf.numeric_jacobian(lin, [1.0], eps=-1e-6), "eps"),
    ("numeric_jacobian/x NaN", lambda: kf.numeric_jacobian(lin, [NAN]), "x"),
    ("numeric_jacobian/x 2-D", lambda: kf.numeric_jacobian(lin, [[1.0, 2.0]]), "x"),
    ("numeric_jacobian/f returns a matrix", lambda: kf.numeric_jacobian(lambda x: np.eye(2), [1.0]), "f"),
    ("constant_velocity/dt zero", lambda: models.constant_velocity(0.0, 2), "dt"),
    ("constant_velocity/dim zero", lambda: models.constant_velocity(0.1, 0), "dim"),
    ("constant_velocity/dim fractional", lambda: models.constant_velocity(0.1, 1.5), "dim"),
    ("pose_residual/a wrong length", lambda: models.pose_residual([0.0, 0.0], POSE), "a"),
    ("range_bearing_residual/b NaN", lambda: models.range_bearing_residual([1.0, 0.0], [NAN, 0.0]), "b"),
    ("pose_mean/weights wrong length", lambda: models.pose_mean(np.zeros((3, 3)), [0.5, 0.5]), "weights"),
    ("range_bearing_mean/points NaN", lambda: models.range_bearing_mean([[NAN, 0.0]], [1.0]), "points"),
    # ------------------------------------------------------------ EKF
    ("ekf_predict/g not callable", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], "g", G_ok, 0.01 * I3), "g"),
    ("ekf_predict/G not callable", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, np.eye(3), 0.01 * I3), "G"),
    (
        "ekf_predict/g wrong shape",
        lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], lambda x, u: x[:2], G_ok, 0.01 * I3),
        "g",
    ),
    (
        "ekf_predict/g returns NaN",
        lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], lambda x, u: x * NAN, G_ok, 0.01 * I3),
        "g",
    ),
    ("ekf_predict/G wrong shape", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, lambda x, u: I2, 0.01 * I3), "G"),
    ("ekf_predict/R indefinite", lambda: kf.ekf_predict(MU2, I2, None, g_ok, G_ok, INDEFINITE), "R"),
    ("ekf_predict/Sig non-symmetric", lambda: kf.ekf_predict(MU2, NONSYM, None, g_ok, G_ok, I2), "Sig"),
    ("ekf_predict/mu inf", lambda: kf.ekf_predict([INF, 0.0], I2, None, g_ok, G_ok, I2), "mu"),
    ("ekf_update/h not callable", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], None, H_rb, Q_RB), "h"),
    ("ekf_update/H not callable", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H12, Q_RB), "H"),
    ("ekf_update/h wrong shape", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], lambda x: x, H_rb, Q_RB), "h"),
    ("ekf_update/H wrong shape", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, lambda x: I3, Q_RB), "H"),
    ("ekf_update/Q negative variance", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, NEGVAR), "Q"),
    (
        "ekf_update/Sig_bar indefinite",
        lambda: kf.ekf_update(POSE, np.diag([1.0, -1.0, 1.0]), [4.6, 0.95], h_rb, H_rb, Q_RB),
        "Sig_bar",
    ),
    ("ekf_update/z NaN", lambda: kf.ekf_update(POSE, I3, [4.6, NAN], h_rb, H_rb, Q_RB), "z"),
    (
        "ekf_update/residual wrong shape",
        lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, Q_RB, residual=lambda a, b: [0.0]),
        "residual",
    ),
    # ------------------------------------------------------------ UKF
    ("sigma_points/lam with n+lam=0", lambda: kf.sigma_points(MU2, I2, -2.0), "lam"),
    ("sigma_points/lam with n+lam<0", lambda: kf.sigma_points(MU2, I2, -3.0), "lam"),
    ("sigma_points/lam NaN", lambda: kf.sigma_points(MU2, I2, NAN), "lam"),
    ("sigma_points/Sig indefinite", lambda: kf.sigma_points(MU2, INDEFINITE, 1.0), "Sig"),
    ("sigma_points/Sig wrong shape", lambda: kf.sigma_points(MU2, I3, 1.0), "Sig"),
    ("sigma_points/beta inf", lambda: kf.sigma_points(MU2, I2, 1.0, beta=INF), "beta"),
    ("unscented_transform/f not callable", lambda: kf.unscented_transform(MU2, I2, [1, 2], 1.0), "f"),
    ("unscented_transform/lam with n+lam=0", lambda: kf.unscented_transform([2.0], [[1.0]], lin, -1.0), "lam"),
    ("unscented_transform/Sig non-symmetric", lambda: kf.unscented_transform(MU2, NONSYM, lin, 1.0), "Sig"),
    ("unscented_transform/f returns a matrix", lambda: kf.unscented_transform(MU2, I2, lambda x: np.eye(2), 1.0), "f"),
    ("unscented_1d/var negative", lambda: kf.unscented_1d(2.0, -1.0, lin), "var"),
    ("unscented_1d/lam with 1+lam=0", lambda: kf.unscented_1d(2.0, 1.0, lin, lam=-1.0), "lam"),
    ("unscented_1d/f not callable", lambda: kf.unscented_1d(2.0, 1.0, 4.0), "f"),
    ("unscented_1d/f returns a vector", lambda: kf.unscented_1d(2.0, 1.0, lambda x: [x, x]), "f"),
    ("unscented_1d/mu NaN", lambda: kf.unscented_1d(NAN, 1.0, lin), "mu"),
    ("ukf_predict/g not callable", lambda: kf.ukf_predict(MU2, I2, None, "g", 0.01 * I2, 1.0), "g"),
    ("ukf_predict/g wrong shape", lambda: kf.ukf_predict(MU2, I2, None, lambda x, u: x[:1], 0.01 * I2, 1.0), "g"),
    ("ukf_predict/lam with n+lam=0", lambda: kf.ukf_predict(MU2, I2, None, g_ok, 0.01 * I2, -2.0), "lam"),
    ("ukf_predict/R indefinite", lambda: kf.ukf_predict(MU2, I2, None, g_ok, INDEFINITE, 1.0), "R"),
    ("ukf_predict/Sig non-symmetric", lambda: kf.ukf_predict(MU2, NONSYM, None, g_ok, I2, 1.0), "Sig"),
    ("ukf_update/h not callable", lambda: kf.ukf_update(MU2, I2, [1.2], 1.0, Q11, 1.0), "h"),
    ("ukf_update/h wrong shape", lambda: kf.ukf_update(MU2, I2, [1.2], lin, Q11, 1.0), "h"),
    ("ukf_update/lam with n+lam<0", lambda: kf.ukf_update(MU2, I2, [1.2], lambda x: x[:1], Q11, -2.5), "lam"),
    ("ukf_update/Q negative", lambda: kf.ukf_update(MU2, I2, [1.2], lambda x: x[:1], [[-0.5]], 1.0), "Q"),
    (
        "ukf_update/Sig_bar non-symmetric",
        lambda: kf.ukf_update(MU2, NONSYM, [1.2], lambda x: x[:1], Q11, 1.0),
        "Sig_bar",
    ),
    ("ukf_update/Sig_bar wrong shape", lambda: kf.ukf_update(MU2, I3, [1.2], lambda x: x[:1], Q11, 1.0), "Sig_bar"),
    ("ukf_update/z inf", lambda: kf.ukf_update(MU2, I2, [INF], lambda x: x[:1], Q11, 1.0), "z"),
    # ------------------------------------------------------------ association
    ("mahalanobis/nu NaN", lambda: kf.mahalanobis([NAN, 0.0], I2), "nu"),
    ("mahalanobis/S wrong shape", lambda: kf.mahalanobis([1.0, 0.0], I3), "S"),
    ("mahalanobis/S indefinite", lambda: kf.mahalanobis([1.0, 0.0], INDEFINITE), "S"),
    ("mahalanobis/S singular", lambda: kf.mahalanobis([1.0, 0.0], np.diag([1.0, 0.0])), "S"),
    ("mahalanobis/S non-symmetric", lambda: kf.mahalanobis([1.0, 0.0], NONSYM), "S"),
    *[
        (f"associate/{label}", (lambda kw=kw: kf.associate(**{**ASSOC_OK, **kw})), arg)
        for label, kw, arg in [
            ("z NaN", {"z": [NAN, 0.9]}, "z"),
            ("gate zero", {"gate": 0.0}, "gate"),
            ("gate negative", {"gate": -3.0}, "gate"),
            ("landmarks 3-D", {"landmarks": np.zeros((2, 2, 2))}, "landmarks"),
            ("landmarks NaN", {"landmarks": [[NAN, 6.0]]}, "landmarks"),
            ("h not callable", {"h": "range"}, "h"),
            ("H not callable", {"H": 0}, "H"),
            ("h wrong shape", {"h": lambda x, m: [1.0]}, "h"),
            ("H wrong shape", {"H": lambda x, m: I2}, "H"),
            ("Q wrong shape", {"Q": I3}, "Q"),
            ("Sig_bar non-symmetric", {"Sig_bar": np.triu(np.ones((3, 3)))}, "Sig_bar"),
            ("mu_bar inf", {"mu_bar": [INF, 2.0, 0.0]}, "mu_bar"),
        ]
    ],
]


# a message starts with the argument; a model's output, or a helper's argument, is named after it
NAMES_ARG = r"^(?:the result of |pose_residual |range_bearing_residual )?"


@pytest.mark.parametrize(("call", "arg"), [pytest.param(c, a, id=i) for i, c, a in CASES])
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    with pytest.raises(ValueError, match=NAMES_ARG + re.escape(arg) + r"(?!\w)"):
        call()


def test_case_ids_are_unique():
    ids = [i for i, _, _ in CASES]
    assert len(ids) == len(set(ids))


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.bayes_predict([0.5, 0.5], {0: 1.0})
    kf.bayes_update([0.5, 0.5], [0.5, 0.5])
    kf.kf_1d_step(mu=2.0, var=0.4, u=1.0, z=3.6)
    kf.steady_state_1d(0.04, 0.25)
    kf.fuse(MU2, I2, MU2, I2)
    kf.affine_gaussian(MU2, I2, F2, [1.0, 2.0])
    kf.mvn_pdf(MU2, MU2, I2)
    kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, H12, 0.01 * I2, Q11)
    kf.kf_gain(I2, H12, Q11)
    kf.range_bearing(POSE, LM)
    kf.unicycle(POSE, [0.5, 0.0], 1.0)
    kf.numeric_jacobian(lin, [1.0])
    kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, G_ok, 0.01 * I3)
    kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, Q_RB)
    kf.sigma_points(MU2, I2, 1.0)
    kf.unscented_transform(MU2, I2, lin, 1.0)
    kf.unscented_1d(2.0, 1.0, lin)
    kf.ukf_predict(MU2, I2, None, g_ok, 0.01 * I2, 1.0)
    kf.ukf_update(MU2, I2, [1.2], lambda chi: chi[:, :1], Q11, 1.0)
    kf.mahalanobis([1.0, 0.0], I2)
    idx, _ = kf.associate(**ASSOC_OK)
    assert idx == 0


# Hooks and kernels that are not what they should be.
def _rb(x):
    return kf.range_bearing(x, [4.0, 6.0])


def _rb_jac(x):
    return kf.range_bearing_jacobian(x, [4.0, 6.0])


@pytest.mark.parametrize(
    "call",
    [
        lambda: kf.ekf_update(np.zeros(3), np.eye(3), [5.0, 0.9], _rb, _rb_jac, np.eye(2), residual=3),
        lambda: kf.ukf_update(np.zeros(3), np.eye(3), [5.0, 0.9], _rb, np.eye(2), 0.0, residual="wrap"),
        lambda: kf.ukf_predict(np.zeros(3), np.eye(3), None, lambda x, u: x, np.eye(3), 0.0, mean=1),
        lambda: kf.numeric_jacobian(_rb, np.zeros(3), residual=[1]),
    ],
    ids=["ekf_update", "ukf_update", "ukf_predict-mean", "numeric_jacobian"],
)
def test_hook_that_is_not_callable(call):
    with pytest.raises(ValueError, match=r"\b(residual|mean) must be callable"):
        call()


@pytest.mark.parametrize("kernel", [{"a": 1.0}, {None: 1.0}, {1: 1.5, 0: -0.5}], ids=["text", "none", "negative"])
def test_bad_kernel_is_named(kernel):
    with pytest.raises(ValueError, match=r"^kernel"):
        kf.bayes_predict([0.5, 0.5], kernel)


def test_empty_covariance():
    with pytest.raises(ValueError, match=r"^Sig must not be empty"):
        kf.kf_predict(np.zeros(0), np.zeros((0, 0)), None, np.zeros((0, 0)), None, np.zeros((0, 0)))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: models.constant_velocity(0.0, 2), "dt must be a time step > 0 s"),
        (lambda: kf.unicycle(POSE, [0.5, 0.0], -0.1), "dt must be a time step > 0 s"),
        (lambda: kf.numeric_jacobian(lin, [1.0], eps=0.0), "eps must be a finite-difference step > 0"),
        (lambda: kf.gaussian_pdf(0.0, 0.0, 0.0), "var must be a variance > 0"),
        (lambda: kf.ellipse_axes(I2, nsig=0.0), "nsig must be a number of standard deviations > 0"),
        (lambda: kf.associate(**ASSOC_OK, gate=-3.0), "gate must be a distance > 0 standard deviations"),
        (lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, R=-0.2), "R must be a variance >= 0"),
        (lambda: kf.kf_1d_gain(-0.6), "var_bar must be a variance >= 0"),
        (lambda: kf.sim.drift_sigma(-0.1, 4), "step_std must be a standard deviation >= 0 m"),
        (lambda: kf.sim.simulate_line(sensor_std=0.0), "sensor_std must be a standard deviation > 0 m"),
        (lambda: kf.sim.motion_kernel(1.2), "reliability must be a probability in [0, 1]"),
        (lambda: kf.sim.door_likelihood([True, False], True, -0.1), "reliability must be a probability in [0, 1]"),
        (
            lambda: kf.sim.read_door(0, [True], 1.5, np.random.default_rng(0)),
            "reliability must be a probability in [0, 1]",
        ),
    ],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    with pytest.raises(ValueError, match=re.escape(message)):
        call()


def test_one_dimensional_steps_agree_with_the_cycle():
    """kf_1d_cycle is kf_1d_predict, kf_1d_gain and kf_1d_update in a row (valid inputs)."""
    cyc = kf.kf_1d_cycle(2.0, 0.4, 1.0, 3.6, a=0.9, b=1.1, c=1.2, R=0.3, Q=0.2)
    mu_bar, var_bar = kf.kf_1d_predict(2.0, 0.4, 1.0, a=0.9, b=1.1, R=0.3)
    assert (mu_bar, var_bar) == (cyc.mu_bar, cyc.var_bar)
    assert kf.kf_1d_gain(var_bar, c=1.2, Q=0.2) == cyc.K
    assert kf.kf_1d_update(mu_bar, var_bar, 3.6, c=1.2, Q=0.2) == (cyc.mu, cyc.var)
    assert cyc.mu != cyc.mu_bar and cyc.var < cyc.var_bar  # the update did something
