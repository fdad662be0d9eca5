"""How the course's own scripts start a notebook kernel (the site build, storing outputs, the chapter benchmark)."""

from __future__ import annotations

import zmq
from traitlets.config import Config


def kernel_config() -> Config:
    """Kernels that talk to their client over CurveZMQ-encrypted transport where the kernel supports it
    (as under ``make lab``, ``binder/jupyter-config``), or over IPC (Unix sockets) where pyzmq lacks
    CurveZMQ; never over plain TCP, which ipykernel warns about on every start."""
    if zmq.has("curve"):
        return Config({"KernelManager": {"transport_encryption": "auto"}})
    return Config({"KernelManager": {"transport": "ipc"}})
