"""Per-step speed of kfcourse's filters next to filterpy's, and the import time.

Run by hand from the repository root (it is not a pytest test)::

    python benchmarks/bench_filters.py

It needs the ``dev`` extra (filterpy).  Three filters are timed on the same
problems in both libraries -- the linear Kalman filter on a 2-D constant-velocity
tracker, and the EKF and the UKF on a unicycle robot reading range and bearing to
one landmark -- after checking that both libraries compute the same numbers.
Each row reports the median, over several rounds, of the mean time of one
predict + update step, and the range of the kfcourse / filterpy ratio over the
rounds (on a shared machine the spread says how far to trust the median); a last
row reports ``import kfcourse`` in a fresh interpreter.  kfcourse checks every input on every call (finite, shapes, each
covariance symmetric and positive semi-definite); filterpy checks none.

Noise letters differ between the libraries: kfcourse's ``R`` (process) is
filterpy's ``Q``, and kfcourse's ``Q`` (measurement) is filterpy's ``R``.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from functools import partial

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter, JulierSigmaPoints, KalmanFilter, UnscentedKalmanFilter

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual

STEPS = 2_000  # filter steps per timed round
ROUNDS = 7  # timed rounds per library; the median round is reported
IMPORT_RUNS = 7  # fresh interpreters timed for `import kfcourse`
DT = 0.1  # s, time step of every model
SEED = 20240601  # random seed for the simulated runs

KF_TARGET = 1.5  # kfcourse / filterpy time ratio the kf_step (inputs fully checked on every call) must not exceed
UKF_TARGET = 0.5  # kfcourse / filterpy time ratio the UKF step must not exceed
IMPORT_TARGET = 0.3  # s, `import kfcourse` must take less than this

# Constant-velocity tracker (2-D): state [px, py, vx, vy] (m, m, m/s, m/s).
CV_R = np.diag([1e-4, 1e-4, 1e-2, 1e-2])  # process noise (m², m², m²/s², m²/s²)
CV_Q = np.diag([0.25, 0.25])  # measurement noise, m²
CV_MU0 = np.array([0.0, 0.0, 1.0, 0.5])  # initial mean (m, m, m/s, m/s)
CV_SIG0 = np.diag([1.0, 1.0, 4.0, 4.0])  # initial covariance (m², m², m²/s², m²/s²)

# Unicycle robot reading one landmark: pose [x, y, theta] (m, m, rad).
LANDMARK = np.array([5.0, 3.0])  # m
CONTROL = np.array([1.0, 0.2])  # [V (m/s), omega (rad/s)], a circle of radius 5 m
UNI_R = np.diag([1e-3, 1e-3, 1e-4])  # process noise (m², m², rad²)
UNI_Q = np.diag([0.01, 0.0025])  # measurement noise (m², rad²)
UNI_MU0 = np.array([0.0, 0.0, 0.0])  # initial pose (m, m, rad)
UNI_SIG0 = np.diag([0.1, 0.1, 0.05])  # initial covariance (m², m², rad²)
UKF_LAM = 3 - UNI_MU0.size  # kfcourse spread lam = 3 - n; filterpy's Julier kappa is the same number


# ---------------------------------------------------------------- simulated runs
def cv_measurements(rng: np.random.Generator) -> list[np.ndarray]:
    """Noisy 2-D positions of a target moving at constant velocity."""
    F, H = kf.models.constant_velocity(DT, 2)
    x, zs = CV_MU0.copy(), []
    for _ in range(STEPS):
        x = F @ x + rng.multivariate_normal(np.zeros(4), CV_R)
        zs.append(H @ x + rng.multivariate_normal(np.zeros(2), CV_Q))
    return zs


def unicycle_measurements(rng: np.random.Generator) -> list[np.ndarray]:
    """Noisy range-bearing readings of LANDMARK from a robot driving a circle."""
    x, zs = UNI_MU0.copy(), []
    for _ in range(STEPS):
        x = kf.unicycle(x, CONTROL, DT) + rng.multivariate_normal(np.zeros(3), UNI_R)
        z = kf.range_bearing(x, LANDMARK) + rng.multivariate_normal(np.zeros(2), UNI_Q)
        zs.append(np.array([z[0], kf.wrap_angle(z[1])]))
    return zs


# ---------------------------------------------------------------- the filters
# Each factory returns ``run(zs) -> list of (mean, covariance)``, one pair per step,
# starting afresh from the initial belief.  The same functions are timed.

g = partial(kf.unicycle, dt=DT)  # g(x, u)
G = partial(kf.unicycle_jacobian, dt=DT)  # G(x, u)
h = partial(kf.range_bearing, landmark=LANDMARK)  # h(x)
H_jac = partial(kf.range_bearing_jacobian, landmark=LANDMARK)  # H(x)


def kfcourse_kf() -> Callable:
    F, H = kf.models.constant_velocity(DT, 2)

    def run(zs):
        mu, Sig, out = CV_MU0, CV_SIG0, []
        for z in zs:
            mu, Sig = kf.kf_step(mu, Sig, None, z, F, None, H, CV_R, CV_Q)
            out.append((mu, Sig))
        return out

    return run


def filterpy_kf() -> Callable:
    F, H = kf.models.constant_velocity(DT, 2)
    f = KalmanFilter(dim_x=4, dim_z=2)
    f.F, f.H, f.Q, f.R = F, H, CV_R, CV_Q  # filterpy: Q process, R measurement

    def run(zs):
        f.x, f.P, out = CV_MU0.copy(), CV_SIG0.copy(), []
        for z in zs:
            f.predict()
            f.update(z)
            out.append((f.x, f.P))
        return out

    return run


def kfcourse_ekf() -> Callable:
    def run(zs):
        mu, Sig, out = UNI_MU0, UNI_SIG0, []
        for z in zs:
            mu, Sig = kf.ekf_predict(mu, Sig, CONTROL, g, G, UNI_R)
            mu, Sig = kf.ekf_update(mu, Sig, z, h, H_jac, UNI_Q, residual=range_bearing_residual)
            out.append((mu, Sig))
        return out

    return run


class _UnicycleEKF(ExtendedKalmanFilter):
    """filterpy's EKF with the nonlinear motion model for the mean."""

    def predict_x(self, u=0):
        self.x = g(self.x, u)


def filterpy_ekf() -> Callable:
    f = _UnicycleEKF(dim_x=3, dim_z=2)
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement

    def run(zs):
        f.x, f.P, out = UNI_MU0.copy(), UNI_SIG0.copy(), []
        for z in zs:
            f.F = G(f.x, CONTROL)  # Jacobian at the previous mean, before predict_x moves it
            f.predict(CONTROL)
            f.update(z, H_jac, h, residual=range_bearing_residual)
            out.append((f.x, f.P))
        return out

    return run


def kfcourse_ukf() -> Callable:
    def run(zs):
        mu, Sig, out = UNI_MU0, UNI_SIG0, []
        for z in zs:
            mu, Sig = kf.ukf_predict(
                mu, Sig, CONTROL, g, UNI_R, UKF_LAM, residual=pose_residual, mean=pose_mean, vectorized=True
            )
            mu, Sig = kf.ukf_update(
                mu,
                Sig,
                z,
                h,
                UNI_Q,
                UKF_LAM,
                residual=range_bearing_residual,
                mean=range_bearing_mean,
                x_residual=pose_residual,
                vectorized=True,  # the models take all sigma points at once; filterpy calls them per point
            )
            out.append((mu, Sig))
        return out

    return run


def filterpy_ukf() -> Callable:
    points = JulierSigmaPoints(n=3, kappa=UKF_LAM)  # spread n + kappa, as kfcourse's n + lam
    f = UnscentedKalmanFilter(
        dim_x=3,
        dim_z=2,
        dt=DT,
        hx=h,
        fx=lambda x, dt, u: kf.unicycle(x, u, dt),
        points=points,
        x_mean_fn=pose_mean,
        z_mean_fn=range_bearing_mean,
        residual_x=pose_residual,
        residual_z=range_bearing_residual,
    )
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement

    def run(zs):
        f.x, f.P, out = UNI_MU0.copy(), UNI_SIG0.copy(), []
        for z in zs:
            f.predict(u=CONTROL)
            f.update(z)
            out.append((f.x, f.P))
        return out

    return run


# ---------------------------------------------------------------- measuring
def agree(ours: list, theirs: list) -> bool:
    """Whether two runs give the same mean and covariance at every step."""
    return all(
        np.allclose(m1, m2, rtol=1e-7, atol=1e-9) and np.allclose(S1, S2, rtol=1e-7, atol=1e-9)
        for (m1, S1), (m2, S2) in zip(ours, theirs, strict=True)
    )


def per_step_us(runs: dict[str, Callable], zs: list) -> dict[str, list[float]]:
    """The mean µs per step of each of ROUNDS rounds; the libraries' rounds alternate."""
    times: dict[str, list[float]] = {name: [] for name in runs}
    for run in runs.values():
        run(zs[:50])  # warm up
    for _ in range(ROUNDS):
        for name, run in runs.items():
            t0 = time.perf_counter()
            run(zs)
            times[name].append((time.perf_counter() - t0) / len(zs) * 1e6)
    return times


def import_seconds() -> float:
    """Median time of `import kfcourse` measured inside fresh interpreters, s."""
    code = "import time; t = time.perf_counter(); import kfcourse; print(time.perf_counter() - t)"
    runs = [
        float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
        for _ in range(IMPORT_RUNS)
    ]
    return statistics.median(runs)


def main() -> None:
    rng = np.random.default_rng(SEED)
    problems = [
        ("kf_step (CV 4-state)", kfcourse_kf(), filterpy_kf(), cv_measurements(rng), KF_TARGET),
        ("EKF step (unicycle)", kfcourse_ekf(), filterpy_ekf(), unicycle_measurements(rng), None),
        ("UKF step (unicycle)", kfcourse_ukf(), filterpy_ukf(), unicycle_measurements(rng), UKF_TARGET),
    ]

    for name, ours, theirs, zs, _ in problems:
        if not agree(ours(zs), theirs(zs)):
            raise AssertionError(f"{name}: kfcourse and filterpy disagree")
    print(f"agree: yes (kfcourse and filterpy give the same mean and covariance at all {STEPS} steps)")
    print(f"numpy {np.__version__}, python {sys.version.split()[0]}; {ROUNDS} rounds of {STEPS} steps\n")

    header = f"{'step':<22} {'kfcourse µs':>12} {'filterpy µs':>12} {'ratio':>7} {'range':>11}  {'target':<9} met"
    print(header)
    print("-" * len(header))
    verdicts = []
    for name, ours, theirs, zs, target in problems:
        times = per_step_us({"kfcourse": ours, "filterpy": theirs}, zs)
        t = {lib: statistics.median(rounds) for lib, rounds in times.items()}
        ratio = t["kfcourse"] / t["filterpy"]
        per_round = [a / b for a, b in zip(times["kfcourse"], times["filterpy"], strict=True)]  # the spread
        spread = f"{min(per_round):.2f}-{max(per_round):.2f}"
        if target is None:
            want, met = "report", "-"
        else:
            ok = ratio <= target
            want, met = f"<= {target:.1f}", "yes" if ok else "NO"
            verdicts.append((name.split()[0], ok))
        print(f"{name:<22} {t['kfcourse']:>12.1f} {t['filterpy']:>12.1f} {ratio:>7.2f} {spread:>11}  {want:<9} {met}")

    secs = import_seconds()
    ok = secs < IMPORT_TARGET
    verdicts.append(("import", ok))
    want = f"< {IMPORT_TARGET} s"
    print(f"{'import kfcourse':<22} {secs:>11.3f}s {'':>12} {'':>7} {'':>11}  {want:<9} {'yes' if ok else 'NO':<4}")

    met = [n for n, ok in verdicts if ok]
    missed = [n for n, ok in verdicts if not ok]
    if missed:
        print(f"\ntargets: met {', '.join(met) or 'none'}; MISSED {', '.join(missed)}")
    else:
        print(f"\ntargets: all met ({', '.join(met)})")


if __name__ == "__main__":
    main()
