import json, uuid, sys
cells = []
def md(s): cells.append({"cell_type": "markdown", "id": uuid.uuid4().hex[:8], "metadata": {}, "source": s.strip("\n").splitlines(keepends=True)})
def code(s): cells.append({"cell_type": "code", "execution_count": None, "id": uuid.uuid4().hex[:8], "metadata": {}, "outputs": [], "source": s.strip("\n").splitlines(keepends=True)})

md(r'''
# Chapter 12 · A real robot

*Previous: [Chapter 11 · The particle filter](11_particle_filter.ipynb)*

Symbols used throughout: [the notation table](notation.ipynb).

Every robot so far lived in a simulation we wrote, and every sensor in it kept a promise: its noise was
zero-mean, Gaussian, and exactly as large as the filter was told. A real sensor makes no such promise. This
chapter follows a real robot, CMU's in a campus plaza, through its wheel odometry and a radio that measures the
distance to four beacons at surveyed positions, and holds each filter of the course against the robot's
ground truth. The data are those of Djugash, Singh, Kantor and Zhang (ICRA 2006), as they ship with the GTSAM
library.

*Draft: the demo is a prototype.*
''')
code(r'''
import numpy as np

import kfcourse as kf
''')
md(r'''
## Meet the data

Two runs, Plaza1 and Plaza2. Each holds the odometry (distance driven and heading change per step), the ranges
(time, beacon, metres), the four beacons' positions and the ground truth pose.
''')
code(r'''
# NBVAL_CHECK_OUTPUT
logs = {name: kf.data.load_plaza(name) for name in kf.data.PLAZA_RUNS}
for name, log in logs.items():
    print(
        f"{name}: {log.distance.size} odometry steps and {log.range.size} ranges over {log.duration:.0f} s "
        f"and {log.path_length:.0f} m ({log.path_length / log.duration:.1f} m/s on average)"
    )
''')
md(r'''
### Dead reckoning, for real

Chapter 0's drift, with a real robot's wheels: integrate the odometry from the true start and compare.
''')
code(r'''
# NBVAL_CHECK_OUTPUT
for name, log in logs.items():
    drift = np.hypot(*(log.dead_reckoning()[:, :2] - log.truth[:, :2]).T)
    turn_error = np.abs(log.turn - kf.wrap_angle(np.diff(log.truth[:, 2]))).max()
    print(f"{name}: off by {np.median(drift):.1f} m at the median, {drift.max():.0f} m at worst; "
          f"largest heading-change error {turn_error:.2g} rad per step")
''')
md(r'''
Plaza1 drifts only about a metre, Plaza2 tens of metres. The last column says why, and it is a lesson about data,
not filters: in Plaza1 the ground truth's heading changes exactly as the odometry says, so its "true" heading
was made from the odometry itself. Only the wheels' distance can drift there. Before trusting any column of a log,
find out where it came from. (Plaza2's heading column even points backwards: it differs from the direction of
travel by $\pi$; `load_plaza` turns it round.)
''')
md(r'''
On the plaza, at the scale of the data: the four beacons (purple squares), the true path (grey, dotted) and the
dead reckoning (purple, dashed). Plaza1 mows the plaza in stripes for half an hour, its dead reckoning never far
from the truth:
''')
code(r'''
kf.plots.plaza_chart(logs["Plaza1"])
''')
md(r'''
Plaza2 drives laps of a triangle for seven minutes, and its dead reckoning spins off in loops:
''')
code(r'''
kf.plots.plaza_chart(logs["Plaza2"])
''')
md(r'''
### The ranges against the true distances
''')
code(r'''
# NBVAL_CHECK_OUTPUT
for name, log in logs.items():
    d = log.true_distance()
    slope, intercept = np.polyfit(d, log.range, 1)
    spread = np.std(log.range - slope * d - intercept)
    print(f"{name}: range = {slope:.3f} × distance {intercept:+.2f} m, spread {spread:.2f} m about that line")
''')
code(r'''
kf.plots.ranges_chart(logs["Plaza1"])
''')
md(r'''
The radio reads about 7 % long at every distance: a *scale* error, not noise. At 40 m that is almost 3 m, five times
the spread of the readings about the line. No filter that assumes zero-mean noise can average it away.

## The range-only model

One range to a beacon $b$ from the position $p = (x, y)$ of the pose $(x, y, \theta)$:

$$\hat z = h(x) = \lVert p - b \rVert = r, \qquad H = \begin{bmatrix} \dfrac{x - b_x}{r} & \dfrac{y - b_y}{r} & 0 \end{bmatrix} \tag{1}$$

$H$ is the unit vector from the beacon to the robot: a range says nothing about the heading, and nothing about
where on the circle of radius $z$ round the beacon the robot stands. It is chapter 7's range row, with the offset
written the other way round.
''')
code(r'''
# NBVAL_CHECK_OUTPUT
pose, beacon = np.array([2.0, 1.0, 0.3]), np.array([6.0, 4.0])
print("h =", kf.models.range_only(pose, beacon), " H =", kf.models.range_only_jacobian(pose, beacon))
''')
md(r'''
The update is chapter 7's, with a reading of one number:

$$S = H\bar\Sigma H^\top + Q, \qquad K = \bar\Sigma H^\top S^{-1} \tag{2}$$
$$\mu = \bar\mu + K (z - \hat z) \tag{3}$$
$$\Sigma = (I - KH)\bar\Sigma \tag{4}$$

## The EKF, tuned as the data sheet would suggest

`kf.sim.range_localize` runs the course's EKF over a log: the unicycle with each step's odometry (chapter 8), then
every range that arrived during the step, one at a time. Told what a data sheet would say (odometry noise of
5 cm/s and 0.02 rad/s, an unbiased radio with 0.5 m of noise), it starts at the true pose:
''')
code(r'''
# NBVAL_CHECK_OUTPUT
plaza1 = logs["Plaza1"]
first = kf.sim.range_localize(plaza1)
s = first.summary()
print(f"mean error {s['mean_error']:.2f} m; truth inside the 3σ ellipse at {s['inside']:.0%} of steps; "
      f"mean NEES {s['mean_nees']:.0f} (2 if honest): {s['verdict']}")
print(f"without the truth: mean NIS {first.nis.mean():.0f} (1 if honest); the innovations point to a scale of "
      f"{first.fitted_scale():.3f}")
''')
md(r'''
Three metres off, and sure to within centimetres: the truth lies outside its ellipse nearly all the time. The NEES
needs the truth, which a robot in the field does not have. The innovations do not: their normalised squares (the
NIS, chapter 8's gate statistic) average 20 where an honest filter's average 1, and the ranges read longer than the
filter predicts. A least-squares fit of $z \approx s\,\hat r$ over the innovations finds $s \approx 1.04$: the
filter has already dragged its estimate part of the way towards the long readings, so the fit sees only part of
the scale.

## Fix what the innovations found

**Once.** Tell the filter the scale ($h = s\,r$), run again, fit again:
''')
code(r'''
# NBVAL_CHECK_OUTPUT
scale = 1.0
for round_ in range(1, 5):
    run = kf.sim.range_localize(plaza1, scale=scale)
    print(f"round {round_}: scale {scale:.3f}, mean error {run.summary()['mean_error']:.2f} m, "
          f"innovations fit {run.fitted_scale():.3f}")
    scale = run.fitted_scale()  # the scale the innovations point to, for the next round
''')
md(r'''
**Online.** Or make the scale a fourth state, $x = (x, y, \theta, s)$, that the motion leaves alone and the ranges
move: $h = s\,r$, $H = [\,s\frac{x - b_x}{r},\ s\frac{y - b_y}{r},\ 0,\ r\,]$ (`kf.models.scaled_range`).
''')
code(r'''
# NBVAL_CHECK_OUTPUT
online = kf.sim.range_localize(plaza1, scale="online")
gated = kf.sim.range_localize(plaza1, scale="online", gate=3.0)
for label, run in (("scale as a state", online), ("and a 3σ gate", gated)):
    s = run.summary()
    print(f"{label}: s = {run.mu[-1, 3]:.4f} ± {np.sqrt(run.Sig[-1, 3, 3]):.4f}; mean error {s['mean_error']:.2f} m, "
          f"inside 3σ {s['inside']:.0%}, mean NEES {s['mean_nees']:.1f}: {s['verdict']}; "
          f"{np.count_nonzero(~run.used)} ranges refused")
''')
md(r'''
The position NEES of every pose, before and after the fix, against the band an honest filter's NEES lies in at
95 % of its steps (`kf.sim.NEES_BAND`, chi-square with two degrees of freedom):
''')
code(r'''
kf.plots.nees_chart(first, online, labels=["data sheet", "scale as a state"])
''')
md(r'''
The scale alone takes the error from about 3 m to 25 cm. The gate refuses about one range in a hundred and changes
little: once the scale is known, this radio has few outliers. The NEES is still above its band: the filter is still
a little too sure. What is left is the odometry's noise, and it teaches the last lesson of real data.

### Noise per second or per metre?

Tune the odometry noise on Plaza1 until the NEES is honest, then run the same numbers on Plaza2:
''')
code(r'''
# NBVAL_CHECK_OUTPUT
choices = {
    "per second": {"speed_std": 0.15, "turn_std": 0.02, "range_std": 0.5},
    "per metre": {"speed_std": 0.05, "turn_std": 0.01, "range_std": 0.7, "noise_per": "metre"},
}
for label, noise in choices.items():
    for name, log in logs.items():
        s = kf.sim.range_localize(log, scale="online", **noise).summary()
        print(f"noise {label}, {name}: mean error {s['mean_error']:.2f} m, mean NEES {s['mean_nees']:.1f}: {s['verdict']}")
''')
md(r'''
Chapter 8's odometry noise grows with time: so many m/s of speed noise per step. Plaza2 drives three times as fast
as Plaza1 (3.3 m/s against 1.0), in steps half as long (0.1 s against 0.2 s), so per metre driven it gets a seventh
of Plaza1's process noise, and the filter tuned on Plaza1 is over-confident there. Wheels slip per metre, not per
second: a noise whose variance grows with the distance driven, $\sigma^2 |d|$ per step of length $d$, is honest on
both runs.

## Start from nowhere

Chapter 11 showed the EKF failing to find a robot it had lost. Here, with four beacons around the plaza, a range-only
EKF given a wide first ellipse finds the robot from a wrong start:
''')
code(r'''
# NBVAL_CHECK_OUTPUT
plaza2 = logs["Plaza2"]
for guess in ([0.0, 0.0, 0.0], [-40.0, 40.0, 1.0], [10.0, 10.0, -2.0]):
    run = kf.sim.range_localize(plaza2, scale=1.07, start=guess, start_std=(30.0, 30.0, 3.0))
    print(f"EKF from {guess}: {run.error[0]:.0f} m off at the start, {np.median(run.error[1000:]):.2f} m after 100 s")
''')
md(r'''
Four circles meet in one point. With two beacons, two circles meet in two points, mirror images across the line
through the beacons, and an EKF started on the wrong side follows the mirrored path. The particle filter of chapter
11 spreads its cloud over the whole plaza and lets the ranges choose:
''')
code(r'''
# NBVAL_CHECK_OUTPUT
for seed in range(3):
    pf = kf.sim.range_particles(plaza2, n_particles=1000, seed=seed, steps=1000)
    s = pf.summary()
    print(f"PF, seed {seed}: found after {s['found_after']:.1f} s; then {s['error_after']:.2f} m off on average")
''')
md(r'''
## Smoothing: what we know afterwards

A filter's estimate at time $t$ uses the readings up to $t$. Once the run is over, the later readings know more about
$t$ too. The Rauch–Tung–Striebel smoother runs backwards over the filter's stored predictions and estimates:

$$C_k = \Sigma_k F_{k+1}^\top \bar\Sigma_{k+1}^{-1} \tag{5}$$
$$\mu^s_k = \mu_k + C_k(\mu^s_{k+1} - \bar\mu_{k+1}) \tag{6}$$
$$\Sigma^s_k = \Sigma_k + C_k(\Sigma^s_{k+1} - \bar\Sigma_{k+1})C_k^\top \tag{7}$$

($F_{k+1}$ is the motion's Jacobian $G$ at $\mu_k$ for the EKF: `kf.ekf_rts_smoother`.) Beside it, GTSAM solves the
whole run at once as a factor graph: a pose per step, the odometry between them, a range factor per reading with a
robust loss. That is the door to SLAM, where the beacons' positions are unknown too.
''')
code(r'''
# NBVAL_CHECK_OUTPUT
ekf = kf.sim.range_localize(plaza2, scale=1.07)
smoothed, graph = kf.sim.smoothed(ekf), kf.sim.factor_graph(plaza2)
for label, run in (("EKF", ekf), ("RTS smoother", smoothed), ("factor graph", graph)):
    s = run.summary()
    print(f"{label:<13} mean error {s['mean_error']:.2f} m, 95 % under {s['p95_error']:.2f} m")
''')
md(r'''
On the plaza, the three paths lie on the truth and on one another, where the dead reckoning is tens of metres off:
''')
code(r'''
kf.plots.plaza_chart(plaza2, ekf, smoothed, graph, labels=["EKF", "RTS smoother", "factor graph"])
''')
md(r'''
### The real run

Everything above in one picture. Choose a filter and play the log: the orange arcs are the ranges as they arrive,
the strip under the plaza the NEES of every pose against its honest band. Give the EKF the scale and the gate,
then take its start away; turn its trust in the odometry (R) or in the ranges (Q) up and down and watch the strip
leave its band; let the particle filter find the robot from nowhere; overlay the smoother's path. A setting the demo
has not run yet takes a second or two: it runs the whole log once, and keeps it.
''')
code(r'''
kf.demos.real_run(seed=0)
''')
md(r'''
## Your turn

**(a) The range update.** Write equations (1)-(4) for one range:
''')
code(r'''
def my_range_update(mu_bar, Sig_bar, z, beacon, Q):
    """EKF update of a pose [x, y, theta] with one range z (shape (1,)) to a beacon [bx, by]."""
    raise NotImplementedError("write equations (1)-(4)")
''')
code(r'''
kf.check.range_update(my_range_update)
''')
md(r'''
**(b) Blind tuning.** Choose the noises on Plaza1 only (`kf.sim.range_localize(logs["Plaza1"], ...)`), then let the
scorer run them on Plaza2, which you never looked at:
''')
code(r'''
print(kf.sim.tuning_score(speed_std=0.05, turn_std=0.02, range_std=0.5, scale=1.0))
''')
nb = {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"}, "language_info": {"codemirror_mode": {"name": "ipython", "version": 3}, "file_extension": ".py", "mimetype": "text/x-python", "name": "python", "nbconvert_exporter": "python", "pygments_lexer": "ipython3", "version": "3.11.7"}}, "nbformat": 4, "nbformat_minor": 5}
json.dump(nb, open(sys.argv[1], "w"), indent=1, ensure_ascii=False); open(sys.argv[1], "a").write("\n")
