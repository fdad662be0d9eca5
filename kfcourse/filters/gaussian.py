"""Gaussians and their three closure properties.

Introduced in chapter 2: a 1-D density ``N(mu, var)``, a multivariate density
``N(mu, Sig)``, and the operations that keep a Gaussian Gaussian (an affine map,
the sum of independent Gaussians, the product of two densities).
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as v


def gaussian_pdf(x, mu: float, var: float) -> np.ndarray:
    r"""1-D Gaussian density.

    .. math:: \mathcal N(x; \mu, \sigma^2) = \frac{1}{\sqrt{2\pi\sigma^2}}
              \exp\!\left(-\frac{(x-\mu)^2}{2\sigma^2}\right)

    Introduced in chapter 2.

    Parameters
    ----------
    x : array_like
        Where to evaluate, any shape.
    mu : float
        Mean.
    var : float
        Variance, > 0.

    Returns
    -------
    ndarray, same shape as ``x`` (a float for scalar ``x``)
    """
    x = v.finite(x, "x")
    mu = v.scalar(mu, "mu")
    var = v.positive(var, "var", "a variance")
    y = np.exp(-0.5 * (x - mu) ** 2 / var) / math.sqrt(2.0 * math.pi * var)
    return float(y) if y.ndim == 0 else y


def mvn_pdf(x, mu, Sig) -> np.ndarray:
    r"""Multivariate Gaussian density.

    .. math:: \mathcal N(x; \mu, \Sigma) = \det(2\pi\Sigma)^{-1/2}
              \exp\!\left(-\tfrac12 (x-\mu)^\top \Sigma^{-1} (x-\mu)\right)

    Introduced in chapter 2.

    Parameters
    ----------
    x : array_like, shape (..., n)
        Points.
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
        Positive definite covariance.

    Returns
    -------
    ndarray, shape (...)
    """
    mu = v.vector(mu, "mu")
    n = mu.size
    Sig = v.covariance(Sig, "Sig", n)
    x = v.finite(x, "x")
    if x.shape[-1:] != (n,):
        raise ValueError(f"x must have last dimension {n}, got shape {x.shape}")
    sign, logdet = np.linalg.slogdet(2.0 * math.pi * Sig)
    if sign <= 0:
        raise ValueError("Sig must be positive definite for a density")
    d = x - mu
    m2 = np.einsum("...i,ij,...j->...", d, np.linalg.inv(Sig), d)  # squared Mahalanobis
    return np.exp(-0.5 * m2 - 0.5 * logdet)


def affine_gaussian(mu, Sig, A, b=None):
    r"""Closure property 1: ``Y = A X + b`` with ``X ~ N(mu, Sig)``.

    .. math:: Y \sim \mathcal N(A\mu + b,\; A \Sigma A^\top)

    Introduced in chapter 2.  Scalars work too (then ``A Sig A^T = A^2 Sig``).

    Parameters
    ----------
    mu : array_like, shape (n,) or scalar
    Sig : array_like, shape (n, n) or scalar
    A : array_like, shape (m, n) or scalar
    b : array_like, shape (m,) or scalar, optional

    Returns
    -------
    (mu_y, Sig_y) : shapes (m,), (m, m); plain floats for scalar input
    """
    scalar_in = np.ndim(mu) == 0
    mu_v = v.vector(mu, "mu")
    n = mu_v.size
    Sig_m = v.covariance(Sig, "Sig", n)
    A_m = v.matrix(A, "A", None, n) if np.ndim(A) else v.scalar(A, "A") * np.eye(n)
    b_v = np.zeros(A_m.shape[0]) if b is None else v.vector(b, "b", A_m.shape[0])
    mu_y = A_m @ mu_v + b_v  # A mu + b
    Sig_y = A_m @ Sig_m @ A_m.T  # A Sig A^T
    if scalar_in and mu_y.size == 1:
        return float(mu_y[0]), float(Sig_y[0, 0])
    return mu_y, 0.5 * (Sig_y + Sig_y.T)


def add_gaussians(mu1, Sig1, mu2, Sig2):
    r"""Closure property 2: the sum of two independent Gaussians.

    .. math:: X_1 + X_2 \sim \mathcal N(\mu_1 + \mu_2,\; \Sigma_1 + \Sigma_2)

    Introduced in chapter 2 (it is why process noise *adds* to the variance).

    Returns
    -------
    (mu, Sig) : plain floats for scalar input, else arrays (n,), (n, n)
    """
    scalar_in = np.ndim(mu1) == 0 and np.ndim(mu2) == 0
    m1 = v.vector(mu1, "mu1")
    m2 = v.vector(mu2, "mu2", m1.size)
    S1 = v.covariance(Sig1, "Sig1", m1.size)
    S2 = v.covariance(Sig2, "Sig2", m1.size)
    if scalar_in:
        return float(m1[0] + m2[0]), float(S1[0, 0] + S2[0, 0])
    return m1 + m2, S1 + S2


def fuse(mu1, var1, mu2, var2):
    r"""Closure property 3: inverse-variance fusion of two estimates of one quantity.

    The product of the densities ``N(mu1, var1)`` and ``N(mu2, var2)`` is, up to a
    constant, the Gaussian returned here:

    .. math:: \sigma^2 = \left(\sigma_1^{-2} + \sigma_2^{-2}\right)^{-1},
              \qquad \mu = \sigma^2 \left(\mu_1/\sigma_1^2 + \mu_2/\sigma_2^2\right)

    Introduced in chapter 2 (closure property 3); chapter 4 shows it equals the
    Kalman update.
    Written in the gain form ``mu1 + K (mu2 - mu1)`` so that one variance may be 0.

    Parameters
    ----------
    mu1, mu2 : float or array_like, shape (n,)
    var1, var2 : float or array_like, shape (n, n)
        Variances (covariances); their sum must be invertible.

    Returns
    -------
    (mu, var) : floats for scalar input, else arrays (n,), (n, n)
    """
    scalar_in = np.ndim(mu1) == 0 and np.ndim(mu2) == 0
    m1 = v.vector(mu1, "mu1")
    m2 = v.vector(mu2, "mu2", m1.size)
    P1 = v.covariance(var1, "var1", m1.size)
    P2 = v.covariance(var2, "var2", m1.size)
    total = P1 + P2
    if abs(np.linalg.det(total)) <= 1e-300:
        raise ValueError("var1 + var2 must be invertible (both estimates exact is undefined)")
    K = np.linalg.solve(total.T, P1.T).T  # K = P1 (P1 + P2)^-1, the inverse-variance weight
    mu = m1 + K @ (m2 - m1)  # mu = mu1 + K (mu2 - mu1)
    P = P1 - K @ P1  # P = (I - K) P1 = (P1^-1 + P2^-1)^-1
    P = 0.5 * (P + P.T)
    if scalar_in:
        return float(mu[0]), float(P[0, 0])
    return mu, P


def ellipse_axes(Sig, nsig: float = 1.0):
    r"""Geometry of the ``nsig``-sigma contour of a 2-D Gaussian.

    The contour :math:`(x-\mu)^\top\Sigma^{-1}(x-\mu) = k^2` is an ellipse whose
    semi-axes are :math:`k\sqrt{\lambda_i}` along the eigenvectors of Σ.
    Introduced in chapter 2.

    Parameters
    ----------
    Sig : array_like, shape (2, 2)
    nsig : float
        Number of standard deviations ``k`` (> 0).

    Returns
    -------
    (width, height, angle_deg) : full axis lengths and the tilt of the major axis
        in degrees, in [-90, 90), as matplotlib's ``Ellipse`` takes them.
    """
    Sig = v.covariance(Sig, "Sig", 2)
    k = v.positive(nsig, "nsig", "a number of standard deviations")
    w, V = np.linalg.eigh(Sig)
    w = np.clip(w, 0.0, None)
    angle = math.degrees(math.atan2(V[1, 1], V[0, 1]))  # direction of the major axis
    angle = (angle + 90.0) % 180.0 - 90.0  # an axis has no sign: report it in [-90, 90)
    return 2 * k * math.sqrt(w[1]), 2 * k * math.sqrt(w[0]), angle


def mass_inside(nsig, dim: int = 2):
    r"""Probability mass of a Gaussian inside its ``nsig``-sigma contour.

    In 1-D this is the familiar 68 / 95 / 99.7 %.  In 2-D the squared Mahalanobis
    distance is chi-square with 2 degrees of freedom, so

    .. math:: P(d \le k) = 1 - e^{-k^2/2}

    which is only 39.3 % for k = 1.  Introduced in chapter 2.

    Parameters
    ----------
    nsig : float or array_like
        Contour radius ``k`` in standard deviations (>= 0).
    dim : {1, 2}

    Returns
    -------
    float or ndarray
    """
    k = v.finite(nsig, "nsig")
    if (k < 0).any():
        raise ValueError(f"nsig must be >= 0, got {nsig!r}")
    if dim == 1:
        out = np.vectorize(lambda s: math.erf(s / math.sqrt(2.0)))(k)
    elif dim == 2:
        out = 1.0 - np.exp(-0.5 * k**2)
    else:
        raise ValueError(f"dim must be 1 or 2, got {dim!r}")
    return float(out) if np.ndim(out) == 0 else out
