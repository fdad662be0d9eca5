"""Wrong (and a few right) solutions to the "Your turn" exercises of chapters 0 to 5.

Written from the exercise texts and the chapters' equations only, as students who read the chapter would
write them; not from the checkers.  Chapters 0, 1, 2 and 4 number no equations, so their ``equation`` is "";
chapters 3 and 5 number theirs (1) to (5).
"""

from __future__ import annotations

import numpy as np

from tests.check.wrong_set import right, wrong

# ---------------------------------------------------------------- drift_sigma (chapter 0)


@wrong("drift_sigma", equation="", inputs=("n",), what="adds up the standard deviations, so the spread grows like n")
def drift_linear(step_std, n):
    return step_std * np.asarray(n, dtype=float)


@wrong("drift_sigma", equation="", inputs=("n",), what="writes n ** 1/2, which is (n ** 1) / 2, not the square root")
def drift_precedence(step_std, n):
    return step_std * np.asarray(n, dtype=float) ** 1 / 2


@wrong("drift_sigma", equation="", inputs=("n",), what="writes the exponent as 1 // 2, which is 0, so n drops out")
def drift_integer_exponent(step_std, n):
    return step_std * np.asarray(n, dtype=float) ** (1 // 2)


@wrong(
    "drift_sigma", equation="", inputs=("step_std", "n"), what="returns the variance n σ² instead of its square root"
)
def drift_variance(step_std, n):
    return step_std**2 * np.asarray(n, dtype=float)


@wrong("drift_sigma", equation="", inputs=("step_std",), what="takes step_std for a variance: returns √(σ n)")
def drift_std_as_variance(step_std, n):
    return np.sqrt(step_std * np.asarray(n, dtype=float))


@wrong("drift_sigma", equation="", inputs=("step_std",), what="squares the step's standard deviation: σ² √n")
def drift_squared_std(step_std, n):
    return step_std**2 * np.sqrt(n)


@wrong("drift_sigma", equation="", inputs=("n",), what="counts one step too few, σ √(n - 1)")
def drift_one_step_short(step_std, n):
    return step_std * np.sqrt(np.asarray(n, dtype=float) - 1)


@wrong("drift_sigma", equation="", inputs=("n",), what="counts the start as a step too, σ √(n + 1)")
def drift_one_step_long(step_std, n):
    return step_std * np.sqrt(np.asarray(n, dtype=float) + 1)


@wrong(
    "drift_sigma", equation="", inputs=("n",), what="divides by √n (the spread of an average) instead of multiplying"
)
def drift_divided(step_std, n):
    with np.errstate(divide="ignore"):
        return step_std / np.sqrt(np.asarray(n, dtype=float))


@wrong("drift_sigma", equation="", inputs=("step_std",), what="hard-codes the chapter's 0.02 m and ignores step_std")
def drift_hard_coded(step_std, n):
    return 0.02 * np.sqrt(n)


@wrong("drift_sigma", equation="", inputs=(), what="converts to centimetres, as the chapter's table prints it")
def drift_in_cm(step_std, n):
    return 100 * step_std * np.sqrt(n)


@wrong("drift_sigma", equation="", inputs=("n",), what="guards n with max(n, 1), so zero steps get one step's spread")
def drift_at_least_one(step_std, n):
    return step_std * np.sqrt(np.maximum(n, 1))


@wrong("drift_sigma", equation="", inputs=("n",), what="adds the step count to the variance instead of multiplying")
def drift_added(step_std, n):
    return np.sqrt(step_std**2 + np.asarray(n, dtype=float))


@right("drift_sigma", what="adds the variances first, then takes one square root")
def drift_via_variance(step_std, n):
    variance = np.asarray(n, dtype=float) * step_std**2  # variances of independent steps add
    out = np.sqrt(variance)
    return float(out) if out.ndim == 0 else out


@right("drift_sigma", what="a plain loop that sums one variance per step, for a number or each entry of an array")
def drift_by_loop(step_std, n):
    counts = np.asarray(n)
    spreads = []
    for steps in counts.ravel():
        total = 0.0
        for _ in range(int(steps)):
            total += step_std * step_std
        spreads.append(total**0.5)
    if counts.ndim == 0:
        return spreads[0]
    return np.array(spreads).reshape(counts.shape)


# ---------------------------------------------------------------- bayes_predict (chapter 1)


@wrong("bayes_predict", equation="", inputs=("boundary",), what="always stops at the walls, also on a ring")
def predict_always_wall(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            bel_bar[min(max(start + offset, 0), n - 1)] += p * belief[start]
    return bel_bar


@wrong("bayes_predict", equation="", inputs=("boundary",), what="always wraps around, also in a hallway with walls")
def predict_always_wrap(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            bel_bar[(start + offset) % n] += p * belief[start]
    return bel_bar


@wrong("bayes_predict", equation="", inputs=("boundary",), what="treats wall and wrap the wrong way round")
def predict_boundaries_swapped(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = min(max(start + offset, 0), n - 1) if boundary == "wrap" else (start + offset) % n
            bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=("boundary",),
    what="at a wall, drops the mass that would leave instead of keeping it in the end cell",
)
def predict_wall_loses_mass(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = start + offset
            if boundary == "wrap":
                bel_bar[end % n] += p * belief[start]
            elif 0 <= end < n:
                bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=("boundary",),
    what="at a wall, drops the mass that leaves and renormalises, spreading it over every cell",
)
def predict_wall_renormalised(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = start + offset
            if boundary == "wrap":
                bel_bar[end % n] += p * belief[start]
            elif 0 <= end < n:
                bel_bar[end] += p * belief[start]
    return bel_bar / bel_bar.sum()


@wrong(
    "bayes_predict",
    equation="",
    inputs=("kernel",),
    what="moves the belief the wrong way: start - offset instead of start + offset",
)
def predict_wrong_direction(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = start - offset
            end = end % n if boundary == "wrap" else min(max(end, 0), n - 1)
            bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=(),
    what="gathers from the clipped source cell instead of pushing to the clipped end cell, which breaks at a wall",
)
def predict_gather_at_wall(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for end in range(n):
        for offset, p in kernel.items():
            start = end - offset
            start = start % n if boundary == "wrap" else min(max(start, 0), n - 1)
            bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=(),
    what="clips only at the far wall (min without max): a move left past cell 0 lands at the far end",
)
def predict_no_left_wall(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = (start + offset) % n if boundary == "wrap" else min(start + offset, n - 1)
            bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=(),
    what="vectorises with bel_bar[dst] += ..., which adds only once where several cells pile up at a wall",
)
def predict_fancy_index_add(belief, kernel, boundary="wall"):
    bel = np.asarray(belief, dtype=float)
    n = bel.size
    src = np.arange(n)
    bel_bar = np.zeros(n)
    for offset, p in kernel.items():
        dst = (src + offset) % n if boundary == "wrap" else np.clip(src + offset, 0, n - 1)
        bel_bar[dst] += p * bel
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=(),
    what="assigns with = instead of adding with +=, so each end cell keeps only the last contribution",
)
def predict_overwrites(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = (start + offset) % n if boundary == "wrap" else min(max(start + offset, 0), n - 1)
            bel_bar[end] = p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=("kernel",),
    what="forgets the move probabilities and renormalises, so every offset counts the same",
)
def predict_ignores_probabilities(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset in kernel:
            end = (start + offset) % n if boundary == "wrap" else min(max(start + offset, 0), n - 1)
            bel_bar[end] += belief[start]
    return bel_bar / bel_bar.sum()


@wrong(
    "bayes_predict",
    equation="",
    inputs=("kernel",),
    what="uses the position of each entry in the kernel as its offset instead of its key",
)
def predict_enumerated_kernel(belief, kernel, boundary="wall"):
    n = len(belief)
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in enumerate(kernel.values()):
            end = (start + offset) % n if boundary == "wrap" else min(max(start + offset, 0), n - 1)
            bel_bar[end] += p * belief[start]
    return bel_bar


@wrong(
    "bayes_predict",
    equation="",
    inputs=("boundary",),
    what="np.convolve, cut to the hallway: mass that leaves is lost, at a wall and on a ring alike",
)
def predict_convolve_cut(belief, kernel, boundary="wall"):
    lo, hi = min(kernel), max(kernel)
    weights = [kernel.get(offset, 0.0) for offset in range(lo, hi + 1)]
    full = np.convolve(np.asarray(belief, dtype=float), weights)  # full[j] is the cell j + lo
    n = len(belief)
    out = np.zeros(n)
    for j, mass in enumerate(full):
        if 0 <= j + lo < n:
            out[j + lo] = mass
    return out


@wrong(
    "bayes_predict",
    equation="",
    inputs=("belief",),
    what="right numbers, but writes them into the belief it was given (modifies its input)",
)
def predict_in_place(belief, kernel, boundary="wall"):
    bel = np.asarray(belief, dtype=float)
    n = bel.size
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = (start + offset) % n if boundary == "wrap" else min(max(start + offset, 0), n - 1)
            bel_bar[end] += p * bel[start]
    bel[:] = bel_bar
    return bel


@right("bayes_predict", what="np.roll on a ring; on a wall, a shifted copy plus the overflow added to the end cell")
def predict_by_shifting(belief, kernel, boundary="wall"):
    bel = np.asarray(belief, dtype=float)
    n = bel.size
    out = np.zeros(n)
    for offset, p in kernel.items():
        if boundary == "wrap":
            out += p * np.roll(bel, offset)
            continue
        shifted = np.zeros(n)
        if offset >= 0:
            k = min(offset, n)
            shifted[k:] = bel[: n - k]
            shifted[-1] += bel[n - k :].sum()  # everything that would pass the right wall stops there
        else:
            k = min(-offset, n)
            shifted[: n - k] = bel[k:]
            shifted[0] += bel[:k].sum()  # everything that would pass the left wall stops there
        out += p * shifted
    return out


@right("bayes_predict", what="builds the transition matrix p(x_t | u_t, x_{t-1}) and multiplies it by the belief")
def predict_by_matrix(belief, kernel, boundary="wall"):
    bel = np.asarray(belief, dtype=float)
    n = bel.size
    T = np.zeros((n, n))  # T[end, start] = p(end | start)
    for start in range(n):
        for offset, p in kernel.items():
            end = (start + offset) % n if boundary == "wrap" else min(max(start + offset, 0), n - 1)
            T[end, start] += p
    return T @ bel


# ---------------------------------------------------------------- bayes_update (chapter 1)


@wrong("bayes_update", equation="", inputs=(), what="multiplies but never normalises, so the belief does not sum to 1")
def update_not_normalised(belief, likelihood):
    return np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)


@wrong(
    "bayes_update",
    equation="",
    inputs=("likelihood",),
    what="divides by the sum of the likelihood instead of the sum of the product",
)
def update_eta_from_likelihood(belief, likelihood):
    lik = np.asarray(likelihood, dtype=float)
    return lik * np.asarray(belief, dtype=float) / lik.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=(),
    what="adds the likelihood to the belief instead of multiplying, then normalises",
)
def update_adds(belief, likelihood):
    total = np.asarray(likelihood, dtype=float) + np.asarray(belief, dtype=float)
    return total / total.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=("belief",),
    what="returns the normalised likelihood and forgets the prior belief",
)
def update_ignores_prior(belief, likelihood):
    lik = np.asarray(likelihood, dtype=float)
    return lik / lik.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=("likelihood",),
    what="divides the belief by the likelihood instead of multiplying",
)
def update_divides(belief, likelihood):
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.asarray(belief, dtype=float) / np.asarray(likelihood, dtype=float)
    return ratio / ratio.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=(),
    what="normalises by the largest entry, so the peak is 1 instead of the total",
)
def update_normalised_by_max(belief, likelihood):
    product = np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)
    return product / product.max()


@wrong("bayes_update", equation="", inputs=(), what="normalises to unit length (np.linalg.norm) instead of unit sum")
def update_unit_length(belief, likelihood):
    product = np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)
    return product / np.linalg.norm(product)


@wrong(
    "bayes_update",
    equation="",
    inputs=(),
    what="normalises by the mean instead of the sum, so the belief sums to the number of cells",
)
def update_normalised_by_mean(belief, likelihood):
    product = np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)
    return product / product.mean()


@wrong("bayes_update", equation="", inputs=(), what="computes eta with integer division, 1 // total")
def update_floor_eta(belief, likelihood):
    product = np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)
    eta = 1 // product.sum()
    return eta * product


@wrong("bayes_update", equation="", inputs=(), what="rounds the belief to three decimals, as the chapter prints it")
def update_rounded(belief, likelihood):
    product = np.asarray(likelihood, dtype=float) * np.asarray(belief, dtype=float)
    return np.round(product / product.sum(), 3)


@wrong(
    "bayes_update",
    equation="",
    inputs=("likelihood",),
    what="adds a small constant to the likelihood 'to avoid zeros', which shifts every answer",
)
def update_smoothed(belief, likelihood):
    product = (np.asarray(likelihood, dtype=float) + 0.01) * np.asarray(belief, dtype=float)
    return product / product.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=("likelihood",),
    what="multiplies by the likelihood twice, counting the reading two times",
)
def update_twice(belief, likelihood):
    lik = np.asarray(likelihood, dtype=float)
    product = lik * lik * np.asarray(belief, dtype=float)
    return product / product.sum()


@wrong(
    "bayes_update",
    equation="",
    inputs=("belief",),
    what="right numbers, but computed in place in the belief it was given (modifies its input)",
)
def update_in_place(belief, likelihood):
    bel = np.asarray(belief, dtype=float)
    bel *= np.asarray(likelihood, dtype=float)
    bel /= bel.sum()
    return bel


@right("bayes_update", what="in log space, normalised with a log-sum-exp")
def update_in_logs(belief, likelihood):
    with np.errstate(divide="ignore"):
        log_post = np.log(np.asarray(likelihood, dtype=float)) + np.log(np.asarray(belief, dtype=float))
    top = log_post.max()
    weights = np.exp(log_post - top)
    return weights / weights.sum()


@right("bayes_update", what="a loop over the cells with Python floats, eta computed first")
def update_by_loop(belief, likelihood):
    products = [float(p) * float(b) for p, b in zip(likelihood, belief, strict=True)]
    total = 0.0
    for value in products:
        total += value
    eta = 1.0 / total
    return np.array([eta * value for value in products])


# ---------------------------------------------------------------- affine_gaussian (chapter 2)


@wrong(
    "affine_gaussian",
    equation="",
    inputs=("A",),
    what="leaves out the transpose: the covariance is A Σ, half the sandwich",
)
def affine_half_sandwich(mu, Sig, A, b):
    return A @ mu + b, A @ Sig


@wrong("affine_gaussian", equation="", inputs=("b",), what="forgets to add b to the mean")
def affine_mean_without_b(mu, Sig, A, b):
    return A @ mu, A @ Sig @ A.T


@wrong("affine_gaussian", equation="", inputs=("b",), what="subtracts b from the mean instead of adding it")
def affine_mean_minus_b(mu, Sig, A, b):
    return A @ mu - b, A @ Sig @ A.T


@wrong("affine_gaussian", equation="", inputs=("b",), what="lets the shift b widen the covariance by b bᵀ")
def affine_b_in_covariance(mu, Sig, A, b):
    return A @ mu + b, A @ Sig @ A.T + np.outer(b, b)


@wrong(
    "affine_gaussian", equation="", inputs=("Sig",), what="treats Σ as a standard deviation and squares it: (A Σ)(A Σ)ᵀ"
)
def affine_sig_squared(mu, Sig, A, b):
    spread = A @ Sig
    return A @ mu + b, spread @ spread.T


@wrong("affine_gaussian", equation="", inputs=("Sig",), what="keeps only the variances of Σ and drops its covariances")
def affine_diagonal_sig(mu, Sig, A, b):
    return A @ mu + b, A @ np.diag(np.diag(Sig)) @ A.T


@wrong("affine_gaussian", equation="", inputs=(), what="returns only the variances of Y, with zeros off the diagonal")
def affine_diagonal_result(mu, Sig, A, b):
    return A @ mu + b, np.diag(np.diag(A @ Sig @ A.T))


@wrong(
    "affine_gaussian", equation="", inputs=("A",), what="uses |A| in the covariance so that no negative numbers appear"
)
def affine_abs_a(mu, Sig, A, b):
    return A @ mu + b, np.abs(A) @ Sig @ np.abs(A).T


@wrong("affine_gaussian", equation="", inputs=(), what="returns the pair in the wrong order, (covariance, mean)")
def affine_swapped_pair(mu, Sig, A, b):
    return A @ Sig @ A.T, A @ mu + b


@wrong(
    "affine_gaussian",
    equation="",
    inputs=(),
    what="measures the mean and covariance of 100 000 pushed samples instead of using the formula",
)
def affine_by_sampling(mu, Sig, A, b):
    rng = np.random.default_rng(0)
    samples = rng.multivariate_normal(mu, Sig, size=100_000) @ A.T + b
    cov = np.atleast_2d(np.cov(samples, rowvar=False))
    return samples.mean(axis=0), cov


@wrong(
    "affine_gaussian",
    equation="",
    inputs=("b",),
    what="right numbers, but builds the mean in the array b it was given (modifies its input)",
)
def affine_in_place(mu, Sig, A, b):
    mean = b
    mean += A @ mu
    return mean, A @ Sig @ A.T


@right("affine_gaussian", what="explicit loops over the entries, Σ_jk A_ij Σ_jk A_lk")
def affine_by_loops(mu, Sig, A, b):
    A, Sig, mu, b = (np.asarray(x, dtype=float) for x in (A, Sig, mu, b))
    m, n = A.shape
    mean = np.zeros(m)
    cov = np.zeros((m, m))
    for i in range(m):
        mean[i] = b[i] + sum(A[i, j] * mu[j] for j in range(n))
        for l in range(m):
            cov[i, l] = sum(A[i, j] * Sig[j, k] * A[l, k] for j in range(n) for k in range(n))
    return mean, cov


@right("affine_gaussian", what="row-vector convention with einsum: mu Aᵀ + b and A_ij Σ_jk A_lk")
def affine_by_einsum(mu, Sig, A, b):
    mean = np.asarray(mu) @ np.asarray(A).T + b
    cov = np.einsum("ij,jk,lk->il", A, Sig, A)
    return mean, cov


# ---------------------------------------------------------------- kf_1d_step (chapter 3)


@wrong("kf_1d_step", equation="(3)", inputs=("Q",), what="the gain leaves Q out of its denominator")
def kf1d_gain_without_q(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong(
    "kf_1d_step", equation="(2)-(3)", inputs=("R", "Q"), what="swaps the letters: Q added in the predict, R in the gain"
)
def kf1d_r_q_swapped(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + Q
    K = c * var_bar / (c * c * var_bar + R)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(2)", inputs=("a",), what="scales the variance by a instead of a²")
def kf1d_var_times_a(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(2)", inputs=("a",), what="does not scale the variance by a² at all")
def kf1d_var_without_a(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(2)", inputs=("R",), what="scales the process noise by a² too: a² (σ² + R)")
def kf1d_r_scaled(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * (var + R)
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(2)", inputs=("R",), what="takes R for a standard deviation and squares it")
def kf1d_r_squared(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R**2
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(1)", inputs=("b",), what="forgets b in the predicted mean: a μ + u")
def kf1d_mean_without_b(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong(
    "kf_1d_step",
    equation="(3)",
    inputs=("var",),
    what="computes the gain from the prior variance instead of the predicted one",
)
def kf1d_gain_from_prior(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var / (c * c * var + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(5)", inputs=("var",), what="shrinks the prior variance instead of the predicted one")
def kf1d_shrinks_prior(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var


@wrong("kf_1d_step", equation="(3)", inputs=("c",), what="leaves c out of the gain's numerator")
def kf1d_gain_numerator_without_c(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(3)", inputs=("c",), what="writes c instead of c² in the gain's denominator")
def kf1d_gain_denominator_c(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(4)", inputs=("c",), what="the innovation forgets c: z - μ̄")
def kf1d_innovation_without_c(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(5)", inputs=("c",), what="shrinks the variance by (1 - K) instead of (1 - K c)")
def kf1d_shrink_without_c(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K) * var_bar


@wrong(
    "kf_1d_step",
    equation="(4)",
    inputs=("mu",),
    what="the innovation compares z with the prior mean instead of the predicted one",
)
def kf1d_innovation_from_prior(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(4)", inputs=(), what="flips the sign of the innovation, c μ̄ - z")
def kf1d_innovation_sign(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (c * mu_bar - z), (1 - K * c) * var_bar


@wrong(
    "kf_1d_step",
    equation="(3)",
    inputs=(),
    what="computes the gain with floor division //, which makes it 0 or a whole number",
)
def kf1d_floor_gain(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar // (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


@wrong("kf_1d_step", equation="(5)", inputs=(), what="returns the predicted variance: the update never shrinks it")
def kf1d_no_shrink(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), var_bar


@wrong("kf_1d_step", equation="", inputs=(), what="returns the pair in the wrong order, (var, mu)")
def kf1d_swapped_pair(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a * a * var + R
    K = c * var_bar / (c * c * var_bar + Q)
    return (1 - K * c) * var_bar, mu_bar + K * (z - c * mu_bar)


@wrong(
    "kf_1d_step",
    equation="(7)",
    inputs=(),
    what="updates in precision form (7), dividing by the predicted variance, so a predicted variance of 0 gives nan",
)
def kf1d_precision_form(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = np.float64(a * a * var + R)
    with np.errstate(divide="ignore", invalid="ignore"):
        var_new = 1 / (1 / var_bar + c * c / Q)
        mu_new = var_new * (mu_bar / var_bar + c * z / Q)
    return float(mu_new), float(var_new)


@right("kf_1d_step", what="the Bayes-product form: a weighted average over the common denominator c² σ̄² + Q")
def kf1d_product_form(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar = a * mu + b * u
    var_bar = a**2 * var + R
    denominator = c**2 * var_bar + Q
    mu_new = (Q * mu_bar + c * var_bar * z) / denominator
    var_new = var_bar * Q / denominator
    return mu_new, var_new


@right("kf_1d_step", what="predict and update as inner functions, the variance shrunk by K² S with S = c² σ̄² + Q")
def kf1d_with_innovation_variance(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    def predict(m, v):
        return a * m + b * u, a * a * v + R

    def update(m, v):
        S = c * c * v + Q  # variance of the innovation
        K = c * v / S
        return m + K * (z - c * m), v - K * K * S

    return update(*predict(mu, var))


# ---------------------------------------------------------------- fuse (chapter 4)


@wrong(
    "fuse", equation="", inputs=("var1", "var2"), what="weights each mean by its own variance instead of the other's"
)
def fuse_weights_swapped(mu1, var1, mu2, var2):
    return (var1 * mu1 + var2 * mu2) / (var1 + var2), var1 * var2 / (var1 + var2)


@wrong(
    "fuse", equation="", inputs=("var1", "var2"), what="takes the plain average of the means, whatever their variances"
)
def fuse_plain_average(mu1, var1, mu2, var2):
    return (mu1 + mu2) / 2, var1 * var2 / (var1 + var2)


@wrong("fuse", equation="", inputs=(), what="averages the variances instead of adding the precisions")
def fuse_average_variance(mu1, var1, mu2, var2):
    return (var2 * mu1 + var1 * mu2) / (var1 + var2), (var1 + var2) / 2


@wrong("fuse", equation="", inputs=(), what="returns the total precision 1/σ1² + 1/σ2² instead of its inverse")
def fuse_returns_precision(mu1, var1, mu2, var2):
    w1, w2 = 1 / var1, 1 / var2
    return (w1 * mu1 + w2 * mu2) / (w1 + w2), w1 + w2


@wrong("fuse", equation="", inputs=(), what="inverts the sum of the variances instead of summing the inverses")
def fuse_inverse_of_sum(mu1, var1, mu2, var2):
    return (var2 * mu1 + var1 * mu2) / (var1 + var2), 1 / (var1 + var2)


@wrong(
    "fuse", equation="", inputs=(), what="forgets to divide the precision-weighted sum of means by the total precision"
)
def fuse_mean_not_divided(mu1, var1, mu2, var2):
    return mu1 / var1 + mu2 / var2, 1 / (1 / var1 + 1 / var2)


@wrong(
    "fuse",
    equation="",
    inputs=("var1", "var2"),
    what="takes the variances for standard deviations and weights by 1/var² instead of 1/var",
)
def fuse_squares_variances(mu1, var1, mu2, var2):
    w1, w2 = 1 / var1**2, 1 / var2**2
    return (w1 * mu1 + w2 * mu2) / (w1 + w2), 1 / (w1 + w2)


@wrong(
    "fuse", equation="", inputs=("var1", "var2"), what="gain form with the wrong variance on top, K = σ2² / (σ1² + σ2²)"
)
def fuse_gain_wrong_numerator(mu1, var1, mu2, var2):
    K = var2 / (var1 + var2)
    return mu1 + K * (mu2 - mu1), (1 - K) * var1


@wrong("fuse", equation="", inputs=("var1", "var2"), what="gain form, but shrinks σ2² instead of σ1²: (1 - K) σ2²")
def fuse_shrinks_wrong_variance(mu1, var1, mu2, var2):
    K = var1 / (var1 + var2)
    return mu1 + K * (mu2 - mu1), (1 - K) * var2


@wrong("fuse", equation="", inputs=("mu1", "mu2"), what="gain form with the difference the wrong way round, μ1 - μ2")
def fuse_difference_reversed(mu1, var1, mu2, var2):
    K = var1 / (var1 + var2)
    return mu1 + K * (mu1 - mu2), (1 - K) * var1


@wrong("fuse", equation="", inputs=(), what="keeps the smaller variance, as if fusing only picked the better estimate")
def fuse_min_variance(mu1, var1, mu2, var2):
    return (var2 * mu1 + var1 * mu2) / (var1 + var2), min(var1, var2)


@wrong("fuse", equation="", inputs=(), what="writes var1 * var2 / var1 + var2 without brackets, which is 2 σ2²")
def fuse_variance_precedence(mu1, var1, mu2, var2):
    return (var2 * mu1 + var1 * mu2) / (var1 + var2), var1 * var2 / var1 + var2


@wrong("fuse", equation="", inputs=(), what="computes the gain with floor division //, so it is 0 and nothing is fused")
def fuse_floor_gain(mu1, var1, mu2, var2):
    K = var1 // (var1 + var2)
    return mu1 + K * (mu2 - mu1), (1 - K) * var1


@wrong("fuse", equation="", inputs=(), what="returns the pair in the wrong order, (var, mu)")
def fuse_swapped_pair(mu1, var1, mu2, var2):
    K = var1 / (var1 + var2)
    return (1 - K) * var1, mu1 + K * (mu2 - mu1)


# Written as a wrong one (a variance of 0 gives nan), but the exercise allows the precision form, so a variance
# of 0 is outside its contract: counted as right.
@right("fuse", what="the precision form, numpy floats")
def fuse_precision_zero_variance(mu1, var1, mu2, var2):
    with np.errstate(divide="ignore", invalid="ignore"):
        w1, w2 = 1 / np.float64(var1), 1 / np.float64(var2)
        mu = (w1 * mu1 + w2 * mu2) / (w1 + w2)
        var = 1 / (w1 + w2)
    return float(mu), float(var)


@right(
    "fuse", what="the weighted average over the common denominator σ1² + σ2², each mean weighted by the other variance"
)
def fuse_cross_weighted(mu1, var1, mu2, var2):
    total = var1 + var2
    return (var2 * mu1 + var1 * mu2) / total, var1 * var2 / total


@right(
    "fuse", what="gain form around the second estimate, μ2 + K2 (μ1 - μ2) with K2 = σ2² / (σ1² + σ2²), variance K2 σ1²"
)
def fuse_gain_from_second(mu1, var1, mu2, var2):
    K2 = var2 / (var1 + var2)
    return mu2 + K2 * (mu1 - mu2), K2 * var1  # (1 - K2) σ2² = K2 σ1², without the cancellation of 1 - K2


# ---------------------------------------------------------------- kf_step (chapter 5)


@wrong(
    "kf_step",
    equation="(2)-(3)",
    inputs=("R", "Q"),
    what="swaps the letters: Q added to the predicted covariance, R to S (raises when k ≠ n)",
)
def kf_r_q_swapped(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + Q
    S = H @ Sig_bar @ H.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(2)", inputs=("F",), what="leaves out the transpose: F Σ + R")
def kf_half_sandwich(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(2)", inputs=("F",), what="forgets .T on the right: F Σ F + R")
def kf_no_transpose(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(2)", inputs=("F",), what="puts the transpose on the wrong side: Fᵀ Σ F + R")
def kf_transpose_wrong_side(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F.T @ Sig @ F + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(2)", inputs=("F",), what="multiplies entry by entry, F * Σ * Fᵀ, instead of with @")
def kf_elementwise_predict(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F * Sig * F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(2)", inputs=("R",), what="forgets the process noise R in the predicted covariance")
def kf_without_r(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(1)", inputs=("B", "u"), what="forgets the control term B u in the predicted mean")
def kf_without_control(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(3)", inputs=("Q",), what="leaves Q out of S (singular when H = 0)")
def kf_s_without_q(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong(
    "kf_step",
    equation="(3)",
    inputs=("Sig",),
    what="builds S and the gain from the prior covariance Σ instead of the predicted Σ̄",
)
def kf_gain_from_prior(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig @ H.T + Q
    K = Sig @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(3)", inputs=(), what="puts S⁻¹ on the left of the gain (runs only when k = n)")
def kf_inverse_on_left(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = np.linalg.inv(S) @ Sig_bar @ H.T
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(4)", inputs=(), what="flips the sign of the innovation, H μ̄ - z")
def kf_innovation_sign(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (H @ mu_bar - z), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong(
    "kf_step", equation="(4)", inputs=("mu",), what="adds the correction to the prior mean μ instead of the predicted μ̄"
)
def kf_correct_prior_mean(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar


@wrong("kf_step", equation="(5)", inputs=("Sig",), what="shrinks the prior covariance Σ instead of the predicted Σ̄")
def kf_shrinks_prior(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig


@wrong("kf_step", equation="(5)", inputs=(), what="multiplies (I - K H) and Σ̄ entry by entry with *")
def kf_elementwise_update(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) * Sig_bar


@wrong("kf_step", equation="(5)", inputs=("Q",), what="Joseph form without its K Q Kᵀ term")
def kf_joseph_without_kqk(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    I_KH = np.eye(mu.size) - K @ H
    return mu_bar + K @ (z - H @ mu_bar), I_KH @ Sig_bar @ I_KH.T


@wrong("kf_step", equation="(5)", inputs=(), what="adds K H Σ̄ instead of subtracting it: (I + K H) Σ̄")
def kf_covariance_sign(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) + K @ H) @ Sig_bar


@wrong(
    "kf_step",
    equation="",
    inputs=("z",),
    what="right numbers, but computes the innovation in place in the array z it was given (modifies its input)",
)
def kf_innovation_in_place(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    y = z
    y -= H @ mu_bar
    return mu_bar + K @ y, (np.eye(mu.size) - K @ H) @ Sig_bar


@right("kf_step", what="np.linalg.solve for the gain and the covariance as Σ̄ - K S Kᵀ")
def kf_solve_and_kskt(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    S = H @ Sig_bar @ H.T + Q
    K = np.linalg.solve(S, H @ Sig_bar).T  # S symmetric: K^T = S^-1 H Σ̄
    Sig_new = Sig_bar - K @ S @ K.T
    return mu_bar + K @ (z - H @ mu_bar), (Sig_new + Sig_new.T) / 2


@right(
    "kf_step",
    what="one scalar update per reading, in the eigenbasis of Q where the reading noises are independent",
)
def kf_sequential_scalar(mu, Sig, u, z, F, B, H, R, Q):
    m = F @ mu + B @ u
    P = F @ Sig @ F.T + R
    noise, V = np.linalg.eigh(Q)  # Q = V diag(noise) V^T
    z_rot, H_rot = V.T @ z, V.T @ H  # readings with independent noises
    for i in range(noise.size):
        h = H_rot[i]
        Ph = P @ h
        s = h @ Ph + noise[i]  # scalar innovation variance
        k = Ph / s
        m = m + k * (z_rot[i] - h @ m)
        P = P - np.outer(k, Ph)
    return m, (P + P.T) / 2
