"""The course palette: one colour per role, used by every figure.

Prediction purple, measurement orange, estimate / fused teal, truth faint grey,
landmarks purple squares.
"""

PREDICTION = "#7b4fc9"  # purple: the predicted belief (bel-bar)
MEASUREMENT = "#f28c28"  # orange: sensor readings and the measurement likelihood
ESTIMATE = "#14a3a0"  # teal: the filtered / fused estimate
TRUTH = "#a6a6a6"  # faint grey: the true state the robot never sees
LANDMARK = PREDICTION  # purple squares on maps
INK = "#333333"  # text and axes
GRID = "#e6e6e6"
