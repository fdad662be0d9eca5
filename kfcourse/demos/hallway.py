"""Chapter 1: the histogram (discrete Bayes) filter in a hallway with doors."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Rectangle

from ..filters.bayes import bayes_predict, bayes_update
from ..plots import palette
from ..plots.artists import belief_bars, update_belief_bars
from ..plots.style import FigureRenderer, new_figure
from ..sim.hallway import door_likelihood, motion_kernel, move, read_door
from ._base import Demo, button, slider

N_CELLS = 20
DOORS = np.isin(np.arange(N_CELLS), [2, 5, 6, 12, 17])


class HallwayModel:
    """Model: the belief, the hidden true cell and the last reading."""

    def __init__(self, seed: int, motion_reliability: float = 0.8, sensor_reliability: float = 0.8):
        self.seed = seed
        self.motion_reliability = motion_reliability
        self.sensor_reliability = sensor_reliability
        self.boundary = "wall"
        self.reset()

    def reset(self) -> None:
        """Uniform belief, a fresh (seeded) true cell, and a first look."""
        self.rng = np.random.default_rng(self.seed)
        self.true_cell = int(self.rng.integers(N_CELLS // 2))  # start in the left half
        self.belief = np.full(N_CELLS, 1.0 / N_CELLS)
        self.steps = 0
        self.update()

    def predict(self) -> None:
        """Command "one cell right": the truth moves (noisily), the belief shifts and blurs."""
        kernel = motion_kernel(self.motion_reliability)
        self.true_cell = move(self.true_cell, kernel, self.rng, N_CELLS, self.boundary)
        self.belief = bayes_predict(self.belief, kernel, self.boundary)
        self.phase = "predicted"
        self.steps += 1

    def update(self) -> None:
        """Read the door sensor and apply Bayes' rule."""
        self.saw_door = read_door(self.true_cell, DOORS, self.sensor_reliability, self.rng)
        self.likelihood = door_likelihood(DOORS, self.saw_door, self.sensor_reliability)
        self.belief, self.eta = bayes_update(self.belief, self.likelihood, return_eta=True)
        self.phase = "updated"

    def set_motion_reliability(self, p: float) -> None:
        self.motion_reliability = p

    def set_sensor_reliability(self, p: float) -> None:
        """A new reliability also changes the likelihood of the last reading."""
        self.sensor_reliability = p
        self.likelihood = door_likelihood(DOORS, self.saw_door, p)

    def set_boundary(self, boundary: str) -> None:
        self.boundary = boundary


def hallway(seed: int = 0) -> Demo:
    """Demo "histogram hallway" (chapter 1): Predict shifts and blurs the bars,
    Update multiplies by the door sensor's likelihood and renormalises.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = HallwayModel(seed)
    fig, (ax, ax_lik) = new_figure(8.0, 4.2, nrows=2, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    cells = np.arange(N_CELLS)
    ax.set_xlim(-0.6, N_CELLS - 0.4)
    ax.set_ylim(0, 1.0)
    ax.set_ylabel("belief  bel(x)")
    bars = belief_bars(ax, model.belief)
    (robot,) = ax.plot([model.true_cell], [0.0], marker="^", ms=14, color=palette.TRUTH, clip_on=False, zorder=5)
    robot.set_markeredgecolor("#666666")
    status = ax.text(0.99, 0.97, "", transform=ax.transAxes, ha="right", va="top", fontsize=10)
    setup = ax.text(0.01, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9, color=palette.INK)
    ax_lik.set_ylim(0, 1.05)
    ax_lik.set_ylabel("p(z | x)")
    ax_lik.set_xlabel("cell   (doors shaded, grey triangle = true cell)")
    ax_lik.set_xticks(cells)
    for axis in (ax, ax_lik):
        for c in cells[DOORS]:
            axis.add_patch(Rectangle((c - 0.5, 0), 1, 1.05, color="#c8a27a", alpha=0.22, lw=0, zorder=0))
    lik_bars = belief_bars(ax_lik, model.likelihood, color=palette.MEASUREMENT)
    dynamic = [*bars, robot, status, setup, *lik_bars]
    renderer = FigureRenderer(fig, dynamic)

    def draw() -> None:
        top = 0.25 * np.ceil(1.1 * float(model.belief.max()) / 0.25)  # in steps of 0.25: few full redraws
        if ax.get_ylim()[1] != top:
            ax.set_ylim(0, top)
            renderer.invalidate()
        update_belief_bars(bars, model.belief)
        colour = palette.PREDICTION if model.phase == "predicted" else palette.ESTIMATE
        for bar in bars:
            bar.set_color(colour)
        robot.set_data([model.true_cell], [0.0])
        update_belief_bars(lik_bars, model.likelihood)
        for bar in lik_bars:
            bar.set_alpha(0.35 if model.phase == "predicted" else 1.0)
        reading = "door" if model.saw_door else "no door"
        if model.phase == "predicted":
            text = rf"after Predict (move right ×{model.steps}): $\overline{{bel}}$ is shifted and blurred"
        else:
            text = f"after Update: sensor says “{reading}”, η = {model.eta:.2f}"
        status.set_text(f"{text}\nΣ bel = {model.belief.sum():.3f}")
        k = motion_kernel(model.motion_reliability)
        setup.set_text(
            f"motion kernel: +1 cell {k[1]:.2f}, stall {k[0]:.2f}, +2 cells {k[2]:.2f}\n"
            f"sensor right {model.sensor_reliability:.2f} of the time; ends: {model.boundary}"
        )

    boundary = widgets.ToggleButtons(options=["wall", "wrap"], value="wall", description="ends:")
    boundary.style.button_width = "60px"
    caption = (
        "<b>Histogram hallway.</b> Bars: the belief bel(x) over 20 cells "
        "(purple after <i>Predict</i>, teal after <i>Update</i>); orange: the door sensor's likelihood "
        "p(z | x); shaded cells are doors; the grey triangle is the true cell. "
        "Sliders set how reliable motion and sensing are; <i>ends</i> chooses walls or a ring."
    )
    return Demo(
        name="hallway",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "predict": (button("Predict", icon="arrow-right", tooltip="Move one cell right"), model.predict),
            "update": (button("Update", icon="eye", tooltip="Read the door sensor"), model.update),
            "reset": (button("Reset", icon="undo", tooltip="Uniform belief, start again"), model.reset),
            "motion_reliability": (
                slider(widgets.FloatSlider, "motion reliability", 0.8, 0.34, 1.0, 0.02),
                model.set_motion_reliability,
            ),
            "sensor_reliability": (
                slider(widgets.FloatSlider, "sensor reliability", 0.8, 0.5, 0.98, 0.02),
                model.set_sensor_reliability,
            ),
            "boundary": (boundary, model.set_boundary),
        },
        layout=[["predict", "update", "reset", "boundary"], ["motion_reliability", "sensor_reliability"]],
    )
