"""Reading a demo's description in the tests: what it says, checked, after a control moves.

The helpers of ``test_descriptions_ch00_ch06.py`` and ``test_descriptions_ch07_ch11.py``: a
description is one or two sentences with every number finite, it changes when a control moves,
and it names a slider's value as the slider's readout shows it.
"""

from __future__ import annotations

import re

import ipywidgets as widgets

SENTENCE_END = re.compile(r"[.!?](?=\s|$)")
NOT_A_NUMBER = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)


def shown_on_page(control: widgets.Widget) -> str:
    """The text a slider's readout shows: its value in d3-format's ``readout_format`` (an IntSlider: the integer).

    Written apart from the demos' own ``shown``: Python's alternate form of "g" keeps the trailing zeros as
    JavaScript's toPrecision does; its exponent loses the leading zero and a whole number its trailing point.
    """
    if isinstance(control, widgets.IntSlider):
        return str(control.value)
    fmt = control.readout_format
    text = format(control.value, fmt.replace(".", "#.") if fmt.endswith("g") else fmt)
    text = re.sub(r"e([+-])0*(\d)", r"e\1\2", text).removesuffix(".")
    if float(text) == 0:
        text = text.lstrip("-")
    return text.replace("-", "\u2212") if text.startswith("-") else text


def said(demo) -> str:
    """The demo's description, checked: one or two sentences, every number finite."""
    text = demo.description.text
    assert text and not NOT_A_NUMBER.search(text), text
    assert 1 <= len(SENTENCE_END.findall(text)) <= 2, text
    return text


def move(demo, name: str, value) -> str:
    """Set a control, and return the new description, which must differ from the one before and, for a
    slider, name the value its readout shows."""
    before = said(demo)
    control = demo.controls[name]
    control.value = value
    after = said(demo)
    assert after != before, (name, value, after)
    if isinstance(control, widgets.IntSlider | widgets.FloatSlider | widgets.FloatLogSlider):
        assert shown_on_page(control) in after, (name, shown_on_page(control), after)
    return after


def press(demo, name: str) -> str:
    """Click a button, and return the new description, which must differ from the one before."""
    before = said(demo)
    demo.controls[name].click()
    after = said(demo)
    assert after != before, (name, after)
    return after


def slider_ends(control: widgets.Widget) -> tuple:
    """A slider's two ends as values (a log slider: its base to the power of its ends)."""
    if isinstance(control, widgets.FloatLogSlider):
        return control.base**control.min, control.base**control.max
    return control.min, control.max


def at_the_ends(demo, names, then=()) -> list[str]:
    """Each slider of ``names`` at its minimum and its maximum, each followed by the presses ``then``: every
    description on the way is checked, and names the slider's readout."""
    texts = []
    for name in names:
        control = demo.controls[name]
        for end in slider_ends(control):
            control.value = end
            assert shown_on_page(control) in said(demo), (name, end, said(demo))
            texts.append(said(demo))
            for button in then:
                demo.controls[button].click()
                texts.append(said(demo))
    return texts
