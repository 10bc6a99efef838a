# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The report never trusts damaged data (issue 41). ``report --finished-only`` checks every
finished run against its DONE.json (tapmc.campaign.verify_finished_run) and refuses a cut or
malformed taps.dat; ``report --from-data`` checks report.json and every figure CSV before it
renders, and ``--refit`` replaces a CSV only by a whole one. Each case: the exit status, a
message naming the damaged file (and line), no traceback, and the page and CSVs already in
the output folder unchanged. Fake campaigns and copies of the committed data in tmp_path;
the commands run in this process (tapmc.paper.cli.main), as the installed tapmc-paper does."""

import json
import re
import os
import shutil
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from paper_fakes import FakeCampaign, write_constant_eps  # noqa: E402
from tapmc.campaign import (CampaignDirectoryError, CampaignError,  # noqa: E402
                            verify_finished_run)
from tapmc.campaign import provenance  # noqa: E402
from tapmc.paper import _plotting as P  # noqa: E402
from tapmc.paper import _runs, cli, validation  # noqa: E402
from tapmc.paper.scales import QUICK  # noqa: E402

DOC = SOURCE / "doc"


def run_cli(capsys, *args):
    """(exit status, stderr) of ``tapmc-paper ARGS``."""
    try:
        status = cli.main([str(a) for a in args])
    except SystemExit as exc:  # argparse's usage errors
        status = exc.code
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return status, err


# -- report --finished-only ------------------------------------------------------------------

def finished_run(tmp_path, checksums=True):
    """A campaign folder with one finished run of Fig. 2 at the quick scale, as Campaign
    leaves it: taps.dat through the last tap and DONE.json (with the outputs' sha256 and size,
    or without them, as a TAPMC before checksums wrote it). Returns (spec, run folder)."""
    spec = _runs.constant_eps_run(QUICK, "fbc", QUICK.fig2_eps[0], 1)
    campaign = FakeCampaign(tmp_path / "campaign", [spec])
    taps = spec.taps + 1
    write_constant_eps(campaign, spec, [0.55 + 1e-4 * t for t in range(taps)],
                       [0.56 + 1e-4 * t for t in range(taps)])
    folder = campaign.result(spec.name)
    done = {"run": spec.describe(), "finished": provenance.now(), "wall_s": 1.0,
            "attempts": 1}
    if checksums:
        done["outputs"] = provenance.output_digests(folder, ["taps.dat"])
    provenance.write_done(folder, done)
    return spec, folder


@pytest.fixture
def page(tmp_path):
    """An output folder that already holds a page and a figure CSV (copies of the committed
    ones): what a damaged input must leave as it is."""
    out = tmp_path / "page"
    (out / "validation").mkdir(parents=True)
    for name in ("validation.rst", "validation/fig2.csv", "validation/report.json"):
        shutil.copyfile(DOC / name, out / name)
    return out


def snapshot(folder):
    return {p.relative_to(folder): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


def finished_only(capsys, tmp_path, out):
    return run_cli(capsys, "report", "--quick", "--seeds", 1, "--finished-only", "--campaign",
                   tmp_path / "campaign", "--out", out, "--lmp", sys.executable, "--quiet")


def test_an_intact_finished_run_passes_the_check(tmp_path):
    spec, folder = finished_run(tmp_path)
    assert verify_finished_run(folder, spec)["run"]["name"] == spec.name
    assert len(_runs.taps_table(FakeCampaign(tmp_path / "campaign", [spec]), spec)) == \
        spec.taps + 1


def _change_a_value(folder):
    """taps.dat with one value changed to 0.98, its size kept (only the sha256 tells)."""
    path = folder / "taps.dat"
    lines = path.read_text().splitlines(keepends=True)
    fields = lines[5].split(" ")
    fields[1] = "0.98"   # phi_b, "0.55" in the fake: as many bytes
    lines[5] = " ".join(fields)
    path.write_text("".join(lines))


def _drop_the_last_row(folder):
    path = folder / "taps.dat"
    path.write_text("".join(path.read_text().splitlines(keepends=True)[:-1]))


@pytest.mark.parametrize("damage, what", [
    (_change_a_value, "sha256 differs from the one recorded"),
    (_drop_the_last_row, "bytes, 6321 when the run finished"),
    (lambda folder: (folder / "taps.dat").unlink(), "taps.dat: missing"),
], ids=["value-changed", "row-dropped", "missing"])
def test_finished_only_refuses_an_output_changed_since_the_run_finished(
        capsys, tmp_path, page, damage, what):
    spec, folder = finished_run(tmp_path)
    damage(folder)
    before = snapshot(page)
    with pytest.raises(CampaignError, match=what):
        verify_finished_run(folder, spec)
    status, err = finished_only(capsys, tmp_path, page)
    assert status == 1
    assert str(folder / "taps.dat") in err and what in err and spec.name in err
    assert snapshot(page) == before


def _cut_done(folder):
    path = folder / "DONE.json"
    path.write_bytes(path.read_bytes()[:100])


def _rewrite_done(change):
    def damage(folder):
        done = json.loads((folder / "DONE.json").read_text())
        change(done)
        (folder / "DONE.json").write_text(json.dumps(done))
    return damage


@pytest.mark.parametrize("damage, what", [
    (_cut_done, "cannot be read as the record of a finished run"),
    (_rewrite_done(lambda d: d["outputs"].pop("taps.dat")), "do not list the per-tap file"),
    (_rewrite_done(lambda d: d["run"].update(name="const_fbc_eps0.05_s1")),
     "records the run 'const_fbc_eps0.05_s1'"),
    (_rewrite_done(lambda d: d["outputs"].update({"taps.dat": "abc"})),
     "'outputs' is not an object"),
], ids=["cut-to-100-bytes", "incomplete", "other-run", "bad-outputs"])
def test_finished_only_refuses_a_damaged_done_json(capsys, tmp_path, page, damage, what):
    spec, folder = finished_run(tmp_path)
    damage(folder)
    before = snapshot(page)
    with pytest.raises(CampaignDirectoryError, match=what):
        verify_finished_run(folder, spec)
    status, err = finished_only(capsys, tmp_path, page)
    assert status == 2
    assert str(folder / "DONE.json") in err and what in err
    assert snapshot(page) == before


def _cut_mid_line(folder):
    path = folder / "taps.dat"
    text = path.read_text()
    path.write_text(text[:len(text) // 2])


def _ends_early(folder):
    path = folder / "taps.dat"
    path.write_text("".join(path.read_text().splitlines(keepends=True)[:40]))


def _non_numeric(folder):
    path = folder / "taps.dat"
    lines = path.read_text().splitlines(keepends=True)
    lines[7] = lines[7].replace("0.56", "O.56", 1)
    path.write_text("".join(lines))


@pytest.mark.parametrize("damage, where", [
    (_cut_mid_line, r"taps\.dat:\d+: cut short: the last line has no end-of-line"),
    (_ends_early, r"taps\.dat:40: cut short: ends at step 38, before the last tap 100"),
    (_non_numeric, r"taps\.dat:8: non-numeric field 'O\.56"),
], ids=["cut-mid-line", "ends-early", "non-numeric"])
def test_a_cut_or_malformed_taps_file_is_named_with_its_line(capsys, tmp_path, page, damage,
                                                             where):
    """A run whose DONE.json has no checksums (a TAPMC before them) is trusted as a whole,
    but its per-tap file is still read whole or refused: no IndexError, no figure drawn from
    part of it, no figure left out as if its runs had not finished."""
    spec, folder = finished_run(tmp_path, checksums=False)
    damage(folder)
    before = snapshot(page)
    status, err = finished_only(capsys, tmp_path, page)
    assert status == 2
    assert str(folder) in err
    assert re.search(where, err), err
    assert snapshot(page) == before and not (page / "fig2.csv").exists()


# -- report --from-data ----------------------------------------------------------------------

@pytest.fixture
def committed(tmp_path):
    """A copy of the committed report's data (report.json, the figure CSVs) and its page."""
    out = tmp_path / "doc"
    (out / "validation").mkdir(parents=True)
    for path in list((DOC / "validation").glob("*.csv")) + [DOC / "validation" / "report.json"]:
        shutil.copyfile(path, out / "validation" / path.name)
    shutil.copyfile(DOC / "validation.rst", out / "validation.rst")
    return out


def _summary(change):
    def damage(out):
        path = out / "validation" / "report.json"
        summary = json.loads(path.read_text())
        path.write_text(json.dumps(change(summary)))
    return damage


@pytest.mark.parametrize("damage, what", [
    (lambda out: (out / "validation" / "report.json").write_text("[]"),
     "a JSON list, expected an object"),
    (lambda out: (out / "validation" / "report.json").write_text("{}"),
     "no field 'scale' (a string or null)"),
    (lambda out: (out / "validation" / "report.json").write_text('{"scale": "medium",\n'),
     "report.json:2: not valid JSON"),
    (_summary(lambda s: dict(s, runs="many")), "field 'runs' is 'many', expected an integer"),
    (_summary(lambda s: dict(s, sizes=[[1024]])), "field 'sizes' is [[1024]], expected a list"),
    (_summary(lambda s: dict(s, initial_phi_c="0.58")), "field 'initial_phi_c' is '0.58'"),
    (_summary(lambda s: dict(s, fields={"taps": 3})), "field 'fields' is {'taps': 3}"),
    (_summary(lambda s: dict(s, seeds_per_point=[1, "2"])), "field 'seeds_per_point'"),
    # values of the right type out of their range would print "-5 runs" or a Phi of 5.8
    (_summary(lambda s: dict(s, runs=-5)), "field 'runs' is -5, expected an integer >= 0"),
    (_summary(lambda s: dict(s, taps=[4000, 0])), "field 'taps' is [4000, 0]"),
    (_summary(lambda s: dict(s, eta=[float("inf")])), "field 'eta' is [inf]"),
    (_summary(lambda s: dict(s, eta=[-1e-7])), "expected a list of numbers > 0"),
    (_summary(lambda s: dict(s, sizes=[[0, 16.0]])), "field 'sizes' is [[0, 16.0]]"),
    (_summary(lambda s: dict(s, sizes=[[1024, -16.0]])), "an integer N >= 1 and a length L > 0"),
    (_summary(lambda s: dict(s, initial_phi_c=[5.8, 0.001, 2])), "the mean in [0, 1]"),
    (_summary(lambda s: dict(s, initial_phi_c=[0.58, -0.001, 2])), "field 'initial_phi_c'"),
    (_summary(lambda s: dict(s, seeds_per_point=[3, 2])), "0 <= fewest <= most"),
    (_summary(lambda s: dict(s, ramp_taps_per_level=[0])), "field 'ramp_taps_per_level'"),
    (_summary(lambda s: dict(s, planned_runs=-1)), "field 'planned_runs' is -1"),
], ids=["list", "empty-object", "cut", "runs-text", "sizes-short", "phi-text", "fields",
        "seeds-per-point", "runs-negative", "taps-zero", "eta-inf", "eta-negative", "size-N",
        "size-L", "phi-above-one", "sem-negative", "seeds-order", "ramp-taps-zero",
        "planned-negative"])
def test_from_data_refuses_a_damaged_report_json(capsys, committed, damage, what):
    damage(committed)
    before = snapshot(committed)
    status, err = run_cli(capsys, "report", "--from-data", "--out", committed)
    assert status == 2
    assert str(committed / "validation" / "report.json") in err and what in err
    assert snapshot(committed) == before


def _csv_lines(out):
    return (out / "validation" / "fig2.csv").read_text().splitlines(keepends=True)


def _write_csv(out, lines):
    (out / "validation" / "fig2.csv").write_text("".join(lines))


def _replace_field(index, value):
    def damage(out):
        lines = _csv_lines(out)
        fields = lines[3].rstrip("\r\n").split(",")
        fields[index] = value
        lines[3] = ",".join(fields) + "\r\n"
        _write_csv(out, lines)
    return damage


@pytest.mark.parametrize("damage, what", [
    (lambda out: _write_csv(out, []), "fig2.csv: empty file"),
    (lambda out: _write_csv(out, _csv_lines(out)[:1]), "fig2.csv: no row after the header"),
    (lambda out: (out / "validation" / "fig2.csv").write_text(
        "".join(_csv_lines(out))[:-30]), "cut short: the last line has no end-of-line"),
    (lambda out: _write_csv(out, ["panel,series,x,mean,sem\r\n"] + _csv_lines(out)[1:]),
     "fig2.csv:1: header 'panel,series,x,mean,sem'"),
    (lambda out: _write_csv(out, _csv_lines(out)[:3] + ["a,eps=0.005,3\r\n"]
                            + _csv_lines(out)[4:]), "fig2.csv:4: 3 fields, expected 6"),
    (_replace_field(3, "0.4x"), "fig2.csv:4: mean = '0.4x' is not a number"),
    (_replace_field(3, "inf"), "fig2.csv:4: mean = 'inf' is not a finite number"),
    (_replace_field(4, "nan"), "fig2.csv:4: sem = 'nan' is not a finite number"),
    (_replace_field(5, "2.5"), "fig2.csv:4: n = '2.5' is not an integer"),
], ids=["empty", "header-only", "cut-mid-line", "header", "columns", "mean", "inf", "nan", "n"])
@pytest.mark.parametrize("refit", [False, True], ids=["render", "refit"])
def test_from_data_refuses_a_damaged_figure_csv(capsys, committed, damage, what, refit):
    """Nothing is rendered from part of a CSV, and --refit never rewrites a damaged one
    (an empty or cut fig2.csv once became a header-only file)."""
    damage(committed)
    before = snapshot(committed)
    status, err = run_cli(capsys, "report", "--from-data", *(["--refit"] if refit else []),
                          "--out", committed)
    assert status == 2
    assert str(committed / "validation" / "fig2.csv") in err and what in err
    assert snapshot(committed) == before


def test_from_data_refuses_a_figure_whose_csv_was_lost(capsys, committed):
    """fig9.png without fig9.csv: the CSV was lost (its claims would turn undecided and the
    figure 'not reproduced'); exit 2 naming it, nothing rendered. CSVs alone render."""
    before = snapshot(committed)
    (committed / "validation" / "fig9.png").write_bytes(b"png")
    (committed / "validation" / "fig9.csv").unlink()
    status, err = run_cli(capsys, "report", "--from-data", "--out", committed)
    assert status == 2 and f"{committed / 'validation' / 'fig9.csv'}: missing beside" in err
    assert (committed / "validation.rst").read_bytes() == before[Path("validation.rst")]


def test_refit_without_from_data_is_a_usage_error(capsys, tmp_path):
    status, err = run_cli(capsys, "report", "--refit", "--campaign", tmp_path / "c")
    assert status == 2 and "--refit" in err and "--from-data" in err
    assert not (tmp_path / "c").exists()


def test_a_refit_replaces_a_csv_only_by_a_whole_one(committed, monkeypatch):
    """An empty refit, or a write that fails half-way, leaves the CSV as it was and no
    temporary file beside it; a good refit replaces it by a CSV that reads back whole."""
    csv = committed / "validation" / "fig2.csv"
    before = csv.read_bytes()
    with pytest.raises(ValueError, match="fig2.csv: the refit gives no row; left as it is"):
        validation._replace_csv(P.FigureTable(), csv)
    table = P.FigureTable()
    table.add("a", "eps=0.1", [0, 1], [0.5, 0.6], None, 1)

    def half_write(self, path):
        Path(path).write_text("panel,series,x,mean,sem,n\r\na,eps=0.1,0,0.5")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(P.FigureTable, "write", half_write)
    with pytest.raises(OSError):
        validation._replace_csv(table, csv)
    assert csv.read_bytes() == before
    assert sorted(p.name for p in csv.parent.glob("fig2.csv*")) == ["fig2.csv"]
    monkeypatch.undo()
    validation._replace_csv(table, csv)
    assert list(P.read_table(csv)) == [("a", "eps=0.1")]
