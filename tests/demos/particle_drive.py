"""Driving chapter 11's two demo models as a student would, for their tests and their prompts' tests."""

from __future__ import annotations

from kfcourse.demos.particle_cloud import CloudModel


def presses(model, cycles: int) -> None:
    """Press Predict, then Update, ``cycles`` times (the particle hallway)."""
    for _ in range(cycles):
        model.predict()
        model.update()


def model_with(seed, **settings) -> CloudModel:
    """The cloud demo's model with the settings a student would pick, rerun once."""
    model = CloudModel(seed)
    for key, value in settings.items():
        setattr(model, key, value)
    model._rerun()
    return model
