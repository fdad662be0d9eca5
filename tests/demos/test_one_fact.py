"""Each demo says a fact once: where a demo has both a description (the sentence under its picture) and a
readout (the HTML beside or under it), the two state the same facts of the state shown, in the same words.

Every demo with a readout is driven through several states (steps, slider positions, buttons); at each, the
numbers and verdicts are read back out of both texts, compared with each other, and where a word could mean two
things ("inside": the drawn 2σ ellipse) checked against the run itself.
"""

from __future__ import annotations

import html
import re

import numpy as np
import pytest

import kfcourse as kf
from tests.demos.describing import said, shown_on_page
from tests.demos.layout import readout
from tests.demos.test_landmark_loop import reference_step

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def plain(text: str) -> str:
    """A readout as the student reads it: its lines, without tags or entities."""
    return html.unescape(re.sub(r"<[^>]+>", "", text.replace("<br>", "\n")))


def found(pattern: str, text: str) -> tuple:
    """The groups of ``pattern``'s one match in ``text``."""
    match = re.search(pattern, text)
    assert match, (pattern, text)
    return match.groups()


# --------------------------------------------------------------------------- chapter 10: landmark loop
def loop_facts_said(text: str) -> dict:
    """What the landmark loop's description says of the step shown."""
    blind = "sees nothing (the sensor is blind)" in text
    used = 0 if blind else found(r" uses (\d+|no) readings?", text)[0]
    rejected = re.search(r", rejects (\d+)", text)
    kidnap = re.search(r"(robot kidnapped|a kidnap comes) at step (\d+)", text)
    area, factor = found(r"its 1σ area (\S+) m²(?: \((×\S+)\))?,", text)
    verdict, nees = found(r"the filter is (honest|timid|over-confident) \(mean NEES ([^)]+)\)\.$", text)
    return {
        "blind": blind,
        "used": 0 if used == "no" else int(used),
        "rejected": int(rejected.group(1)) if rejected else 0,
        "sight back": "(sight back: the nearest landmark only)" in text,
        "kidnap": (kidnap.group(1) == "robot kidnapped", int(kidnap.group(2))) if kidnap else None,
        "error": found(r" is (over 1000|\S+) m off", text)[0],
        "area": area,
        "shrink": factor,
        "inside": found(r", the truth (inside|outside) its 2σ ellipse\.", text)[0],
        "verdict": verdict,
        "nees": nees,
    }


def loop_facts_shown(text: str) -> dict:
    """What the landmark loop's readout says of the step shown, and the two shares it alone gives."""
    text = plain(text).split("Shown: the course's EKF.")[-1]  # a failed step's own message aside
    blind = "sensor blind" in text
    used = 0 if blind else int(found(r"uses (\d+) readings?", text)[0])
    rejected = re.search(r"rejects (\d+) \(outside the gate\)", text)
    kidnap = re.search(r"(kidnapped|a kidnap comes) at step (\d+)", text)
    area, factor = found(r"→ (\S+) m²(?: \((×\S+)\))?\n", text)
    verdict, nees = found(r"this lap, the filter is (honest|timid|over-confident): mean NEES (\S+)", text)
    inside, share, share_3 = found(
        r"truth (inside|outside) the 2σ ellipse; so far inside it at (\d+)% of steps, inside 3σ at (\d+)%", text
    )
    return {
        "blind": blind,
        "used": used,
        "rejected": int(rejected.group(1)) if rejected else 0,
        "sight back": "(sight back: the nearest landmark only)" in text,
        "kidnap": (kidnap.group(1) == "kidnapped", int(kidnap.group(2))) if kidnap else None,
        "error": found(r"position error (over 1000|\S+) m\n", text)[0],
        "area": area,
        "shrink": factor,
        "inside": inside,
        "verdict": verdict,
        "nees": nees,
    }, (int(share), int(share_3))


def check_loop(demo) -> dict:
    """The landmark loop's description and readout say the same facts, and "inside" is the drawn 2σ ellipse."""
    m, run = demo.model, demo.model.run
    k = m.frame
    said_facts = loop_facts_said(said(demo))
    shown_facts, (share, share_3) = loop_facts_shown(readout(demo))
    assert said_facts == shown_facts, (said(demo), readout(demo))
    assert said_facts["inside"] == ("inside" if run.nees[k] <= 2.0**2 else "outside")  # the drawn 2σ ellipse
    assert said_facts["used"] == run.used[k].sum() and said_facts["rejected"] == run.rejected[k].sum()
    assert share == round(100 * np.mean(run.nees[: k + 1] <= 2.0**2))  # the 2σ share, named as the ellipse is
    assert share_3 == round(100 * np.mean(run.inside[: k + 1]))  # the 3σ share, named 3σ
    return said_facts


def test_landmark_loop_says_each_fact_once():
    demo = kf.demos.landmark_loop(seed=0)
    c = demo.controls
    seen = []
    for k in (0, 30, 60, 90, c["frame"].max):  # a normal lap
        c["frame"].value = k
        seen.append(check_loop(demo))
    c["motion"].value = 10**0.5  # prompt 2: blind from step 20 to 89, sight back at 90
    c["frame"].value = 20
    c["dropout"].value = True
    c["frame"].value = 90
    c["dropout"].value = False
    for k in (19, 20, 50, 89, 90, 91):
        c["frame"].value = k
        seen.append(check_loop(demo))
    c["dropout"].value = True  # clear the blind stretch: pressed twice at the same step
    c["dropout"].value = False
    c["motion"].value = 1.0
    c["frame"].value = 60
    c["kidnap"].click()  # prompt 5
    for k in (30, 60, 90):
        c["frame"].value = k
        seen.append(check_loop(demo))
    c["kidnap"].click()
    c["trust_sensor"].value = 0.01  # prompt 6: over-confident, readings rejected
    for k in (40, 100):
        c["frame"].value = k
        seen.append(check_loop(demo))
    # The states cover both sides of each fact.
    assert {s["inside"] for s in seen} == {"inside", "outside"}
    assert {s["kidnap"][0] for s in seen if s["kidnap"]} == {True, False}
    assert any(s["blind"] for s in seen) and any(s["sight back"] for s in seen) and any(s["rejected"] for s in seen)
    assert {s["verdict"] for s in seen} >= {"honest", "over-confident"}
    assert {s["shrink"] is None for s in seen} == {True, False}


def test_landmark_loop_says_each_fact_once_for_your_filter():
    def certain(mu, Sig, u, z, landmarks, dt, M, Q, gate):  # a flat ellipse: the truth outside, the NEES unbounded
        mu, _, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        return mu, np.zeros((3, 3)), used

    demo = kf.demos.landmark_loop(seed=0, filter=certain)
    for k in (0, 60):
        demo.controls["frame"].value = k
        facts = check_loop(demo)
        assert facts["inside"] == "outside" and facts["nees"] == "unbounded"
    demo = kf.demos.landmark_loop(seed=0, filter=reference_step)
    demo.controls["sensor"].value = 10.0
    for k in (0, 60, 121):
        demo.controls["frame"].value = k
        check_loop(demo)


# --------------------------------------------------------------------------- chapter 11: particle cloud
def cloud_facts_said(text: str) -> dict:
    n, error, inside, ess, after = found(
        r"the (\d+) particles spread over .*?their mean (\S+) m from the truth, which is (inside|outside) their 2σ "
        r"ellipse; the effective sample size (\d+) is (under N/2|at or over N/2)",
        text,
    )
    injected = re.search(r"and (\d+) random particles injected", text)
    kidnap = re.search(r"(a kidnap at|a kidnap to come at) step (\d+)", text)
    return {
        "n": int(n),
        "error": error,
        "inside": inside,
        "ess": int(ess),
        "resampled": after == "under N/2" and "so the cloud is resampled" in text,
        "injected": int(injected.group(1)) if injected else 0,
        "kidnap": (kidnap.group(1) == "a kidnap at", int(kidnap.group(2))) if kidnap else None,
    }


def cloud_facts_shown(text: str) -> dict:
    text = plain(text)
    injected = re.search(r", (\d+) particles injected", text)
    kidnap = re.search(r"(kidnapped|a kidnap comes) at step (\d+)", text)
    return {
        "n": int(found(r": (\d+) particles, ", text)[0]),
        "error": found(r"position error (\S+) m, ", text)[0],
        "inside": found(r"truth (inside|outside) the 2σ ellipse\n", text)[0],
        "ess": int(found(r"Neff = (\d+) \(", text)[0]),
        "resampled": "resampled" in text and "Neff under N/2" in text,
        "injected": int(injected.group(1)) if injected else 0,
        "kidnap": (kidnap.group(1) == "kidnapped", int(kidnap.group(2))) if kidnap else None,
    }


def check_cloud(demo) -> dict:
    run, k = demo.model.run, demo.model.frame
    said_facts, shown_facts = cloud_facts_said(said(demo)), cloud_facts_shown(readout(demo))
    assert said_facts == shown_facts, (said(demo), readout(demo))
    assert said_facts["inside"] == ("inside" if run.nees[k] <= 2.0**2 else "outside")  # the drawn 2σ ellipse
    assert said_facts["resampled"] == bool(run.resampled[k])
    return said_facts


def test_particle_cloud_says_each_fact_once():
    demo = kf.demos.particle_cloud(seed=0)
    c = demo.controls
    seen = []
    for k in (0, 1, 60, 100):
        c["frame"].value = k
        seen.append(check_cloud(demo))
    c["global_start"].value = True  # prompt 1: the cloud covers the map, then finds the robot
    for k in (0, 5, 30):
        c["frame"].value = k
        seen.append(check_cloud(demo))
    c["global_start"].value = False
    c["frame"].value = 60
    c["kidnap"].click()  # prompt 2: lost, then found again with injection
    c["injection"].value = True
    for k in (30, 60, 90, 121):
        c["frame"].value = k
        seen.append(check_cloud(demo))
    assert {s["inside"] for s in seen} == {"inside", "outside"}
    assert {s["resampled"] for s in seen} == {True, False} and any(s["injected"] for s in seen)
    assert {s["kidnap"][0] for s in seen if s["kidnap"]} == {True, False}


# --------------------------------------------------------------------------- chapter 6: NEES panel and tracker
def nees_facts_said(text: str) -> tuple:
    factor, which = found(r"assuming (\S+) × the true (R|Q) ", text)
    mean = found(r"has a mean of (\S+) \(", text)[0]
    shares = found(r"band at (\d+) %, (\d+) % and (\d+) % of the steps", text)
    verdict = found(r"The filter is (.+)\.$", text)[0]
    return factor, which, mean, shares, verdict


def nees_facts_shown(text: str) -> tuple:
    text = plain(text)
    factor, which, mean = found(r"filter assumes (\S+) × the true (R|Q): mean NEES = (\S+) ", text)
    shares = found(r"below / inside / above the band: (\d+)% / (\d+)% / (\d+)%", text)
    verdict = text.strip().split("\n")[-1]
    return factor, which, mean, shares, verdict


def test_nees_panel_says_each_fact_once():
    demo = kf.demos.nees_panel(seed=0)
    verdicts = set()
    for which in ("R", "Q"):
        for factor in (0.01, 10**-0.5, 1.0, 10.0, 100.0):
            demo.controls["which"].value = which
            demo.controls["factor"].value = factor
            said_facts = nees_facts_said(said(demo))
            assert said_facts == nees_facts_shown(readout(demo)), (said(demo), readout(demo))
            assert said_facts[0] == shown_on_page(demo.controls["factor"])  # the factor as its slider shows it
            verdicts.add(said_facts[-1].split(":")[0])
    demo.controls["new"].click()
    assert nees_facts_said(said(demo)) == nees_facts_shown(readout(demo))
    assert verdicts == {"honest", "timid", "over-confident"}


def tracker_facts_said(text: str) -> tuple:
    mode, gain, error, inside, radius, verdict = found(
        r": (starting guess|start-up|jittery|coasting|balanced)(?:, K = (\S+))?; (\S+) m off, (inside|outside) the "
        r"2σ ellipse \((\S+) m\); (honest|timid|over-confident)\.$",
        text,
    )
    return mode, gain, error, inside, radius, verdict


def tracker_facts_shown(text: str) -> tuple:
    _, ellipse, regime, honesty = plain(text).split("\n")  # its four lines
    error, inside, radius = found(r"^estimate (\S+) m off, (inside|outside) the 2σ ellipse \(([0-9.]+) m", ellipse)
    gain, regime = found(r"^(?:K = (\S+)\s+)?(.+)$", regime)
    mode = regime.split(":")[0].replace("K → 1", "jittery").replace("K → 0", "coasting")
    verdict = found(r"^(honest|timid|over-confident): mean position NEES", honesty)[0]
    return mode, gain, error, inside, radius, verdict


def test_tracker_says_each_fact_once():
    demo = kf.demos.tracker(seed=0)
    c, m = demo.controls, demo.model
    seen = []
    settings = [{}, {"sigma": 3.0}, {"sigma": 1.0, "Q": 1e4}, {"Q": 1.0, "R": 1e7}, {"R": 1e-3}]
    for setting in settings:  # the five prompts of chapter 6
        for key, value in setting.items():
            c[key].value = value
        for k in (0, 10, 29, 90, 100, c["frame"].max):
            c["frame"].value = k
            said_facts = tracker_facts_said(said(demo))
            assert said_facts == tracker_facts_shown(readout(demo)), (said(demo), readout(demo))
            mode, gain, _, inside, _, _ = said_facts
            off = m.run.truth[k, :2] - m.est.mu[k, :2]
            assert inside == ("inside" if off @ np.linalg.solve(m.est.Sig[k, :2, :2], off) <= 2.0**2 else "outside")
            assert (gain is None) == (k == 0) and mode == m.mode()  # no gain at step 0, in either place
            seen.append(said_facts)
    assert {s[3] for s in seen} == {"inside", "outside"}
    assert {s[0] for s in seen} == {"starting guess", "start-up", "jittery", "coasting", "balanced"}
    assert {s[5] for s in seen} == {"honest", "timid", "over-confident"}


# --------------------------------------------------------------------------- chapter 8: data association
def association_facts_said(text: str) -> dict:
    passed, total = found(r": (\d+) of (\d+) readings pass", text)
    rejected = {
        int(k): (int(j), d) for k, d, j in re.findall(r"reading (\d+) rejected at (\S+)σ from landmark (\d+)", text)
    }
    leg = None
    if "the pedestrian's leg" in text:
        taken = re.search(r"leg taken for landmark (\d+) at (\S+)σ", text)
        if taken:
            leg = (int(taken.group(1)), taken.group(2), True)
        else:
            d, j = found(r"leg rejected at (\S+)σ from landmark (\d+)", text)
            leg = (int(j), d, False)
    stays = re.search(r"the estimate stays the prediction, (\S+) m from the truth", text)
    errors = (stays.group(1), stays.group(1)) if stays else found(r"position error from (\S+) m to (\S+) m\.", text)
    many = re.search(r"\((\d+) landmark readings rejected", text)
    return {
        "passed": (int(passed), int(total)),
        "rejected": rejected,
        "many rejected": int(many.group(1)) if many else None,
        "leg": leg,
        "errors": tuple(errors),
    }


def association_table(text: str) -> list[tuple[str, int, str, bool]]:
    """The readout's rows: (name, landmark, distance, accepted), the heading aside."""
    rows = re.findall(r"<tr>(.*?)</tr>", text)[1:]
    table = []
    for row in rows:
        name, landmark, d, verdict = (plain(cell) for cell in re.findall(r"<td[^>]*>(.*?)</td>", row))
        assert verdict == "rejected" or verdict == f"→ landmark {landmark}", row
        table.append((name, int(landmark), d, verdict != "rejected"))
    return table


def test_data_association_says_each_fact_once():
    seen = set()
    for seed in (0, 3):
        demo = kf.demos.data_association(seed=seed)
        for leg in ("none", "a pedestrian's leg"):
            demo.controls["leg"].value = leg
            for gate in (1.0, 2.0, 3.0, 4.7, 4.8, 5.0, 6.0):
                demo.controls["gate"].value = gate
                text, shown = said(demo), readout(demo)
                facts, table = association_facts_said(text), association_table(shown)
                passed = sum(accepted for *_, accepted in table)
                assert facts["passed"] == (passed, len(table))
                assert f"corrected with {passed} of {len(table)} readings" in shown
                before, after = found(r"predicted (\S+) m; corrected with \d+ of \d+ readings (\S+) m\.", plain(shown))
                assert facts["errors"] == (before, after if passed else before), (text, shown)
                landmarks_lost = [row for row in table if row[0] != "the leg" and not row[3]]
                if facts["many rejected"] is not None:
                    assert facts["many rejected"] == len(landmarks_lost)
                else:
                    assert facts["rejected"] == {int(n.split()[1]): (j, d) for n, j, d, _ in landmarks_lost}
                legs = [(j, d, accepted) for name, j, d, accepted in table if name == "the leg"]
                assert legs == ([facts["leg"]] if facts["leg"] else [])
                if facts["leg"]:
                    seen.add("leg taken" if facts["leg"][2] else "leg rejected")
                seen.add("all pass" if passed == len(table) else "some rejected" if passed else "none pass")
                seen.add("few lost" if facts["rejected"] else "many lost" if facts["many rejected"] else "none lost")
    assert seen == {"leg taken", "leg rejected", "all pass", "some rejected", "few lost", "many lost", "none lost"}
