# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The pages' two rst table writers (tapmc.paper._rst), against tables written out by hand and
parsed back by docutils when it is installed."""
import pytest

from tapmc.paper._rst import list_table, simple_table


def test_list_table_writes_header_and_rows_one_cell_a_line():
    lines = list_table(["a", "b"], [[1, "x y"], ["2", 0.5]], widths=(30, 70))
    assert lines == [".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
                     "   * - a", "     - b",
                     "   * - 1", "     - x y",
                     "   * - 2", "     - 0.5"]
    assert list_table(["only"], [])[:3] == [".. list-table::", "   :header-rows: 1", ""]


def test_simple_table_aligns_columns_on_the_widest_cell():
    assert simple_table(["k", "value"], [["long", 1], ["s", 22]]) == [
        "====  =====", "k     value", "====  =====", "long  1    ", "s     22   ", "====  ====="]


def test_both_tables_parse_as_rst_with_the_cells_given():
    core = pytest.importorskip("docutils.core")
    for lines in (list_table(["h1", "h2"], [["c1", "c2"], ["c3", "c4"]], widths=(1, 1)),
                  simple_table(["h1", "h2"], [["c1", "c2"], ["c3", "c4"]])):
        tree = core.publish_doctree("\n".join(lines),
                                    settings_overrides={"report_level": 2, "halt_level": 2})
        walk = getattr(tree, "findall", None) or tree.traverse  # findall: docutils >= 0.18
        cells = [e.astext() for e in walk() if e.tagname == "entry"]
        assert cells == ["h1", "h2", "c1", "c2", "c3", "c4"]
