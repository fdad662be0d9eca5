"""Every public function and demo refuses a bad value of each argument, and its message names it.

The table :data:`EXAMPLES` holds one valid call of every function in ``kf.__all__``, ``kf.data.__all__``,
``kf.models.__all__``, ``kf.sim.__all__`` and ``kf.demos.__all__``, by keyword, every
argument given.  From each valid value :func:`bad_values` derives the bad ones that fit its
kind (a number, an array, a switch, a choice, a callable, a seed, a record), and each is
passed in turn, the other arguments left valid: the call must raise a ``ValueError`` or
``TypeError`` that names the argument.  :data:`ACCEPTED` lists the few bad values that are
legitimately accepted, each with its reason.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Mapping

import numpy as np
import pytest

import kfcourse as kf

SPACES = {"kf": kf, "kf.models": kf.models, "kf.sim": kf.sim, "kf.data": kf.data, "kf.demos": kf.demos}


def _public() -> dict:
    """Every public function and demo by the name a notebook calls it, each function once."""
    found: dict = {}
    for space, module in SPACES.items():
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isfunction(obj) and obj not in found.values():
                found[f"{space}.{name}"] = obj
    return found


PUBLIC = _public()

# ================================================================ the valid calls
I2, I3 = np.eye(2), np.eye(3)
POSE, ODOMETRY, DT = [0.0, 0.0, 0.0], [1.0, 0.1], 0.2
POSES = [[0.0, 0.0, 0.0], [1.0, 0.5, 0.3]]  # two poses, one a row
LANDMARK, MARKS = [2.0, 1.0], [[2.0, 1.0], [-1.0, 3.0]]
READINGS = [[2.2, 0.4], [3.2, 1.9]]  # [r, phi] of MARKS from POSE, give or take
M_ODO, Q_RB = np.diag([0.01, 0.0025]), np.diag([0.01, 0.001])  # odometry and range-bearing noise
SIG_POSE = np.diag([0.1, 0.1, 0.01])
CLOUD = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.1], [0.0, 0.2, -0.1], [0.2, 0.1, 0.0]])
WEIGHTS = [0.4, 0.3, 0.2, 0.1]
RNG = np.random.default_rng(0)
DOORS = kf.sim.hallway_doors()
KERNEL = {1: 0.9, 0: 0.1}
SHORT = kf.sim.loop_controls()[:12]  # a short drive
WORLD = kf.sim.simulate_robot(SHORT, DT, landmarks=MARKS, sensor_range=6.0)
PREDICT, UPDATE = kf.sim.loop_filter("ekf", DT, M_ODO, Q_RB)
TRACK = kf.sim.localize(WORLD, PREDICT, UPDATE, SIG_POSE)
LAP = kf.sim.landmark_loop(0)
PLAZA = kf.data.load_plaza("Plaza2")
RANGES = kf.sim.range_localize(PLAZA, steps=5)
SCAN = kf.sim.association_scan(0, leg=True)
TARGET = kf.sim.simulate_target(0)
BATCH = kf.sim.simulate_tracks(n_tracks=2, n_steps=3)
F_CV, B_CV = [[1.0, 0.1], [0.0, 1.0]], [[0.005], [0.1]]  # a constant-velocity model, pushed by an acceleration
R_CV, Q_CV = kf.sim.process_noise(0.1, 1.0), I2  # a constant-velocity tracker's noise


def motion(x, u):
    """The unicycle over one step: ``g`` of the EKF and the UKF."""
    return kf.unicycle(x, u, DT)


def motion_jacobian(x, u):
    return kf.unicycle_jacobian(x, u, DT)


def reading(x):
    """Range and bearing of LANDMARK: ``h`` of the EKF and the UKF."""
    return kf.range_bearing(x, LANDMARK)


def reading_jacobian(x):
    return kf.range_bearing_jacobian(x, LANDMARK)


def square(x):
    return x * x


def gate_all(mu_bar, Sig_bar, z, m):
    """A validation gate that accepts every reading."""
    return True


def labels(mu_bar, Sig_bar, z):
    """Data association that says every reading is landmark 0's."""
    return 0


# fmt: off
EXAMPLES: dict[str, dict] = {
    # ---------------------------------------------------------------- kf: the filters
    "kf.add_gaussians": dict(mu1=[0.0, 1.0], Sig1=I2, mu2=[1.0, 0.0], Sig2=0.5 * I2),
    "kf.affine_gaussian": dict(mu=[0.0, 1.0], Sig=I2, A=[[1.0, 1.0], [0.0, 1.0]], b=[0.5, 0.0]),
    "kf.associate": dict(
        z=[2.2, 0.4], mu_bar=POSE, Sig_bar=SIG_POSE, landmarks=MARKS, h=kf.range_bearing,
        H=kf.range_bearing_jacobian, Q=Q_RB, gate=3.0, residual=kf.models.range_bearing_residual,
    ),
    "kf.bayes_predict": dict(belief=[0.25, 0.25, 0.5, 0.0], kernel=KERNEL, boundary="wall"),
    "kf.bayes_update": dict(belief=[0.25, 0.25, 0.5, 0.0], likelihood=[0.9, 0.1, 0.1, 0.9], return_eta=True),
    "kf.effective_sample_size": dict(w=WEIGHTS),
    "kf.ekf_localization_step": dict(
        mu=POSE, Sig=SIG_POSE, u=ODOMETRY, z=READINGS, landmarks=MARKS, dt=DT, M=M_ODO, Q=Q_RB, gate=4.0,
    ),
    "kf.ekf_predict": dict(mu=POSE, Sig=SIG_POSE, u=ODOMETRY, g=motion, G=motion_jacobian, R=0.01 * I3),
    "kf.ekf_rts_smoother": dict(
        mu=[POSE] * 3, Sig=[SIG_POSE] * 3, mu_bar=[POSE] * 3, Sig_bar=[SIG_POSE + 0.01 * I3] * 3, G=motion_jacobian,
        u=[ODOMETRY] * 3, residual=kf.models.pose_residual,
    ),
    "kf.ekf_update": dict(
        mu_bar=POSE, Sig_bar=SIG_POSE, z=[2.2, 0.4], h=reading, H=reading_jacobian, Q=Q_RB,
        residual=kf.models.range_bearing_residual,
    ),
    "kf.ellipse_axes": dict(Sig=[[2.0, 0.5], [0.5, 1.0]], nsig=2.0),
    "kf.fuse": dict(mu1=1.0, var1=0.5, mu2=2.0, var2=0.25),
    "kf.gaussian_pdf": dict(x=0.5, mu=0.0, var=1.0),
    "kf.inject_random": dict(particles=CLOUD, share=0.5, bounds=[[-1.0, 1.0], [-1.0, 1.0]], rng=RNG),
    "kf.kf_1d_cycle": dict(mu=0.0, var=1.0, u=1.0, z=1.2, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1),
    "kf.kf_1d_gain": dict(var_bar=1.0, c=1.0, Q=0.1),
    "kf.kf_1d_predict": dict(mu=0.0, var=1.0, u=1.0, a=1.0, b=1.0, R=0.2),
    "kf.kf_1d_step": dict(mu=0.0, var=1.0, u=1.0, z=1.2, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1),
    "kf.kf_1d_update": dict(mu_bar=1.0, var_bar=1.2, z=1.2, c=1.0, Q=0.1),
    "kf.kf_gain": dict(Sig_bar=I2, H=[[1.0, 0.0]], Q=[[0.5]]),
    "kf.kf_predict": dict(mu=[0.0, 1.0], Sig=I2, u=[0.5], F=F_CV, B=B_CV, R=0.01 * I2),
    "kf.kf_step": dict(mu=[0.0, 1.0], Sig=I2, u=[0.5], z=[0.3], F=F_CV, B=B_CV, H=[[1.0, 0.0]], R=0.01 * I2, Q=[[0.5]]),
    "kf.kf_step_batch": dict(
        mu=np.zeros((3, 2)), Sig=np.stack([I2] * 3), u=np.ones((3, 1)), z=np.ones((3, 1)), F=F_CV, B=B_CV,
        H=[[1.0, 0.0]], R=0.01 * I2, Q=[[0.5]],
    ),
    "kf.kf_update": dict(mu_bar=[0.0, 1.0], Sig_bar=I2, z=[0.3], H=[[1.0, 0.0]], Q=[[0.5]]),
    "kf.mahalanobis": dict(nu=[1.0, 0.5], S=[[2.0, 0.5], [0.5, 1.0]]),
    "kf.mass_inside": dict(nsig=1.0, dim=2),
    "kf.mvn_pdf": dict(x=[0.5, 0.5], mu=[0.0, 0.0], Sig=I2),
    "kf.normalise": dict(log_w=[-1.0, 0.0, -np.inf]),
    "kf.pf_estimate": dict(particles=CLOUD, w=WEIGHTS),
    "kf.pf_predict": dict(particles=CLOUD, u=ODOMETRY, dt=DT, M=M_ODO, rng=RNG),
    "kf.pf_weight": dict(
        particles=CLOUD, z=READINGS, landmarks=MARKS, Q=Q_RB, log_w=[0.0, -1.0, 0.0, 0.0], labelled=True,
    ),
    "kf.range_update": dict(mu_bar=POSE, Sig_bar=SIG_POSE, z=[2.3], beacon=LANDMARK, Q=[[0.01]]),
    "kf.resample_multinomial": dict(w=WEIGHTS, rng=RNG),
    "kf.resample_stratified": dict(w=WEIGHTS, rng=RNG),
    "kf.resample_systematic": dict(w=WEIGHTS, rng=RNG),
    "kf.rts_smoother": dict(
        mu=[POSE] * 3, Sig=[SIG_POSE] * 3, mu_bar=[POSE] * 3, Sig_bar=[SIG_POSE + 0.01 * I3] * 3,
        F=motion_jacobian(POSE, ODOMETRY), residual=kf.models.pose_residual,
    ),
    "kf.sigma_points": dict(mu=[0.0, 1.0], Sig=I2, lam=1.0, beta=2.0),
    "kf.steady_state_1d": dict(R=0.2, Q=0.1, a=1.0, c=1.0),
    "kf.ukf_predict": dict(
        mu=POSE, Sig=SIG_POSE, u=ODOMETRY, g=motion, R=0.01 * I3, lam=0.0, residual=kf.models.pose_residual,
        mean=kf.models.pose_mean, beta=0.0,
    ),
    "kf.ukf_update": dict(
        mu_bar=POSE, Sig_bar=SIG_POSE, z=[2.2, 0.4], h=reading, Q=Q_RB, lam=0.0,
        residual=kf.models.range_bearing_residual, mean=kf.models.range_bearing_mean,
        x_residual=kf.models.pose_residual, beta=0.0,
    ),
    "kf.unscented_1d": dict(mu=2.0, var=1.0, f=square, lam=0.0),
    "kf.unscented_transform": dict(
        mu=POSE, Sig=SIG_POSE, f=reading, lam=0.0, residual=kf.models.range_bearing_residual,
        mean=kf.models.range_bearing_mean, beta=0.0,
    ),
    # ---------------------------------------------------------------- kf: the models
    "kf.numeric_jacobian": dict(f=reading, x=POSE, eps=1e-6, residual=kf.models.range_bearing_residual),
    "kf.range_bearing": dict(state=POSES, landmark=MARKS),
    "kf.range_bearing_jacobian": dict(state=POSE, landmark=LANDMARK),
    "kf.unicycle": dict(state=POSES, u=[[1.0, 0.1], [0.5, -0.2]], dt=DT),
    "kf.unicycle_control_jacobian": dict(state=POSE, u=ODOMETRY, dt=DT),
    "kf.unicycle_jacobian": dict(state=POSE, u=ODOMETRY, dt=DT),
    "kf.wrap_angle": dict(a=4.0),
    "kf.models.constant_velocity": dict(dt=0.1, dim=2),
    "kf.models.pose_mean": dict(points=CLOUD, weights=WEIGHTS),
    "kf.models.pose_residual": dict(a=POSES, b=POSES[::-1]),
    "kf.models.range_bearing_mean": dict(points=READINGS, weights=[0.5, 0.5]),
    "kf.models.range_bearing_residual": dict(a=READINGS, b=READINGS[::-1]),
    "kf.models.range_only": dict(state=POSES, beacon=LANDMARK),
    "kf.models.range_only_jacobian": dict(state=POSE, beacon=LANDMARK),
    "kf.models.scaled_range": dict(state=[[0.0, 0.0, 0.0, 1.07], [1.0, 0.5, 0.3, 1.07]], beacon=LANDMARK),
    "kf.models.scaled_range_jacobian": dict(state=[0.0, 0.0, 0.0, 1.07], beacon=LANDMARK),
    # ---------------------------------------------------------------- kf.sim: the cheapest settings
    "kf.sim.association_scan": dict(seed=0, leg=True),
    "kf.sim.bias_drift": dict(scale_error=0.01, distance=400.0),
    "kf.sim.door_likelihood": dict(doors=DOORS, saw_door=[True, False], reliability=0.9),
    "kf.sim.drift_sigma": dict(step_std=0.05, n=10),
    "kf.sim.factor_graph": dict(
        log=PLAZA, scale=1.07, range_std=0.5, odometry_std=(0.05, 0.05, 0.02), robust=False, steps=5, initial=RANGES.mu
    ),
    "kf.sim.family_table": dict(seeds=[0], particle_counts=[10], runs=[]),
    "kf.sim.filter_target": dict(run=TARGET, R=R_CV, Q=Q_CV),
    "kf.sim.filter_tracks": dict(batch=BATCH, R=R_CV, Q=Q_CV),
    "kf.sim.flipped_bearing_jacobian": dict(state=POSE, landmark=LANDMARK),
    "kf.sim.gate_within": dict(gate=3.0, Q=Q_RB, wrap_bearing=True),
    "kf.sim.gated_update": dict(scan=SCAN, gate=3.0),
    "kf.sim.hallway_doors": dict(n_cells=12, left=(0, 3, 5), right=(2, 4)),
    "kf.sim.landmark_loop": dict(
        seed=0, filter="ekf", dropout=(10, 20), motion_noise=1.0, sensor_noise=1.0, filter_motion_noise=1.0,
        filter_sensor_noise=1.0, one_back=True, kidnap=60, wrap_bearing=True, gate=4.0, laps=1,
        landmarks=kf.sim.DEFAULT_LANDMARKS, sensor_range=4.0, start=POSE, labelled=True, since=LAP,
    ),
    "kf.sim.localize": dict(
        world=WORLD, predict=PREDICT, update=UPDATE, Sig0=SIG_POSE, accept=gate_all, mu0=POSE, identify=labels,
        known=(3, TRACK),
    ),
    "kf.sim.localize_with_step": dict(
        world=WORLD, step=kf.ekf_localization_step, Sig0=SIG_POSE, M=M_ODO, Q=Q_RB, gate=4.0, name="mine", mu0=POSE,
    ),
    "kf.sim.localized": dict(run=LAP, bound=0.5),
    "kf.sim.loop_controls": dict(length=8.0, width=5.0, radius=1.0, speed=1.0, dt=DT, laps=1),
    "kf.sim.loop_filter": dict(filter="ukf", dt=DT, M=M_ODO, Q=Q_RB, wrap_bearing=True),
    "kf.sim.loop_world": dict(seed=0, motion_noise=1.0, sensor_noise=1.0, landmarks=MARKS),
    "kf.sim.monte_carlo_drift": dict(step_std=0.05, n=10, n_robots=10, seed=0),
    "kf.sim.motion_kernel": dict(reliability=0.9),
    "kf.sim.move": dict(cell=3, kernel=KERNEL, rng=RNG, n_cells=12, boundary="wrap"),
    "kf.sim.nees": dict(truth=np.ones((3, 2)), mu=np.zeros((3, 2)), Sig=np.stack([I2] * 3)),
    "kf.sim.nees_band": dict(n_runs=10, dof=2, level=0.95),
    "kf.sim.particle_loop": dict(
        seed=0, n_particles=10, resample="stratified", global_start=False, starts=[POSE], labelled=True, kidnap=60,
        injection=0.05, dropout=(10, 20), motion_noise=1.0, sensor_noise=1.0, laps=1,
        landmarks=kf.sim.DEFAULT_LANDMARKS, sensor_range=4.0,
    ),
    "kf.sim.plain_and_gated": dict(z=[0.1, -0.2, 5.0], mu0=0.0, var0=1.0, R=0.01, Q=0.25, gate=3.0),
    "kf.sim.plaza_family": dict(log=PLAZA, n_particles=10, seed=0, steps=5),
    "kf.sim.process_noise": dict(dt=0.1, accel_var=1.0),
    "kf.sim.process_noise_of_odometry": dict(mu=POSE, u=ODOMETRY, dt=DT, M=M_ODO),
    "kf.sim.range_localize": dict(
        log=PLAZA, filter="ekf", speed_std=0.05, turn_std=0.02, noise_per="metre", range_std=0.5, scale=1.07,
        gate=3.0, start=POSE, start_std=[1.0, 1.0, 0.1], steps=5,
    ),
    "kf.sim.range_particles": dict(
        log=PLAZA, n_particles=10, seed=0, speed_std=0.5, turn_std=0.3, range_std=2.0, scale=1.07, start=POSE, steps=5,
        keep=[0, 5],
    ),
    "kf.sim.read_door": dict(cell=3, doors=DOORS, reliability=0.9, rng=RNG),
    "kf.sim.readings": dict(
        truth=POSES, landmarks=MARKS, sensor_range=4.0, range_std=0.1, bearing_std=0.03, xi=np.zeros((2, 2, 2)),
    ),
    "kf.sim.run_ekf": dict(flipped=True, seed=0, landmarks=kf.sim.TWO_LANDMARKS),
    "kf.sim.simulate_hallway": dict(
        n_cycles=2, motion_reliability=0.9, sensor_reliability=0.95, boundary="wall", doors=DOORS, seed=0,
    ),
    "kf.sim.simulate_line": dict(n_steps=5, step_std=0.05, sensor_std=0.4, speed=0.25, seed=0),
    "kf.sim.simulate_particle_hallway": dict(
        n_particles=20, n_cycles=2, motion_reliability=0.9, sensor_reliability=0.95, boundary="wall", seed=0,
    ),
    "kf.sim.simulate_robot": dict(
        u=SHORT, dt=DT, start=POSE, landmarks=MARKS, sensor_range=4.0, v_std=0.1, omega_std=0.05, range_std=0.1,
        bearing_std=0.03, seed=0, laps=1, kidnap=5, dropout=(2, 4), one_back=True,
    ),
    "kf.sim.simulate_target": dict(seed=0, sensor_std=1.0),
    "kf.sim.simulate_tracks": dict(n_tracks=2, n_steps=3, accel_std=1.0, sensor_std=1.0, dt=0.1, seed=0),
    "kf.sim.simulate_walk": dict(
        n_steps=3, u=1.0, R_true=0.01, Q_true=0.25, R=0.02, Q=0.2, velocity=0.1, x0=0.0, mu0=0.5, var0=0.25, seed=0,
    ),
    "kf.sim.smoothed": dict(run=RANGES),
    "kf.sim.start_cell": dict(rng=RNG, n_cells=12),
    "kf.sim.tuning_score": dict(
        speed_std=0.05, turn_std=0.02, noise_per="metre", range_std=0.5, scale=1.07, gate=3.0, log="Plaza2"
    ),
    "kf.sim.verdict": dict(mean_nees=2.0, band=(1.0, 4.0)),
    # ---------------------------------------------------------------- kf.data: the logs of real robots
    "kf.data.load_plaza": dict(name="Plaza1"),
    # ---------------------------------------------------------------- kf.demos: each builds a figure
    **{f"kf.demos.{name}": dict(seed=0) for name in kf.demos.__all__},
    "kf.demos.landmark_loop": dict(seed=0, filter=kf.ekf_localization_step),
}
# fmt: on

# ================================================================ the bad values
NAN, INF = float("nan"), float("inf")
# a variance, a covariance, a standard deviation or a noise scale: a negative one is bad too
SPREAD = re.compile(r"(Sig|S|R|Q|M|var)(\d|_\w+)?|\w+_var|\w*std|\w*noise")


def kind(name: str, value) -> str:
    """What sort of argument ``name`` is, from its valid value (and for a seed, its name)."""
    if name == "seed":
        return "seed"
    if isinstance(value, bool | np.bool_):
        return "flag"
    if isinstance(value, str):
        return "choice"
    if isinstance(value, Mapping):
        return "mapping"
    if isinstance(value, int | np.integer):
        return "whole"
    if isinstance(value, float):
        return "number"
    if isinstance(value, list | tuple | np.ndarray) and np.size(value) and np.asarray(value).dtype.kind in "biuf":
        return "array"
    if callable(value):
        return "callable"
    return "record"  # a run record, a generator, a list of runs: anything but what it is


def _spoilt(a: np.ndarray, entry: float) -> np.ndarray:
    """The array ``a`` as floats, its first entry replaced by ``entry``."""
    out = a.astype(float)
    out.flat[0] = entry
    return out


def bad_values(name: str, value) -> dict:
    """The bad values of argument ``name`` whose valid value is ``value``, by what is wrong with them."""
    sort = kind(name, value)
    if sort == "seed":
        return {"fraction": 1.5, "text": "3"}
    if sort in ("flag", "callable", "record"):
        return {"text": "x"}
    if sort == "choice":
        return {"unknown": "nope"}
    if sort == "mapping":
        first = next(iter(value))
        return {"text": "x", "nan": {**value, first: NAN}}
    bad = {"nan": NAN, "inf": INF, "text": "x"}
    if sort == "whole":
        bad["fraction"] = value + 0.5
    if sort == "array":
        a = np.asarray(value)
        bad.update(nan=_spoilt(a, NAN), inf=_spoilt(a, INF), shape=a[None])  # shape: one axis too many
        if a.dtype.kind in "iu":
            bad["fraction"] = _spoilt(a, a.flat[0] + 0.5)
    if SPREAD.fullmatch(name):
        bad["negative"] = -np.asarray(value) if sort == "array" else -1.0
    return bad


# Bad values that are legitimately accepted, (function, argument, what is wrong): why.  Each is checked to pass.
ACCEPTED = {
    ("kf.ekf_localization_step", "gate", "inf"): "gate=np.inf is no gate: every reading is used",
    ("kf.sim.localize_with_step", "gate", "inf"): "gate=np.inf is no gate: every reading is used",
    ("kf.sim.localize_with_step", "name", "unknown"): "name labels the step in messages: any text will do",
    ("kf.mvn_pdf", "x", "shape"): "x may be any stack of points, shape (..., n)",
    ("kf.sim.verdict", "mean_nees", "inf"): "the mean NEES of a flat ellipse the truth left: over-confident",
}


def _bad_calls(accepted: bool) -> list:
    """One param (function, argument, bad value) per bad value the table derives, refused or (``accepted``) not."""
    found = []
    for qualname, example in EXAMPLES.items():
        for name, value in example.items():
            for what, bad in bad_values(name, value).items():
                if ((qualname, name, what) in ACCEPTED) == accepted:
                    found.append(pytest.param(qualname, name, bad, id=f"{qualname}-{name}-{what}"))
    return found


def call(qualname: str, **changed):
    """The valid call of ``qualname``, with the arguments ``changed``."""
    return PUBLIC[qualname](**{**EXAMPLES[qualname], **changed})


def names(message: str, name: str) -> bool:
    """Whether ``message`` names the argument as the subject of its complaint: "Sig must ...", "dropout[0]
    must ...", "u of shape ... needs", "truth has shape ..." (so that the article a never counts as argument a)."""
    return re.search(rf"(?<![\w.]){re.escape(name)}(\[\w+\])? (must|has|of shape)\b", message) is not None


# ================================================================ the table
def test_every_public_function_and_demo_has_a_valid_call():
    assert sorted(EXAMPLES) == sorted(PUBLIC)


@pytest.mark.parametrize("qualname", list(EXAMPLES))
def test_the_valid_call_gives_every_argument_in_order(qualname):
    """Every argument of the signature has a valid value, so each gets its bad ones (``**drive`` has no name)."""
    parameters = inspect.signature(PUBLIC[qualname]).parameters.values()
    assert list(EXAMPLES[qualname]) == [p.name for p in parameters if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


@pytest.mark.parametrize("qualname", list(EXAMPLES))
def test_the_valid_call_succeeds(qualname):
    call(qualname)


def test_every_argument_gets_bad_values():
    assert all(bad_values(name, value) for example in EXAMPLES.values() for name, value in example.items())


def test_every_accepted_bad_value_is_one_the_table_derives():
    derived = {
        (q, name, what) for q, ex in EXAMPLES.items() for name, value in ex.items() for what in bad_values(name, value)
    }
    assert set(ACCEPTED) <= derived


# ================================================================ the bad calls
@pytest.mark.parametrize(("qualname", "name", "bad"), _bad_calls(accepted=False))
def test_a_bad_argument_is_refused_by_name(qualname, name, bad):
    with pytest.raises((ValueError, TypeError)) as raised:
        call(qualname, **{name: bad})
    assert names(str(raised.value), name), f"{name} is not named in: {raised.value}"


@pytest.mark.parametrize(("qualname", "name", "bad"), _bad_calls(accepted=True))
def test_an_accepted_bad_value_is_accepted(qualname, name, bad):
    """Each exception of ACCEPTED is still one: once refused, it comes off the list."""
    call(qualname, **{name: bad})
