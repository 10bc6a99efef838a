# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Slow (about 5 minutes of one core): the paper-scale page is what the committed campaign
gives. The fast suite checks that the pages follow from their committed CSVs
(test_validation_report.py); this draws every figure anew from the campaign's finished runs
(profiles, pores, dumps) and compares the CSVs and pages with the committed ones. Run it after
a campaign commit, before committing the regenerated page:

    ctest --test-dir build -L slow -R paper_scale_regeneration
"""

import csv as csv_module
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PYTHON_DIR = SOURCE / "tools" / "python"
sys.path.insert(0, str(PYTHON_DIR))

from tapmc.paper import _runs  # noqa: E402
from tapmc.paper.questions import campaign_runs, ramp_alpha  # noqa: E402
from tapmc.paper.validation_appendix import APPENDICES  # noqa: E402

DOC = SOURCE / "doc"
#: every page a report writes: the main page and its appendices
PAGE_FILES = ["validation.rst"] + [f"{name}.rst" for name in APPENDICES]


@pytest.mark.skipif(not _runs.pores_available(), reason="tapmc-pores is not built: Figs. 9 "
                    "and 10")
def test_paper_scale_page_is_what_the_committed_campaign_gives(tmp_path):
    """doc/paper_scale is 'report --full --finished-only' of the committed paper-scale
    campaign: drawn anew from a copy of its finished runs, the page and its CSVs are the
    committed ones (the questions folder comes from tapmc-paper question)."""
    campaign = tmp_path / "full"
    shutil.copytree(DOC / "validation" / "data" / "full", campaign,
                    ignore=shutil.ignore_patterns("restart.*", "campaign.lock"))
    out = tmp_path / "page"
    shutil.copytree(DOC / "paper_scale" / "validation" / "questions",
                    out / "validation" / "questions",
                    ignore=shutil.ignore_patterns("partial"))  # local work folders
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    done = subprocess.run([sys.executable, "-m", "tapmc.paper", "report", "--full", "--seeds",
                           "1", "--finished-only", "--campaign", str(campaign), "--out",
                           str(out)], env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    committed = DOC / "paper_scale"
    for name in PAGE_FILES:
        assert (out / name).read_text() == (committed / name).read_text(), (
            f"doc/paper_scale/{name} is not what the committed campaign gives: run "
            "'build/tapmc-paper report --full --seeds 1 --finished-only --campaign "
            "doc/validation/data/full --out doc/paper_scale' and commit the result")
    for csv in sorted((committed / "validation").glob("*.csv")):
        assert_same_table(out / "validation" / csv.name, csv)


#: How far a number of a regenerated CSV may lie from the committed one: the last digits of a
#: float written in full depend on the BLAS and numpy that summed it, not on the campaign.
CSV_RELATIVE_TOLERANCE = 1e-9


def _close(a, b):
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    return abs(x - y) <= CSV_RELATIVE_TOLERANCE * max(abs(x), abs(y)) or (x != x and y != y)


def assert_same_table(fresh, committed):
    """The regenerated CSV has the committed one's header and rows, every text cell the same
    and every number within CSV_RELATIVE_TOLERANCE."""
    with open(fresh, newline="") as f:
        new = list(csv_module.reader(f))
    with open(committed, newline="") as f:
        old = list(csv_module.reader(f))
    assert len(new) == len(old), f"{committed.name}: {len(new)} rows, committed {len(old)}"
    for k, (a, b) in enumerate(zip(new, old)):
        assert len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b)), (
            f"{committed.name}, row {k + 1}: {a} is not the committed {b}")


def test_the_table_comparison_takes_rounding_not_a_change(tmp_path):
    """The comparison's own control: a last-digit difference passes, a changed number, a
    changed word and a missing row do not."""
    base = tmp_path / "a.csv"
    base.write_text("x,y,name\n0.1234567890123,1,done\n")
    for text, same in (("0.1234567890124,1,done\n", True), ("0.1234568,1,done\n", False),
                       ("0.1234567890123,1,under way\n", False), ("", False)):
        other = tmp_path / "b.csv"
        other.write_text("x,y,name\n" + text)
        if same:
            assert_same_table(other, base)
        else:
            with pytest.raises(AssertionError):
                assert_same_table(other, base)


def test_the_runs_table_is_the_committed_campaigns(tmp_path):
    """campaign_runs.csv (the checks' appendix: every run's settings, state, costs and
    versions) is what the committed campaign's manifest and run folders give."""
    committed = DOC / "paper_scale" / "validation" / "questions" / campaign_runs.CSV
    fresh = campaign_runs.save(tmp_path / campaign_runs.CSV,
                               campaign_runs.analyse(DOC / "validation" / "data" / "full"))
    assert fresh.read_text() == committed.read_text(), (
        "doc/paper_scale/validation/questions/campaign_runs.csv is not the committed "
        "campaign's: run 'build/tapmc-paper question campaign-runs' with the campaign stopped")


def test_the_paper_ramps_alpha_is_the_committed_campaigns(tmp_path):
    """ramp_alpha.csv (gradient-no-hysteresis's rows at 4000 taps per level) is what the
    committed campaign's paper ramps give, those still running included."""
    committed = DOC / "paper_scale" / "validation" / "questions" / ramp_alpha.CSV
    fresh = ramp_alpha.save(tmp_path / ramp_alpha.CSV,
                            ramp_alpha.analyse(DOC / "validation" / "data" / "full"))
    assert_same_table(fresh, committed)
