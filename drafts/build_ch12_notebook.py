"""Build notebooks/12_real_robot.ipynb (clean, no outputs): python drafts/build_ch12_notebook.py PATH."""

import hashlib
import json
import sys

cells = []


def _id(kind, source):
    return hashlib.md5(f"{len(cells)}:{kind}:{source[:60]}".encode()).hexdigest()[:8]


def md(s):
    s = s.strip("\n")
    cells.append({"cell_type": "markdown", "id": _id("md", s), "metadata": {}, "source": s.splitlines(keepends=True)})


def code(s):
    s = s.strip("\n")
    cells.append(
        {
            "cell_type": "code",
            "execution_count": None,
            "id": _id("code", s),
            "metadata": {},
            "outputs": [],
            "source": s.splitlines(keepends=True),
        }
    )


md(r"""
# Chapter 12 · A real robot

*Previous: [Chapter 11 · The particle filter](11_particle_filter.ipynb)*

Symbols used throughout: [the notation table](notation.ipynb).

Every robot so far lived in a simulation we wrote, and every sensor in it kept a promise: its noise was zero-mean,
Gaussian, and exactly as large as the filter was told. A real sensor makes no such promise. This chapter follows a
real robot, CMU's, through a campus plaza: its wheel odometry, and a radio that measures its distance to four
beacons at surveyed positions. Each filter of the course is held against the robot's ground truth, and the first
one is not honest.

The data are those of Djugash, Singh, Kantor and Zhang (*Range-only SLAM for robots operating cooperatively with
sensor networks*, ICRA 2006), as they ship with the GTSAM library (`pip install gtsam`, which the course's setup
installs; there is no GTSAM for Windows: use Binder or WSL there).

*Run All takes about 45 s on a quiet 2-core machine: every filter runs over logs of seven and thirty minutes. The
slowest cell, the family table, takes about 8 s.*

**What you will learn**

- how to meet a real log: what each column is, where it came from, and what the sensor really does against the
  truth (a range that reads 7 % long is a *bias*, which no filter averages away);
- the range-only model $h = \lVert p - b\rVert$ and its Jacobian, and an EKF over real odometry and ranges;
- how NEES (with the truth) and the innovations (without it) show a filter over-confident, and how to fix what
  they found: the radio's scale estimated once, or online as a fourth state, and chapter 8's gate;
- why odometry noise belongs to the metre driven, not the second;
- an unknown start: when a range-only EKF still finds the robot, when it follows a mirror image, and the particle
  filter that finds it from nowhere;
- smoothing: the Rauch–Tung–Striebel smoother over the whole run, and GTSAM's factor graph beside it;
- the family table of chapter 11, measured again on real data.
""")
code(r"""
import numpy as np

import kfcourse as kf
""")
md(r"""
## Meet the data

Two runs, Plaza1 and Plaza2, each with four parts: the odometry (the distance driven and the change of heading of
each step, from the wheels), the ranges (when, to which beacon, how many metres), the beacons' four surveyed
positions, and the ground truth pose $(x, y, \theta)$ that the authors recorded beside the run.
""")
code(r"""
# NBVAL_CHECK_OUTPUT
logs = {name: kf.data.load_plaza(name) for name in kf.data.PLAZA_RUNS}
for name, log in logs.items():
    print(
        f"{name}: {log.distance.size} odometry steps and {log.range.size} ranges over {log.duration:.0f} s "
        f"and {log.path_length:.0f} m ({log.path_length / log.duration:.1f} m/s on average)"
    )
""")
md(r"""
### Dead reckoning, for real

Chapter 0's drift, with a real robot's wheels: integrate the odometry from the true start and compare it with the
truth. The last two numbers compare the heading: each step's change in the odometry against the truth's, and the
dead-reckoned heading, those changes added up, against the truth's heading.
""")
code(r"""
# NBVAL_CHECK_OUTPUT
for name, log in logs.items():
    drift = np.hypot(*(log.dead_reckoning()[:, :2] - log.truth[:, :2]).T)
    turn_error = np.abs(log.turn - kf.wrap_angle(np.diff(log.truth[:, 2]))).max()
    heading_error = np.abs(kf.wrap_angle(log.dead_reckoning()[:, 2] - log.truth[:, 2])).max()
    print(f"{name}: off by {drift.mean():.1f} m on average (median {np.median(drift):.1f} m), {drift.max():.0f} m "
          f"at worst; heading change against the truth's: at most {turn_error:.1g} rad in a step, "
          f"{heading_error:.1f} rad at worst, added up")
""")
md(r"""
Plaza1 drifts a metre or two, Plaza2 tens of metres. The last number says why, and it is a lesson about data, not
filters. In Plaza1 the truth's heading turns *exactly* as the odometry says, to the last digit a float holds: its
"true" heading was made from the odometry itself, and only the distance driven can drift there. In Plaza2 the two
differ, as two real instruments do: by a thousandth of a radian a step, which adds up to radians, and a heading
radians off sends the dead reckoning tens of metres astray. Before trusting a column of a log, find out where it came from. (Plaza2's
heading column even points backwards, a half turn from the direction of travel; `load_plaza` turns it round.)

On the plaza, at the scale of the data: the four beacons (purple squares), the true path (grey, dotted) and the
dead reckoning (purple, dashed). Plaza1 mows the plaza in stripes for half an hour:
""")
code(r"""
kf.plots.plaza_chart(logs["Plaza1"])
""")
md(r"""
Plaza2 drives laps of a triangle for seven minutes, and its dead reckoning spins off in loops:
""")
code(r"""
kf.plots.plaza_chart(logs["Plaza2"])
""")
md(r"""
### The ranges against the true distances

Each range beside the distance from the true position to its beacon, with a straight line fitted through them:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
for name, log in logs.items():
    d = log.true_distance()
    slope, intercept = np.polyfit(d, log.range, 1)
    spread = np.std(log.range - slope * d - intercept)
    print(f"{name}: range = {slope:.3f} × distance {intercept:+.2f} m, spread {spread:.2f} m about that line")
""")
code(r"""
kf.plots.ranges_chart(logs["Plaza1"])
""")
md(r"""
The radio reads about 7 % long at every distance: a *scale* error, not noise. At 40 m that is almost 3 m, five times
the spread of the readings about the line. No filter that assumes zero-mean noise can average it away.

## The range-only model

One range to a beacon $b$ from the position $p = (x, y)$ of the pose $(x, y, \theta)$: the predicted reading is the
distance $r$ from the pose to the beacon,

$$\hat z = h(x) = \lVert p - b \rVert = r, \qquad H = \begin{bmatrix} \dfrac{x - b_x}{r} & \dfrac{y - b_y}{r} & 0 \end{bmatrix} \tag{1}$$

$H$ is the unit vector from the beacon to the robot. A range says nothing about the heading, and nothing about where
on the circle of radius $z$ round the beacon the robot stands. It is chapter 7's range row, with the offset written
the other way round.
""")
code(r"""
# NBVAL_CHECK_OUTPUT
pose, beacon = np.array([2.0, 1.0, 0.3]), np.array([6.0, 4.0])
print("h =", kf.models.range_only(pose, beacon), " H =", kf.models.range_only_jacobian(pose, beacon))
""")
md(r"""
The update is chapter 7's, with a reading of one number:

$$S = H\bar\Sigma H^\top + Q, \qquad K = \bar\Sigma H^\top S^{-1} \tag{2}$$
$$\mu = \bar\mu + K (z - \hat z) \tag{3}$$
$$\Sigma = (I - KH)\bar\Sigma \tag{4}$$

The worked example: the robot believed at that pose with $\bar\Sigma = \mathrm{diag}(0.5, 0.5, 0.1)$, and the radio
reading 5.35 m with a standard deviation of 0.5 m ($Q = 0.25$):
""")
code(r"""
# NBVAL_CHECK_OUTPUT
mu, Sig = kf.range_update(pose, np.diag([0.5, 0.5, 0.1]), np.array([5.35]), beacon, np.array([[0.25]]))
print("mu =", mu.round(3), " diagonal of Sigma =", np.diag(Sig).round(3))
""")
md(r"""
The reading is 0.35 m longer than the predicted 5 m. With $S = 0.5 + 0.25 = 0.75$ the gain is
$K = \bar\Sigma H^\top / S = (-0.53, -0.40, 0)$, so the robot moves $0.667 \times 0.35 = 0.23$ m straight away from
the beacon, and its ellipse shrinks along that line only. The heading does not move: nothing in $\bar\Sigma$ ties it
to the position.

## The EKF, tuned as the data sheet would suggest

`kf.sim.range_localize` runs the course's EKF over a log: chapter 8's unicycle with each step's odometry, then every
range that arrived during the step, one at a time. Told what a data sheet would say (odometry noise of 5 cm/s and
0.02 rad/s, an unbiased radio with 0.5 m of noise), and started at the true pose:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
plaza1 = logs["Plaza1"]
first = kf.sim.range_localize(plaza1)
s = first.summary()
sigma = np.sqrt(np.linalg.eigvalsh(first.Sig[:, :2, :2]))  # the ellipse's half-axes at 1σ, every pose
print(f"mean error {s['mean_error']:.2f} m; 1σ half-axes {np.median(sigma[:, 0]):.2f} and {np.median(sigma[:, 1]):.2f} m "
      f"(median); truth inside the 3σ ellipse at {s['inside']:.0%} of poses; mean NEES {s['mean_nees']:.0f} "
      f"(2 if honest): {s['verdict']}")
print(f"without the truth: mean NIS {first.nis.mean():.1f} (1 if honest); z against r̂ fits a scale of "
      f"{first.fitted_scale():.3f}")
""")
md(r"""
Three metres off, and sure to within a few decimetres: the truth lies outside the 3σ ellipse at nearly every pose.
The NEES needs the truth, which a robot in the field does not have. The innovations do not. Their normalised squares
(the NIS, chapter 8's gate statistic) average about twenty where an honest filter's average 1: the ranges disagree
with the filter far more than it expects.

They also say how. Call $\hat r$ the distance from the filter's prediction to the beacon, just before a range $z$
arrives. If the radio reads $z \approx s\,\hat r$, a least-squares fit over every range gives
$s = \sum z \hat r / \sum \hat r^2$: 1.036 here, a radio that reads long. It is less than the truth's 1.07 because
$\hat r$ is not the true distance. Each earlier long reading has already pulled the estimate to where the long
ranges fit better, so $\hat r$ is itself too long, and the ratio too small.

## Fix what the innovations found

**Offline, by rounds.** Tell the filter the scale ($\hat z = s\,r$), run the log again, fit again:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
scale = 1.0
for round_ in range(1, 5):
    run = kf.sim.range_localize(plaza1, scale=scale)
    print(f"round {round_}: scale {scale:.3f}, mean error {run.summary()['mean_error']:.2f} m, "
          f"innovations fit {run.fitted_scale():.3f}")
    scale = run.fitted_scale()  # the scale the innovations point to, for the next round
""")
md(r"""
Each round the fit is still a little low, for the same reason, so the scale creeps up towards 1.07 from below and
the error falls with it: four passes over the log bring the error from three metres to a third of one. The filter
can instead learn the scale while it runs.

**Online.** Make the scale a fourth entry of the state, $(x, y, \theta, s)$, that the motion leaves alone and the
ranges move. The filter starts it at $s = 1$ with a standard deviation of 0.1, so that the ranges can move it, and

$$\hat z = s\,r, \qquad H = \begin{bmatrix} s\dfrac{x - b_x}{r} & s\dfrac{y - b_y}{r} & 0 & r \end{bmatrix}$$

(`kf.models.scaled_range` and `kf.models.scaled_range_jacobian`). The last column is new: a long reading can now be
explained by a larger $s$ as well as by a position further away, and the beacons round the plaza tell the two
apart. Add chapter 8's validation gate, which refuses a range whose innovation lies more than 3σ off:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
online = kf.sim.range_localize(plaza1, scale="online")
gated = kf.sim.range_localize(plaza1, scale="online", gate=3.0)
for label, run in (("scale as a state", online), ("and a 3σ gate", gated)):
    s = run.summary()
    print(f"{label}: s = {run.mu[-1, 3]:.4f} ± {np.sqrt(run.Sig[-1, 3, 3]):.4f}; mean error {s['mean_error']:.2f} m, "
          f"inside 3σ {s['inside']:.0%}, mean NEES {s['mean_nees']:.1f}: {s['verdict']}; "
          f"{np.count_nonzero(~run.used)} ranges refused")
""")
md(r"""
The filter never saw the truth, and its scale agrees with the line fitted *with* the truth above to within
0.001. The scale alone takes the error from about 3 m to a quarter of a metre and puts the truth back inside the
ellipse at nine poses in ten. The gate refuses about one range in a hundred and changes little: once the scale is
known, this radio has few outliers.

The position NEES of every pose, before and after, against the band an honest filter's NEES lies in at 95 % of its
poses (`kf.sim.NEES_BAND`: chi-square with two degrees of freedom):
""")
code(r"""
kf.plots.nees_chart(first, online, labels=["data sheet", "scale as a state"])
""")
md(r"""
Most poses are back in the band. Their average, near 5, is still above the honest 2, and more than the honest
2.5 % of poses lie above the band: the filter is still a little too sure of itself. What is left is the odometry's
noise, and it teaches the last lesson of real data.

### Noise per second or per metre?

The data sheet's odometry noise is too small: raised until the NEES on Plaza1 is honest, it becomes 0.15 m/s and
0.02 rad/s. Chapter 8's odometry noise is a noise *per second*: per step of $\Delta t$ seconds the distance driven
gets a variance $\sigma^2 \Delta t^2$. Wheels slip as they roll, though, so the noise may instead grow with the
distance driven: a variance $\sigma^2 |V| \Delta t$ for a step at the speed $V$ (`noise_per="metre"`, $\sigma$ in
metres, or radians, per square-root metre). At Plaza1's pace, $V = 0.96$ m/s in steps of $\Delta t = 0.2$ s, the
two are the same noise when $\sigma_{\text{metre}} = \sigma_{\text{second}} \sqrt{\Delta t / V} = 0.46\,\sigma_{\text{second}}$. Both choices, tuned
on Plaza1, then run on Plaza2 as well:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
per_second = {"speed_std": 0.15, "turn_std": 0.02, "range_std": 0.5}
per_metre = {"speed_std": 0.15 * 0.46, "turn_std": 0.02 * 0.46, "range_std": 0.5, "noise_per": "metre"}
for label, noise in (("per second", per_second), ("per metre", per_metre)):
    for name, log in logs.items():
        s = kf.sim.range_localize(log, scale="online", **noise).summary()
        print(f"noise {label}, {name}: mean error {s['mean_error']:.2f} m, mean NEES {s['mean_nees']:.1f}: {s['verdict']}")
""")
md(r"""
On Plaza1 the two are honest. On Plaza2 only the noise per metre is. Plaza2 drives three times as fast as Plaza1
(3.3 m/s against 1.0) in steps half as long (0.1 s against 0.2). Per metre driven, a noise per second gives a step
the variance $\sigma^2 \Delta t^2 / (V \Delta t) = \sigma^2 \Delta t / V$: $0.21\,\sigma^2$ on Plaza1,
$0.03\,\sigma^2$ on Plaza2, a seventh as much. Tuned on Plaza1, it is over-confident on Plaza2. A noise per metre
does not care how fast the robot drives or how often it is sampled. Tuned once more on Plaza1, with the scale online
and the gate, the course's choice is 0.05 and 0.01 per square-root metre and a 0.7 m radio (`kf.sim.TUNED`, mean NEES
2.1 on Plaza1). The family table and the demo below use it.

## Start from nowhere

Chapter 11's EKF, started on the wrong side of a symmetric map, converged there, confidently. Here, with four beacons
round the plaza, a range-only EKF given a first ellipse as wide as the plaza finds the robot from a wrong start:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
plaza2 = logs["Plaza2"]
print("the true start:", np.round(plaza2.truth[0], 1))
for guess in ([0.0, 0.0, 0.0], [-40.0, 40.0, 1.0], [-20.0, 0.0, -2.0]):
    run = kf.sim.range_localize(plaza2, scale=1.07, start=guess, start_std=(30.0, 30.0, 3.0))
    print(f"EKF from {guess}: {run.error[0]:.0f} m off at the start, {np.median(run.error[1000:]):.2f} m after 100 s")
""")
md(r"""
Three circles meet in one point, when their beacons are not on one line; the fourth checks them. Two circles meet in
two points, mirror images of each other across the line through their beacons. Plaza1, keeping only its ranges to
beacons 2 and 3, with the EKF started at the mirror image of the true start (and a first ellipse of 10 m):
""")
code(r"""
# NBVAL_CHECK_OUTPUT
two = plaza1.only([2, 3])
mirror = plaza1.mirrored_start([2, 3])
lost = kf.sim.range_localize(two, scale=1.07, start=mirror, start_std=(10.0, 10.0, 1.0), steps=2000)
print(f"EKF from the mirror image: {np.median(lost.error):.0f} m off at the median, never within "
      f"{lost.error.min():.0f} m of the robot: {lost.summary()['verdict']}")
""")
md(r"""
It follows the reflected path for over a minute, sure of itself, and never comes back to the robot: every range
agrees with the mirror image as well as with the truth.
The particle filter of chapter 11 spreads its cloud over the whole plaza, beyond the beacons by 20 m on every side,
and over every heading, and lets the ranges choose. The same two beacons, five seeds, each cloud 1 000 particles:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
for seed in range(5):
    s = kf.sim.range_particles(two, n_particles=1000, seed=seed, steps=1000).summary()
    print(f"PF, seed {seed}: " + (f"found after {s['found_after']:.0f} s, then {s['error_after']:.2f} m off on average"
                                  if s["found"] is not None else "not found in 200 s"))
""")
md(r"""
"Found" means the estimate (the cloud's mean) comes within 5 m of the robot and stays there to the end of the run.
Most clouds find the robot within a minute and a half. A cloud can lose as well: when the first ranges happen to fit
the mirror better, the particles near the truth are resampled away, and the cloud holds the mirror image
(chapter 11's particle deprivation).

To search, the particle filter is told far more noise than the robot has: 0.5 m/s and 0.3 rad/s on the odometry and
2 m on the ranges (`kf.sim.range_particles`, with the scale 1.07). A thousand particles over a plaza of about
10 000 m² leave none within centimetres of the truth, and the ranges say nothing about heading until the robot
drives: the odometry's noise must keep spreading the survivors over positions and headings, and the range noise must
let a particle a metre or two off keep some weight. The price is paid once the robot is found: the cloud stays wider
than its error, and hearing two beacons, the estimate stays most of a metre off.

## Smoothing: what we know afterwards

A filter's estimate at time $k$ uses the readings up to $k$. Once the run is over, the later readings know more
about $k$ too. The Rauch–Tung–Striebel smoother runs backwards over the filter's stored estimates $(\mu_k, \Sigma_k)$
and predictions $(\bar\mu_{k+1}, \bar\Sigma_{k+1})$, from the last pose, where the smoothed estimate is the
filter's:

$$C_k = \Sigma_k G_{k+1}^\top \bar\Sigma_{k+1}^{-1} \tag{5}$$
$$\mu^s_k = \mu_k + C_k(\mu^s_{k+1} - \bar\mu_{k+1}) \tag{6}$$
$$\Sigma^s_k = \Sigma_k + C_k(\Sigma^s_{k+1} - \bar\Sigma_{k+1})C_k^\top \tag{7}$$

$G_{k+1}$ is the motion's Jacobian at $\mu_k$ (chapter 7). $\mu^s_{k+1} - \bar\mu_{k+1}$ is what the later readings
taught about step $k+1$ beyond the prediction (its heading difference wrapped), and $C_k$ is a gain, like $K$: how
much of that lesson to carry back to step $k$. It is large where the filter was unsure at $k$ and the motion was
certain, and small the other way round. `kf.ekf_rts_smoother` (`kf.rts_smoother` for a linear model) holds the three
equations.

Beside it, GTSAM solves the whole run at once as a *factor graph*: a pose per step, the odometry between them, a
range factor per reading under Huber's robust loss (squared up to 1.345σ, linear beyond, so that an outlier pulls
less). That is the door to SLAM, where the beacons' positions are unknown too. All three are given the data
sheet's noise and the scale 1.07, so that they differ mainly in how they use the readings (the graph adds a little sideways odometry noise, and Huber's
loss):
""")
code(r"""
# NBVAL_CHECK_OUTPUT
ekf = kf.sim.range_localize(plaza2, scale=1.07)
smoothed, graph = kf.sim.smoothed(ekf), kf.sim.factor_graph(plaza2)
for label, run in (("EKF", ekf), ("RTS smoother", smoothed), ("factor graph", graph)):
    s = run.summary()
    print(f"{label:<13} mean error {s['mean_error']:.2f} m, 95 % under {s['p95_error']:.2f} m")
""")
md(r"""
On the plaza the three paths lie on the truth and on one another, where the dead reckoning is tens of metres off.
Their differences are a few decimetres, which the numbers above tell and the map at this scale cannot:
""")
code(r"""
kf.plots.plaza_chart(plaza2, ekf, smoothed, graph, labels=["EKF", "RTS smoother", "factor graph"])
""")
md(r"""
The smoother and the factor graph agree closely: over a run whose models are nearly linear at the scale of its
errors, the EKF's forward pass followed by the RTS backward pass gives almost the batch solution.

## The family on real data

Chapter 11 closed on the family measured over simulated laps. `kf.sim.plaza_family` measures it again over Plaza2's
first 1 500 steps (150 s). The Kalman filters are tuned as above (`kf.sim.TUNED`); every filter starts at the true
pose, except in the global start column:
""")
code(r"""
family = kf.sim.plaza_family(plaza2, steps=1500)
print(family.table())
""")
md(r"""
The costs per step are this machine's, and yours will differ. What the table says, whatever the machine:
""")
code(r"""
# NBVAL_CHECK_OUTPUT
row = {r.name: r for r in family.rows}
ekf_row, ukf_row, pf_row = row["EKF, tuned"], row["UKF, tuned"], row["PF, N = 1000"]
print("EKF, data sheet: metres off, the truth inside 3σ at under 10 % of poses:",
      row["EKF, data sheet"].mean_error > 2 and row["EKF, data sheet"].inside < 0.1)
print("EKF and UKF, tuned: within 5 cm of each other:", abs(ekf_row.mean_error - ukf_row.mean_error) < 0.05)
print("PF: within 10 cm of the tuned EKF:", abs(pf_row.mean_error - ekf_row.mean_error) < 0.1)
print("global start found: EKF", ekf_row.global_start, "| UKF", ukf_row.global_start, "| PF", pf_row.global_start)
print("RTS smoother below the EKF:", row["RTS smoother"].mean_error < ekf_row.mean_error)
""")
md(r"""
Which of chapter 11's conclusions survive reality?

- **The EKF and the UKF are level.** They still are: at tens of metres a range is nearly a straight function of the
  position, so the UKF's better handling of curvature buys nothing.
- **The Kalman filters are honest.** Only once they are told the truth about the sensor. Told the data sheet, the EKF
  is metres off and almost never has the truth inside its ellipse; the scale, the gate and a noise per metre, all
  found from the data, make it honest.
- **Only the particle filter finds a robot from nowhere.** With four beacons the EKF found it too, from the plaza's
  middle, though not always: from the same start as above but with its gate, the demo below shows it never recovers. The
  UKF, from the plaza's middle, did not either, for the same reason: its first ranges made it sure of a wrong place,
  and its gate then refused the ranges that would have brought it back. With two beacons the EKF followed the mirror, and the particle
  filter found the robot, most of the time.
- **The particle filter is as accurate as the EKF.** From a known start, with four beacons, it still is, within a
  few centimetres, though its cloud, told the wide noise it needs to search, is wider than its error.
- **The smoother is new.** After the run, the readings that came later improve the estimates, on average.

### The real run

Everything above in one picture. Choose a filter and play the log: the orange arcs are the ranges as they arrive, the
strip under the plaza the NEES of every pose against its band. A setting the demo has not run yet takes a second or
two: it runs the whole log once, and keeps it.
""")
code(r"""
kf.demos.real_run(seed=0)
""")
md(r"""
**Try this**

1. The demo opens on the EKF with chapter 12's noise but the radio's scale taken as 1, though its ranges read about
   7 % long. Press **Run** (or drag *t (s)*): the NEES strip stays far above its shaded band, and the verdict under
   the picture says *over-confident* (mean NEES about 180) while the filter is about 3.7 m off on average. Choose
   **EKF + scale and gate**: the strip comes down into its band and stays there at about 96 % of the poses (an
   honest filter's 95 %), the verdict turns *honest*, and the filter is 0.35 m off on average. Press **smoothed**:
   the pale path lies closer to the truth still, about 0.25 m off on average.
2. Keep **EKF + scale and gate** and move *filter's Q ×* down to 0.10: the filter now believes its ranges to 22 cm
   (0.7 m × √0.1). The strip climbs above its band at most poses, the verdict turns *over-confident*, and the gate
   starts refusing good ranges (dotted arcs: about a quarter of them). At 0.010 it refuses most of them and wanders
   off, more than 10 m from the robot for much of the log. Put Q back to 1.0 and move *filter's R ×* up to 100
   (1.0e+2): the strip sinks below its dotted average, to the middle of its band, and the verdict turns *timid*
   (mean NEES under 1), while the filter is 0.53 m off, half as much again as at R ×1: a timid filter is safe, but
   its ellipse tells you less than it could.
3. Put R back to 1.0 and set *start* to **unknown**: the filter starts at the plaza's origin, 57 m from the robot,
   with an ellipse as wide as the plaza. With **EKF + scale and gate**, the first ranges shrink its 3σ ellipse to a
   few metres within a second while the estimate is still about 20 m off; from then on the gate refuses the ranges
   that would pull it back (most of the log's, dotted), and the filter is lost for good: *over-confident*, the truth
   outside its ellipse at almost every pose, tens of metres off on average. Now choose **EKF** and press **scale**
   (no gate): from the same start the ranges to the four beacons pull it onto the robot, and from t = 40 s on it
   stays within 2 m of it. Its verdict still reads *over-confident*: the first half-minute's search weighs on the
   mean NEES, and from t = 40 s on its NEES averages about 2.6, honest. A gate protects a filter that knows where it is, and locks out the help of one that
   does not.
4. Choose **PF**, the start still unknown: its particles start spread over the whole plaza. Drag *t (s)* to 0: the
   estimate stands mid-plaza, more than 10 m from the robot, its 3σ ellipse so wide that its outline lies off the
   map (the description: the truth inside it). Press **Run**: within the first minute the estimate lands on the
   robot and stays within 2 m of it to the end of the log. So it does for every seed from 0 to 9
   (`kf.demos.real_run(seed=1)`, …). The verdict under the picture depends on the search: while the cloud
   searches, its mean can stray metres from the robot with the truth outside its ellipse, and those poses weigh on
   the whole run's mean NEES (seed 0: *over-confident*). From the first minute on its NEES averages under 1 in every
   seed, *timid*, as a cloud told wide noise is.
""")
md(r"""
## Your turn

**(a) The range update.** Write equations (1)-(4) for one range, then let the checker try it: first on the worked
example above, then on the hard cases (a beacon straight ahead, a tiny range, a belief whose heading is tied to its
position). A robot standing exactly on its beacon has no direction to it, and $H$ is $0/0$ there: raise a
`ValueError` for it, as `kf.range_update` does.
""")
code(r"""
def my_range_update(mu_bar, Sig_bar, z, beacon, Q):
    "EKF update of a pose [x, y, theta] with one range z (shape (1,)) to a beacon [bx, by]; Q is (1, 1)."
    raise NotImplementedError("write equations (1)-(4)")
""")
code(r"""
kf.check.range_update(my_range_update)
""")
md(r"""
Then compare it with `kf.range_update`, the course's own, in `kfcourse/filters/ranging.py`.

**(b) A blind tuning round.** In the field you tune on the runs you have and are judged on the next one. The
chapter played that round once, tuning on Plaza1 and judging on Plaza2, and its choice (`kf.sim.TUNED`) scores
0.35 m, honest. Play it yourself, aiming for an honest verdict with the NEES in its band at about 95 % of the poses:
between sensible choices the error hardly changes, and the verdict is what tells them apart. Choose the odometry noise (per second or per metre),
the radio's noise, the scale (a number, or `"online"`) and the gate (`gate=`, in standard deviations, or `None`)
by running `kf.sim.range_localize(logs["Plaza1"], ...)` only. Then let the scorer run your choice once on Plaza2, with
the same arguments. It reports the mean error, the share of poses whose NEES lies in its band, and a verdict: honest,
timid or over-confident. The data sheet's choice first:
""")
code(r"""
print(kf.sim.tuning_score(speed_std=0.05, turn_std=0.02, range_std=0.5, scale=1.0))
""")
md(r"""
## Questions

**1.** A range says nothing about the heading: the last entry of $H$ is 0, and in the worked example the heading did
not move. Yet over a log the ranges keep the EKF's heading sure, where dead reckoning's doubt about it grows without
end. How?

<details><summary>Answer</summary>

Through $\bar\Sigma$. As the robot drives, a heading error becomes a position error sideways to the path: the motion's
Jacobian $G$ carries $\theta$'s doubt into $x$ and $y$, and $\bar\Sigma$ then holds a correlation between the heading
and the position. The gain $K = \bar\Sigma H^\top S^{-1}$ reads $\bar\Sigma$'s whole column, so a range that moves the
position moves the heading too, by as much as the two are tied. In the worked example $\bar\Sigma$ was diagonal, and
nothing tied them.

</details>

**2.** The smoother's estimate of a pose is better than the filter's. Why can a robot not drive with it?

<details><summary>Answer</summary>

Because it uses readings that arrive after the pose: at step $k$ the smoother needs the ranges of every later step,
and the robot has to act at step $k$. A smoother is for what you know afterwards: a map built from a drive, the
ground truth of a test, the path of a delivery to be audited. A robot that must act can only smooth over a window
that has already passed, as a factor graph over its last few seconds does.

</details>
""")
code(r"""
# NBVAL_CHECK_OUTPUT
blind = kf.sim.range_localize(plaza2.only([]), scale=1.07, steps=1500)  # no ranges: dead reckoning's ellipse
print(f"Q1: the heading's σ after 150 s: {np.sqrt(blind.Sig[-1, 2, 2]):.2f} rad without ranges, "
      f"{np.sqrt(ekf.Sig[1500, 2, 2]):.3f} rad with them")
print(f"Q2: smoothed {smoothed.summary()['mean_error']:.2f} m off on average, "
      f"filtered {ekf.summary()['mean_error']:.2f} m")
""")
md(r"""
## Recap

- **Meet the data first.** Where each column came from (Plaza1's "true" heading is its odometry), what its sign and
  units are (Plaza2's heading points backwards), and what the sensor does against the truth: a range 7 % long is a
  bias, not noise.
- **Range-only EKF**: $\hat z = \lVert p - b\rVert$, $H$ the unit vector from the beacon, equations (1)-(4). A range
  is a circle; with one beacon more than the unknowns, the circles meet in one point.
- **Honest, or not**: NEES against the truth, and the innovations (NIS, and $z$ against $\hat r$) without it, both
  showed the data sheet's EKF over-confident and pointed at the scale.
- **Fix what they found**: the scale, once and again by rounds or online as a fourth state; a 3σ gate; and an
  odometry noise per metre, which is honest on a fast run and a slow one alike.
- **An unknown start**: with enough beacons the EKF finds the robot from a wide first ellipse; with two it follows a
  mirror image, and the particle filter finds the robot, most of the time, at the price of a wider belief.
- **Smoothing**: the RTS smoother (5)-(7) carries later readings back to every pose; a factor graph solves the whole
  run at once and gives the same answer here.

This is the end of the course's path: from a robot that only knew its wheels to one that checks its filter against
the truth on real data. What comes next is to drop the map. With the beacons' positions unknown too, the same
factor graph, a pose per step and a range factor per reading with the beacons as variables, is range-only SLAM, the
problem the authors of this data set set out to solve.

*Previous: [Chapter 11 · The particle filter](11_particle_filter.ipynb)*
""")

nb = {
    "cells": cells,
    "metadata": {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {
            "codemirror_mode": {"name": "ipython", "version": 3},
            "file_extension": ".py",
            "mimetype": "text/x-python",
            "name": "python",
            "nbconvert_exporter": "python",
            "pygments_lexer": "ipython3",
            "version": "3.11.7",
        },
    },
    "nbformat": 4,
    "nbformat_minor": 5,
}
with open(sys.argv[1], "w", encoding="utf-8") as f:
    json.dump(nb, f, indent=1, ensure_ascii=False)
    f.write("\n")
