"""The plain-text tables run records print: aligned columns, a rule under the header, and a clear error."""

import pytest

from kfcourse.sim.records import text_table


def test_columns_line_up_under_their_header():
    text = text_table(["seed", "error (m)"], [["0", "0.12"], ["10", "1.5"]])
    header, rule, first, second = text.splitlines()
    assert rule == "----  ---------"
    assert first.startswith("0 ") and first.endswith("0.12")
    assert second.startswith("10") and second.endswith("1.5")
    assert len({len(header), len(rule), len(first), len(second)}) == 1


def test_a_row_with_the_wrong_number_of_cells_is_refused():
    with pytest.raises(ValueError, match="2 cells"):
        text_table(["a", "b"], [["1"]])
