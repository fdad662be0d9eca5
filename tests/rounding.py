"""Noise draws perturbed at the level of rounding: what a chapter states must survive them.

Another CPU takes other SIMD code paths through numpy, and its sines and arctangents can
differ from ours in the last bit.  A filter that diverges magnifies that bit, so the last
digits of such a run are not a fact of the course.  Scaling every normal draw by
``1 + size`` (``size`` about 1e-12) moves a run the way another machine's rounding would,
only more: what still holds then is a fact; what changes was a digit of this machine.

``pytest --perturb=1e-12`` (see the root ``conftest.py``) installs this in the test process
and, through an IPython start-up file, in every notebook kernel that nbval starts.
"""

from __future__ import annotations

import numpy as np


class PerturbedGenerator(np.random.Generator):
    """numpy's Generator with every normal draw scaled by ``factor`` (the same stream otherwise)."""

    factor = 1.0

    def standard_normal(self, *args, **kwargs):
        return super().standard_normal(*args, **kwargs) * self.factor

    def normal(self, loc=0.0, scale=1.0, size=None):
        return loc + (super().normal(0.0, scale, size) * self.factor)


def perturbed_default_rng(size: float):
    """A stand-in for ``np.random.default_rng`` whose generators scale every normal draw by ``1 + size``."""

    class Generator(PerturbedGenerator):
        factor = 1.0 + size

    def default_rng(seed=None):
        if isinstance(seed, np.random.Generator):
            return seed
        return Generator(seed if isinstance(seed, np.random.BitGenerator) else np.random.PCG64(seed))

    return default_rng


def perturb_noise(size: float) -> None:
    """Perturb every run of this process: ``np.random.default_rng`` becomes :func:`perturbed_default_rng`."""
    np.random.default_rng = perturbed_default_rng(size)


def startup_script(size: float) -> str:
    """An IPython start-up file that perturbs the noise of a notebook kernel as :func:`perturb_noise` does."""
    return f"import runpy\nrunpy.run_path({__file__!r})['perturb_noise']({size!r})\n"
