"""Which tests state facts of seeded runs: the ``fact`` marker, its guard, and a runner for planted tests.

A test marked ``fact`` states something about a run built on seeded random draws (a count, a
bound, a verdict).  ``make test`` runs every such test, and every notebook, again as
another CPU's rounding (``tests/repeats.py``: numpy's lower SIMD levels) with every normal draw
scaled by ``1 ± 1e-12`` (``tests/rounding.py``): what it states must hold in every repeat.  The
repeats select by the marker (``-m fact``), not by folder.

**The guard.** In a run without ``--perturb``, every test that makes a seeded generator
(``np.random.default_rng``, which every simulation, demo model and particle filter of the
course calls), or uses a fixture that did, must be marked ``fact`` or listed in
:data:`UNMARKED` with the reason it needs no repeat; otherwise the test fails, naming the
marker.  So a new test that states a seeded run's number cannot leave the repeats unseen.
"""

from __future__ import annotations

import functools
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

MARKER = "fact"
ROOT = Path(__file__).resolve().parents[1]

# Tests that make seeded generators but state no fact of a seeded run that rounding could move,
# by node id (a file, or a file and a test): the reason each needs no repeat.
UNMARKED = {
    "tests/test_rounding.py": "it perturbs its runs itself and compares them with the plain run: one pass is the check",
    "tests/filters/": "random inputs to identities and properties checked to a tolerance (any draw must pass), "
    "or statistical checks of the filters' own draws with margins of many standard errors",
    "tests/check/": "the checkers run a student's function and the course's on the same draws and compare them "
    "to a tolerance: a verdict, not a number of a noisy run",
    "tests/test_package.py::test_the_nees_is_computed_in_one_place": "a run's NEES against kf.sim.nees of the same "
    "run: one computation both ways, whatever the rounding",
    "tests/test_recording.py": "the frames of a recording against the demo's own pictures: the same run both ways",
    "tests/test_charts.py": "what each chart draws (titles, axes, artists), not the run's numbers",
    "tests/test_bad_arguments.py": "that a bad argument is refused by name, and that a valid call runs: "
    "no number of a noisy run",
    "tests/demos/test_stale.py": "which artists a control redraws and when the picture is drawn in full, not a number",
    "tests/demos/test_light_and_crisp.py": "the light picture against the crisp one of one state",
    "tests/demos/test_hallway_layout.py": "where the two text blocks stand, not what the run did",
    "tests/plots/test_density.py": "the same picture at more pixels: one run drawn twice",
    "tests/plots/test_loop_animation.py": "the README's animation draws the demo's own frames, not the run's numbers",
    "tests/plots/test_role_styles.py": "the line style of each role in every figure, not the run's numbers",
    "tests/sim/test_plaza_family.py::test_the_table_prints_a_row_per_filter_and_how_it_was_measured": (
        "that the table prints each row's name and its notes, not the runs' numbers"
    ),
    # tests of files whose other tests state facts (each marked fact on its own)
    "tests/demos/test_landmark_loop.py::test_sliders_rerun_the_lap_once_where_they_are_let_go": (
        "which sliders rerun when let go and which follow the drag, not the run"
    ),
    "tests/demos/test_landmark_loop.py::test_moving_in_time_never_reruns": (
        "that stepping in time keeps the run it shows: no number of the run"
    ),
    "tests/demos/test_landmark_loop.py::test_kidnap_button_carries_the_robot_off_at_the_step_shown_and_undoes": (
        "the kidnap step the button sets and the readout names, and the run against kf.sim.landmark_loop of the same "
        "settings: one run both ways"
    ),
    "tests/demos/test_landmark_loop.py::test_the_column_fits_a_laptop": "the widths of the column's rows, not the run",
    "tests/demos/test_landmark_loop.py::test_picture_shows_the_step": (
        "each artist against the run it draws at the step shown, the notes of the dropout and kidnap it was given, the "
        "strips' round limit: one run both ways"
    ),
    "tests/demos/test_landmark_loop.py::test_the_demo_widgets_are_found": (
        "that the readout widget is found, not the run"
    ),
    "tests/demos/test_demos.py::test_first_frame_is_drawn_and_repeatable": (
        "the first picture is drawn, finite at the opening settings, the same for the same seed, and the buttons are "
        "as listed: one run drawn twice"
    ),
    "tests/demos/test_demos.py::test_hallway_predict_update_reset": (
        "Predict and Update against the motion kernel and Bayes' rule on what the sensor read (a reliability under 1: "
        "never a zero likelihood): the same formulas both ways, whatever the draws"
    ),
    "tests/demos/test_demos.py::test_hallway_reset_restores_first_frame": (
        "Reset against the first picture: one run drawn twice"
    ),
    "tests/demos/test_demos.py::test_run_plays_to_the_end_on_an_event_loop": (
        "the animation's frames on an event loop, forward to the end, not the run's numbers"
    ),
    "tests/demos/test_demos.py::test_pause_stops_before_the_next_frame": (
        "that Pause stops the animation, not the run's numbers"
    ),
    "tests/demos/test_descriptions_ch00_ch06.py::test_hallway_sets_the_step_off_with_a_comma": (
        "the punctuation of the description at the opening settings, not the run's numbers"
    ),
    "tests/demos/test_descriptions_ch00_ch06.py::test_coloured_text_uses_the_text_shades_and_choices_have_a_name": (
        "the colours the readouts write and the names of the choice buttons, not the run's numbers"
    ),
    "tests/demos/test_descriptions_ch00_ch06.py::test_the_tracker_readout_writes_the_estimate_in_its_text_shade": (
        "the colour of the estimate's words, not the run's numbers"
    ),
    "tests/demos/test_descriptions_ch07_ch11.py::test_landmark_loop_says_the_drawn_ellipse": (
        "inside or outside in the description against the run's own NEES at the 2σ bound: the same comparison both ways"
    ),
    "tests/demos/test_descriptions_ch07_ch11.py::test_landmark_loop_says_blind_kidnapped_and_honest": (
        "the verdict against the run's own honesty(), and the blind and kidnap words of the settings given: the same "
        "facts both ways"
    ),
    "tests/demos/test_descriptions_ch07_ch11.py::test_particle_cloud_says_whether_it_resampled": (
        "the resampling words against the run's own resampled flags: the same facts both ways"
    ),
    "tests/demos/test_descriptions_ch07_ch11.py::test_readouts_write_colours_in_the_text_shades": (
        "the colours the readouts write, not the run's numbers"
    ),
    "tests/demos/test_descriptions_ch07_ch11.py::test_every_group_of_choice_buttons_has_a_name": (
        "the names of the choice buttons, not the run"
    ),
    "tests/demos/test_sigma_points.py::test_exact_row_only_for_x_squared": (
        "which functions get an exact row, and its closed form: no sampled number"
    ),
    "tests/demos/test_sigma_points.py::test_output_legend_sits_above_the_panel_and_densities_stay_inside_it": (
        "where the legends sit, and the Gaussians cut at the density axis's top (an arrow at variance 0), whatever top "
        "the samples give"
    ),
    "tests/demos/test_sigma_points.py::test_ukf_readout_is_unscented_1d_at_the_slider_values": (
        "the UKF row against kf.unscented_1d of the slider values: no draw enters it"
    ),
    "tests/demos/test_sigma_points.py::test_ukf_mean_of_x_squared_is_exact_and_its_variance_short_by_s4": (
        "the UKF's moments against their closed form: no draw enters them"
    ),
    "tests/demos/test_sigma_points.py::test_every_function_has_output_limits_that_hold_its_curve": (
        "each function's fixed output axis, not the samples"
    ),
    "tests/demos/test_sigma_points.py::test_bad_lam_is_refused_by_the_model": "that a bad λ is refused",
    "tests/demos/test_sigma_points.py::test_the_mean_slider_starts_inside_its_range_and_moves_both_ways": (
        "the slider's range, and the sigma points and the UKF's answer it moves: no draw enters them"
    ),
    "tests/demos/test_sigma_points.py::test_the_ekf_is_teal_dashed_and_the_ukf_teal_solid": (
        "the colours and line styles of the estimates, not the run"
    ),
    "tests/demos/test_linearization.py::test_first_frame_is_x_squared_and_the_ekf_is_the_tangent_gaussian": (
        "the opening settings and the EKF's tangent Gaussian: no draw enters them"
    ),
    "tests/demos/test_linearization.py::test_the_ekf_is_drawn_teal_and_the_caption_says_so": (
        "the EKF's colour and the caption, not the run"
    ),
    "tests/demos/test_curve_axes.py::test_every_tick_label_reads_its_ticks_value": (
        "each tick label against its tick, whatever limits the samples give"
    ),
    "tests/demos/test_curve_axes.py::test_densities_are_real_densities": (
        "the input density against its formula and the histogram's area against the share of the same samples: one "
        "computation both ways"
    ),
    "tests/demos/test_curve_axes.py::test_a_new_function_gets_its_own_output_axis_in_one_full_draw": (
        "each function's fixed output axis, set in one full draw: not the samples"
    ),
    "tests/demos/test_particle_cloud.py::test_first_frame": (
        "the opening settings, and the run and its readout against kf.sim.particle_loop of the same settings: one run "
        "both ways"
    ),
    "tests/demos/test_particle_cloud.py::test_kidnap_acts_at_the_step_shown": (
        "the kidnap step the button sets, not the run's numbers"
    ),
    "tests/demos/test_particle_cloud.py::test_moving_in_time_only_redraws": (
        "that stepping in time keeps the run and moves the cursor, not the run's numbers"
    ),
    "tests/demos/test_particle_cloud.py::test_readout_says_what_happened_after_the_weights": (
        "the readout's resampling words against the run's own flags, and the injected count round(0.05 N): the same "
        "facts both ways"
    ),
    "tests/demos/test_particle_cloud.py::test_the_column_fits_a_laptop": (
        "the widths and the height of the layout, with room for many more readout lines: not the run"
    ),
    "tests/demos/test_tracker.py::test_sensor_slider_changes_the_world_and_the_filter_is_told_the_truth": (
        "the same noise draw scaled by the sensor slider, and the filter's Q from the settings: identities whatever "
        "the draws"
    ),
    "tests/demos/test_tracker.py::test_readout_says_the_honesty_test_and_the_ellipse_reach": (
        "the readout against the run's own honesty, ellipse and error: the same numbers both ways"
    ),
    "tests/demos/test_tracker.py::test_picture_shows_the_frame_estimate_ellipse_and_velocities": (
        "each artist and readout number against the run it draws at the step shown: one run both ways"
    ),
    "tests/demos/test_tracker.py::test_time_and_retuning_never_redraw_the_map": (
        "that stepping and retuning never redraw the map, whose limits are made from the true path: not a number of "
        "the run"
    ),
    "tests/demos/test_association.py::test_the_estimate_is_drawn_over_the_truth_and_its_ellipse_over_the_estimate": (
        "the drawing order and colours of the estimate and the truth, not the run"
    ),
    "tests/demos/test_association.py::test_the_close_up_sits_where_no_gate_reaches": (
        "the gates, drawn from the scene's fixed prediction (the same for every scan), against the close-up's box: no "
        "draw enters them"
    ),
    "tests/demos/test_association.py::test_gates_drawn_around_every_landmark_and_they_grow_with_the_slider": (
        "the gates of the scene's fixed prediction, growing with the slider: no draw enters them"
    ),
    "tests/demos/test_association.py::test_the_leg_label_stands_at_the_leg_reading_only_with_the_leg": (
        "the leg's label at the leg's reading, shown only with the leg: one run both ways"
    ),
    "tests/demos/test_nees.py::test_factor_reruns_where_it_is_let_go_and_never_redraws_the_axes": (
        "that the slider reruns when let go and the axes are never redrawn, not the run's numbers"
    ),
    "tests/demos/test_nees.py::test_band_is_the_chi_square_band_for_the_number_of_tracks": (
        "the band from the χ² quantiles and the batch's shape: no draw enters them"
    ),
    "tests/demos/test_particle_hallway.py::test_model_replays_the_run_record": (
        "the demo's model against kf.sim's run record of the same seed: one run both ways"
    ),
    "tests/demos/test_particle_hallway.py::test_particle_count_replays_the_same_readings": (
        "a new particle count keeps the truth, the bars and the readings, held at the slider's ends: identities "
        "whatever the draws"
    ),
    "tests/demos/test_particle_hallway.py::test_reset_and_new_run": (
        "Reset restores the first picture, and a new run starts where kf.sim's of its seed does: one run both ways"
    ),
    "tests/demos/test_particle_hallway.py::test_fits_a_laptop": "the picture's height on a laptop, not the run",
    "tests/sim/test_particle_run.py::test_the_world_is_chapter_tens_draw_for_draw": (
        "the particle filter's world against chapter 10's, draw for draw: the same draws both ways"
    ),
    "tests/sim/test_particle_run.py::test_bad_arguments_are_named": "that a bad argument is refused by name",
    "tests/sim/test_localization.py::test_data_are_simulate_robots_step_for_step": (
        "the loop's data against kf.sim.simulate_robot of the same seed: the same draws both ways"
    ),
    "tests/sim/test_localization.py::test_record_is_read_only_and_consistent": (
        "the record's shapes, its read-only arrays and its fields against their definitions (an update never grows det "
        "Σ, whatever the draws): one run both ways"
    ),
    "tests/sim/test_localization.py::test_noise_scales_the_world_and_by_default_the_filter": (
        "the same draws scaled by the noise settings: an identity whatever the draws"
    ),
    "tests/sim/test_localization.py::test_the_filter_is_honest_by_default_and_can_be_told_otherwise": (
        "the filter's noise defaults to the world's, and a noise it is told changes the filter, not the world: "
        "identities whatever the draws"
    ),
    "tests/sim/test_localization.py::test_a_step_function_gets_copies_and_the_infinite_gate": (
        "what a step function is handed (copies, an infinite gate, the shapes), not the run's numbers"
    ),
    "tests/sim/test_localization.py::test_a_broken_step_function_gets_a_value_error_naming_it_and_the_step": (
        "that a broken step function is refused by name, at the step it broke"
    ),
    "tests/sim/test_localization.py::test_a_long_message_prints_the_returned_array_briefly": (
        "the length of an error message, not the run's numbers"
    ),
    "tests/sim/test_localization.py::test_a_run_since_another_is_the_same_run_to_the_last_bit": (
        "a run continued from another against the same run computed afresh, bit for bit: one run both ways"
    ),
    "tests/sim/test_localization.py::test_since_copies_the_steps_before_a_kidnap_and_nothing_after_a_change_of_filter": (  # noqa: E501
        "which steps since= copies from the last run: one run both ways"
    ),
    "tests/plots/test_loop.py::test_position_errors_are_truth_minus_estimate_and_two_sigma_per_axis": (
        "the strips' errors and bounds against their definitions: one run both ways"
    ),
    "tests/plots/test_loop.py::test_chart_draws_the_step_asked_for": (
        "the chart's artists against the run at the step asked for, in strips whose limit holds the run by "
        "construction: one run both ways"
    ),
    "tests/plots/test_loop.py::test_kidnap_splits_the_true_path": (
        "the true path split at the kidnap step the run was given, not its numbers"
    ),
    "tests/plots/test_loop.py::test_a_step_outside_the_run_is_refused": "that a step outside the run is refused",
    "tests/plots/test_loop.py::test_the_ellipses_are_drawn_over_the_estimated_robot": (
        "the drawing order of the ellipses and the robot, not the run"
    ),
    "tests/plots/test_loop.py::test_strips_plot_metres_on_real_axes_with_a_round_limit": (
        "the strips' round limit and ticks against the rule that makes them from the run, and the error where it is "
        "drawn: one run both ways"
    ),
    "tests/plots/test_loop.py::test_run_never_redraws_the_background": (
        "that Run blits over a background drawn once, not a number of the run"
    ),
    "tests/plots/test_particles_view.py::test_the_picture_shows_the_step": (
        "each artist against the run it draws at the step asked for: one run both ways"
    ),
    "tests/plots/test_particles_view.py::test_a_kidnap_splits_the_truth_and_marks_the_strip": (
        "the same artists moved to a kidnapped run, split at the kidnap step it was given: not its numbers"
    ),
    "tests/plots/test_particles_view.py::test_a_bigger_cloud_replaces_the_offsets": (
        "the cloud takes a bigger run's particle count: a shape"
    ),
    "tests/plots/test_particles_view.py::test_bad_step": "that a step outside the run is refused",
    "tests/plots/test_particles_view.py::test_the_cloud_chart_is_the_picture_of_one_step": (
        "the static chart's cloud and trail against the run at the step asked for: one run both ways"
    ),
    "tests/plots/test_particles_view.py::test_the_dots_take_the_size_asked_for": "the dots' size, not the run",
    "tests/plots/test_particles_view.py::test_both_particle_pictures_shade_the_particles_with_the_palettes_purple": (
        "the colormap and legend colours of the particles, not the run's numbers"
    ),
    "tests/plots/test_ukf_charts.py::test_comparison_chart_draws_both_estimates_and_errors": (
        "the lines' styles and data against the two runs, and the RMS errors the legend prints from them: the same "
        "numbers both ways"
    ),
    "tests/plots/test_ukf_charts.py::test_comparison_chart_refuses_two_different_drives": (
        "that two runs of different drives are refused"
    ),
    "tests/plots/test_curves_view.py::test_linearization_view_follows_the_model": (
        "the view's artists and text against the model it draws: one run both ways"
    ),
    "tests/plots/test_curves_view.py::test_sigma_points_view_follows_the_model": (
        "the sigma points and the UKF row against the model: no draw enters them"
    ),
    "tests/plots/test_tracking_view.py::test_tracker_map_holds_the_path_at_one_scale_and_shows_the_step": (
        "the map's limits, made from the true path, and each artist against the run at the step shown: one run both "
        "ways"
    ),
    "tests/plots/test_tracking_view.py::test_tracker_steps_redraw_only_the_moving_artists": (
        "that steps redraw only the moving artists, not a number of the run"
    ),
    "tests/plots/test_tracking_view.py::test_tracker_ellipse_is_lightly_filled_so_a_huge_one_still_shows": (
        "the ellipse's fill and edge colours, not the run"
    ),
    "tests/plots/test_runs.py::test_chart_draws_two_finite_panels": (
        "two finite panels and a PNG of a short walk at ordinary settings: a picture, not a number of the run"
    ),
    "tests/plots/test_runs.py::test_top_panel_is_estimate_band_truth_and_readings_relative_to_the_commanded_path": (
        "each line and the band against the run it draws: one run both ways"
    ),
    "tests/plots/test_runs.py::test_without_detrend_positions_are_plotted_as_they_are": (
        "the truth's line against the run it draws: one run both ways"
    ),
    "tests/plots/test_runs.py::test_bottom_panel_is_innovations_in_their_sqrt_S_band": (
        "the innovations and their band against the run: one run both ways"
    ),
    "tests/plots/test_runs.py::test_bad_start_is_refused": "that a bad start is refused by name",
}

_made = [0]  # seeded generators made in this process
seeded_fixtures: set = set()  # the fixture definitions whose set-up made a seeded generator


def _counting(default_rng):
    """``np.random.default_rng`` that also counts the generators it makes."""

    @functools.wraps(default_rng)
    def counted(*args, **kwargs):
        _made[0] += 1
        return default_rng(*args, **kwargs)

    return counted


def count_one() -> None:
    """Count a seeded run handed out again (``tests/frozen_runs.py``) as a generator made: its test used one."""
    _made[0] += 1


def install() -> None:
    """Count every generator made from now on (the guard's eyes)."""
    np.random.default_rng = _counting(np.random.default_rng)


def made() -> int:
    """How many seeded generators were made so far."""
    return _made[0]


def seeded(item) -> bool:
    """Whether the test made a seeded generator (in its set-up or its call) or uses a fixture that did."""
    if made() > getattr(item, "generators_before", made()):
        return True
    definitions = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    return any(d in seeded_fixtures for name in item.fixturenames for d in definitions.get(name, ()))


def listed(nodeid: str) -> str | None:
    """The reason a test may make seeded generators without the marker, or None."""
    for where, reason in UNMARKED.items():
        if where.endswith(("/", ".py")):  # a folder or a whole file
            hit = nodeid.startswith(where)
        else:  # one test, with all its parameters
            hit = nodeid == where or nodeid.startswith(where + "[")
        if hit:
            return reason
    return None


def complaint(item) -> str | None:
    """What is wrong with the test's marker, or None: a seeded run neither marked nor listed."""
    marked = item.get_closest_marker(MARKER) is not None
    if seeded(item) and not marked and listed(item.nodeid) is None:
        return (
            f"{item.nodeid} runs a seeded simulation (it made a seeded generator or uses a fixture "
            f"that did) but is not marked '{MARKER}': mark it (@pytest.mark.{MARKER}, or pytestmark in its module) "
            "so that make test repeats it under other rounding, or list it in tests/facts.py UNMARKED with the "
            "reason it needs no repeat"
        )
    return None


def run_planted(files: dict[str, str], *options: str) -> str:
    """Run pytest, with ``options``, on ``files`` (name: text) written to a folder under tests/ (so the
    root conftest governs them), in a fresh process; what pytest printed (``-rA``: every verdict)."""
    folder = Path(tempfile.mkdtemp(prefix=".probe-", dir=ROOT / "tests"))
    try:
        for name, text in files.items():
            (folder / name).write_text(text)
        result = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-rA", "-p", "no:cacheprovider", *options, str(folder)],
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=300,
        )
    finally:
        shutil.rmtree(folder)
    return result.stdout


def planted(source: str, *options: str) -> tuple[dict[str, str], str]:
    """:func:`run_planted` on ``source`` as one test file: each test's verdict by name, and what pytest printed."""
    printed = run_planted({"test_planted.py": source}, *options)
    found = re.findall(r"^(PASSED|FAILED) \S*::(\w+)", printed, re.M)
    return {name: verdict for verdict, name in found}, printed
