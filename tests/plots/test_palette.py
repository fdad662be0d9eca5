"""The palette stays readable with a colour vision deficiency, and colour is never the only cue.

Every number is computed from kfcourse.plots.palette with the maths in colour_vision.py
(CIEDE2000, Machado et al. 2009 at severity 1.0 in linear RGB, WCAG 2 contrast).
"""

from itertools import combinations

import pytest
from colour_vision import VISIONS, ciede2000, contrast, difference, lab

from kfcourse.plots import palette

ROLES = {
    "prediction": palette.PREDICTION,
    "measurement": palette.MEASUREMENT,
    "estimate": palette.ESTIMATE,
    "truth": palette.TRUTH,
}
TEXT = {
    "PREDICTION_TEXT": palette.PREDICTION_TEXT,
    "MEASUREMENT_TEXT": palette.MEASUREMENT_TEXT,
    "ESTIMATE_TEXT": palette.ESTIMATE_TEXT,
    "TRUTH_TEXT": palette.TRUTH_TEXT,
}

# Sharma, Wu & Dalal (2005), table 1: (L*, a*, b*) pairs and their CIEDE2000, pairs
# 1, 4, 7, 13, 16, 17, 19, 21, 25, 29 and 34 (the hue wrap at 0°/360°, near-neutral a*, dark colours).
SHARMA = [
    ((50.0, 2.6772, -79.7751), (50.0, 0.0, -82.7485), 2.0425),
    ((50.0, -1.3802, -84.2814), (50.0, 0.0, -82.7485), 1.0000),
    ((50.0, 0.0, 0.0), (50.0, -1.0, 2.0), 2.3669),
    ((50.0, 2.4900, -0.0010), (50.0, -2.4900, 0.0009), 7.1792),
    ((50.0, 2.4900, -0.0010), (50.0, -2.4900, 0.0012), 7.2195),
    ((50.0, 2.5, 0.0), (73.0, 25.0, -18.0), 27.1492),
    ((50.0, 2.5, 0.0), (56.0, -27.0, -3.0), 31.9030),
    ((50.0, 2.5, 0.0), (50.0, 3.1736, 0.5854), 1.0000),
    ((60.2574, -34.0099, 36.2677), (60.4626, -34.1751, 39.4387), 1.2644),
    ((22.7233, 20.0904, -46.6940), (23.0331, 14.9730, -42.5619), 2.0373),
    ((2.0776, 0.0795, -1.1350), (0.9033, -0.0636, -0.5514), 0.9082),
]


@pytest.mark.parametrize(("lab1", "lab2", "expected"), SHARMA)
def test_ciede2000_matches_the_published_pairs(lab1, lab2, expected):
    assert ciede2000(lab1, lab2) == pytest.approx(expected, abs=1e-4)
    assert ciede2000(lab2, lab1) == pytest.approx(expected, abs=1e-4)  # symmetric


def test_lab_of_white_black_and_grey():
    assert lab("#ffffff") == pytest.approx([100.0, 0.0, 0.0], abs=0.05)  # D65 rounded to 5 digits
    assert lab("#000000") == pytest.approx([0.0, 0.0, 0.0], abs=1e-9)
    L, a, b = lab("#777777")
    assert L == pytest.approx(50.0, abs=0.1)
    assert abs(a) < 0.1 and abs(b) < 0.1


@pytest.mark.parametrize("vision", VISIONS)
def test_simulation_leaves_greys_grey(vision):
    for grey in ("#000000", "#808080", "#ffffff"):
        assert lab(grey, vision) == pytest.approx(lab(grey), abs=0.05)


def test_the_audit_is_reproduced():
    """The old teal and grey: 23.9 apart for normal vision, 4.8 under protanopia, 12.4 under deuteranopia."""
    old_teal, old_grey = "#14a3a0", "#a6a6a6"
    assert difference(old_teal, old_grey, "normal") == pytest.approx(23.9, abs=0.05)
    assert difference(old_teal, old_grey, "protan") == pytest.approx(4.8, abs=0.1)
    assert difference(old_teal, old_grey, "deutan") == pytest.approx(12.4, abs=0.05)


def test_simulation_changes_red_green_but_not_the_others_alike():
    red, green = "#d62728", "#2ca02c"
    assert difference(red, green, "normal") > 50
    assert difference(red, green, "deutan") < 20  # the classic confusion
    assert difference(red, green, "tritan") > 40


@pytest.mark.parametrize("vision", VISIONS)
@pytest.mark.parametrize(("role1", "role2"), list(combinations(ROLES, 2)))
def test_roles_stay_apart(role1, role2, vision):
    d = difference(ROLES[role1], ROLES[role2], vision)
    assert d >= 15, f"{role1} and {role2} are only {d:.1f} apart (CIEDE2000) under {vision} vision"


@pytest.mark.parametrize("name", TEXT)
def test_text_shades_read_on_white(name):
    ratio = contrast(TEXT[name], "#ffffff")
    assert ratio >= 4.5, f"{name} {TEXT[name]} has {ratio:.2f}:1 on white"


def test_contrast_formula():
    assert contrast("#000000", "#ffffff") == pytest.approx(21.0)
    assert contrast("#767676", "#ffffff") == pytest.approx(4.54, abs=0.01)  # WCAG's usual grey example
    assert contrast("#ffffff", "#ffffff") == pytest.approx(1.0)


def test_text_shades_keep_their_role_hue():
    """A text shade is a darker version of its role colour, not another colour."""
    for role, shade in (
        (palette.PREDICTION, palette.PREDICTION_TEXT),
        (palette.MEASUREMENT, palette.MEASUREMENT_TEXT),
        (palette.ESTIMATE, palette.ESTIMATE_TEXT),
        (palette.TRUTH, palette.TRUTH_TEXT),
    ):
        _, a1, b1 = lab(role)
        _, a2, b2 = lab(shade)
        assert a1 * a2 + b1 * b2 >= 0.8 * (a1**2 + b1**2) ** 0.5 * (a2**2 + b2**2) ** 0.5 - 1e-6


def test_particles_are_shades_of_the_prediction_purple():
    """palette.PARTICLE_WEIGHTS runs from a pale shade of the prediction purple (weight 0) to the purple itself (1),
    lighter to darker and keeping its hue, so a cloud of particles never looks like the teal estimate."""
    from matplotlib.colors import to_hex

    cmap = palette.PARTICLE_WEIGHTS
    assert to_hex(cmap(1.0)) == palette.PREDICTION and to_hex(cmap(0.0)) == palette.PARTICLE_LIGHT
    shades = [to_hex(cmap(x)) for x in (0.0, 0.25, 0.5, 0.75, 1.0)]
    lightness = [lab(c)[0] for c in shades]
    assert lightness == sorted(lightness, reverse=True)  # darker = heavier
    _, a1, b1 = lab(palette.PREDICTION)
    for shade in shades:
        _, a2, b2 = lab(shade)
        assert a1 * a2 + b1 * b2 >= 0.8 * (a1**2 + b1**2) ** 0.5 * (a2**2 + b2**2) ** 0.5 - 1e-6
    for vision in VISIONS:
        assert difference(palette.PARTICLE_LIGHT, palette.ESTIMATE, vision) >= 15


def test_line_styles_tell_the_roles_apart():
    lines = {
        "prediction": palette.PREDICTION_LINE,
        "estimate": palette.ESTIMATE_LINE,
        "truth": palette.TRUTH_LINE,
        "measurement": palette.MEASUREMENT_LINE,
    }
    assert len(set(lines.values())) == len(lines), lines
    assert palette.ESTIMATE_LINE == "-"  # the answer is the solid line
    assert palette.TRUTH_WIDTH >= 2.0  # dots thinner than that vanish
