"""The course palette: one colour and one line style per role, used by every figure.

Prediction purple and dashed, measurement orange (points, or dash-dot where it is a line),
estimate / fused teal and solid, truth light grey and dotted; landmarks purple squares.
Colour is never the only cue: a reader who cannot tell two of the colours apart still
tells the roles apart by the line style.

The four role colours are chosen to stay apart for readers with a colour vision
deficiency. Every pair of them is at least 15 apart in CIEDE2000 (Sharma, Wu & Dalal
2005; kL = kC = kH = 1; CIELAB from sRGB with the D65 white X, Y, Z = 0.95047, 1, 1.08883)
under normal vision and under protanopia, deuteranopia and tritanopia simulated with the
matrices of Machado, Oliveira & Fernandes (2009) at severity 1.0, applied in linear RGB
and clipped to [0, 1]. The closest pair is prediction and estimate under deuteranopia
(about 22). The earlier teal #14a3a0 and grey #a6a6a6 were only about 5 apart under
protanopia, so the estimate trail and the true path looked the same; the darker teal
against the lighter grey fixes that.

Coloured text on white uses the ``*_TEXT`` shades, each at least 4.5:1 in WCAG 2
contrast (relative luminance); a role colour serves as its own text shade where it
already reaches that. tests/plots/test_palette.py checks all of these numbers.

Particles are purple in every picture: a particle is a sample moved by the prediction, and
its shade shows its weight, pale for the lightest to the prediction purple for the heaviest
(``PARTICLE_WEIGHTS``), so that the teal estimate stands out against a cloud of them.
"""

from matplotlib.colors import LinearSegmentedColormap

PREDICTION = "#7b4fc9"  # purple: the predicted belief (bel-bar)
MEASUREMENT = "#f28c28"  # orange: sensor readings and the measurement likelihood
ESTIMATE = "#007b6e"  # teal: the filtered / fused estimate
TRUTH = "#b8b8b8"  # light grey: the true state the robot never sees
LANDMARK = PREDICTION  # purple squares on maps
INK = "#333333"  # text and axes
GRID = "#e6e6e6"

# Line styles, so that colour is never the only cue (matplotlib's linestyle strings).
PREDICTION_LINE = "--"  # dashed
MEASUREMENT_LINE = "-."  # dash-dot, where readings are joined into a line; else points
ESTIMATE_LINE = "-"  # solid
TRUTH_LINE = ":"  # dotted; draw it at TRUTH_WIDTH or wider so the dots show
TRUTH_WIDTH = 2.0  # points: the thinnest a dotted truth line (path, curve) is drawn

# Coloured text on white (readouts, labels): shades of the roles at 4.5:1 contrast or more.
PREDICTION_TEXT = PREDICTION  # 5.5:1
MEASUREMENT_TEXT = "#a85a10"  # 5.1:1 (the orange itself is 2.5:1)
ESTIMATE_TEXT = ESTIMATE  # 5.2:1
TRUTH_TEXT = "#6b6b6b"  # 5.3:1 (the grey itself is 2.0:1)

# Particles, shaded by weight: 0 (lightest) pale purple to 1 (heaviest) the prediction purple.
PARTICLE_LIGHT = "#d6cbef"
PARTICLE_WEIGHTS = LinearSegmentedColormap.from_list("particle_weights", [PARTICLE_LIGHT, PREDICTION])


def line_style(color) -> str:
    """The line style of the role drawn in ``color`` (one of the four role colours); solid for any other colour.

    Lets a helper such as :func:`~kfcourse.plots.gaussian_curve` draw a prediction dashed
    without being told twice.
    """
    roles = {PREDICTION: PREDICTION_LINE, MEASUREMENT: MEASUREMENT_LINE, ESTIMATE: ESTIMATE_LINE, TRUTH: TRUTH_LINE}
    return roles.get(color, "-") if isinstance(color, str) else "-"
