# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Readers of tapmc.readers on real LAMMPS outputs written here by lmp_tapmc (a tiny tapping run
# with two `run` commands and a warning between them), cross-checked against each other and
# against exact stereology recomputed from the dumps; and on broken files (file and line named).
import os
import re
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from lammps_outputs import run_input  # noqa: E402
from tapmc.readers import (TapmcFormatError, read_ave_time, read_dump,  # noqa: E402
                           read_fix_print, read_log)




# Box with a non-zero lower corner in every direction, so that a reader that shifts positions
# to the origin (as MDAnalysis does) is caught.
INPUT = """
units lj
atom_style sphere
boundary p p fm
region box block -2 2 -1.5 2.5 -1 11
create_box 1 box
create_packing 150 1 0.5 4928 floor 0.0
compute phi all stereo/profile floor 0.0
compute vprof all stereo/profile floor 0.0 planes 0.0 8.0 16
compute tprof all stereo/profile axis x window 1.0 5.0 lateral 1.0 floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 maxsweeps 100
fix avs all ave/time 1 1 1 c_phi[1] c_phi[2] c_phi[3] c_tprof[5] c_tprof[6] file scalar.dat
fix avv all ave/time 1 1 2 c_vprof[*] mode vector file vector.dat
fix pr all print 1 "$(step) $(c_phi[1]:%.8f) $(c_phi[3]:%.8f)" file print.dat screen no title "# step phib z"
dump d1 all custom 2 with_type.dump id type x y z radius
dump_modify d1 format float %.10g
dump d2 all custom 2 no_type.dump id x y z diameter
dump_modify d2 format float %.10g
dump d3 all atom 2 atom.dump
dump d4 all custom 2 items.dump id type x y z
dump_modify d4 units yes time yes format float %.10g
thermo_style custom step c_phi[1] c_phi[2] c_phi[3]
thermo_modify format float %.10g
thermo 1
run 3
fix n1 all nve
fix n2 all nve
thermo_style custom step c_phi[1] c_phi[3]
run 2
"""


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    return run_input(tmp_path_factory.mktemp("lammps_outputs"), INPUT, "in.small")


def test_log_runs_warnings_and_concatenation(run_dir):
    log = read_log(run_dir / "log.lammps")
    assert len(log.runs) == 2
    assert [len(r) for r in log.runs] == [4, 3]
    assert log.runs[1].columns == ["Step", "c_phi[1]", "c_phi[3]"]
    assert all(r.complete for r in log.runs)
    assert any("time integrated more than once" in w for w in log.warnings)
    assert any("time integrated more than once" in w for w in log.runs[1].warnings) is False
    th = log.thermo
    np.testing.assert_array_equal(th["Step"], np.arange(6))
    # the run-boundary row keeps run 1's values, a column absent from run 2 is NaN after it
    assert th["c_phi[2]"][3] == log.runs[0]["c_phi[2]"][3]
    assert np.isnan(th["c_phi[2]"][4:]).all()


def _log_of_runs(*runs):
    """A log text of one-line thermo runs, each given as its list of (step, value) rows."""
    text = "LAMMPS (29 Sep 2021)\n"
    for rows in runs:
        text += "Per MPI rank memory allocation (min/avg/max) = 3.5 | 3.5 | 3.5 Mbytes\n"
        text += "Step Phi\n" + "".join(f"{s} {v}\n" for s, v in rows)
        text += "Loop time of 0.1 on 1 procs for 10 steps with 10 atoms\n\n"
    return text


def test_log_of_a_resumed_run_appended_names_the_repeated_steps(tmp_path):
    """A run resumed from its restart at step 30 with 'log log.run append' prints steps 30 and
    40 again: Log.thermo counted them twice without a word (steps 0 ... 40 30 40 50 60). It
    raises naming the run and the steps; join(repeats='last') keeps the later run's rows."""
    first = [(0, 0.55), (10, 0.56), (20, 0.57), (30, 0.58), (40, 0.59)]
    again = [(30, 0.58), (40, 0.595), (50, 0.6), (60, 0.61)]
    log = read_log(_write(tmp_path, "log.run", _log_of_runs(first, again)))
    with pytest.raises(TapmcFormatError, match="run 2 starts at step 30, after step 40"):
        log.thermo
    last = log.join(repeats="last")
    np.testing.assert_array_equal(last["Step"], [0, 10, 20, 30, 40, 50, 60])
    np.testing.assert_array_equal(last["Phi"], [0.55, 0.56, 0.57, 0.58, 0.595, 0.6, 0.61])
    assert len(log.join(repeats="all")) == 9
    # consecutive runs (the boundary step printed twice) are merged as before
    consecutive = read_log(_write(tmp_path, "log.two", _log_of_runs(
        first, [(40, 0.5900001), (50, 0.6), (60, 0.61)])))   # the same step 40, other format
    np.testing.assert_array_equal(consecutive.thermo["Step"], [0, 10, 20, 30, 40, 50, 60])
    with pytest.raises(ValueError, match="repeats = 'first'"):
        log.join(repeats="first")
    # a boundary step printed with other values (atoms deleted between the runs): the earlier
    # run's row is kept, with a warning naming the columns
    changed = read_log(_write(tmp_path, "log.changed",
                              _log_of_runs(first, [(40, 0.5), (50, 0.6)])))
    with pytest.warns(UserWarning, match="step 40 ends run 1 and starts run 2 with other "
                                         "values of Phi"):
        np.testing.assert_array_equal(changed.thermo["Phi"][-2:], [0.59, 0.6])


def test_log_keeps_the_table_of_a_run_with_pre_no(tmp_path):
    """'run N pre no' prints no memory line (LAMMPS sets nothing up): its table was left out,
    steps missing from Log.thermo without a word. Its header follows the run's echo; a 'Loop
    time' whose table cannot be found (echo none) raises."""
    text = _log_of_runs([(0, 0.55), (10, 0.56)]) + (
        "run             10 pre no post no\nStep Phi\n10 0.56\n15 0.565\n20 0.57\n"
        "Loop time of 0.05 on 1 procs for 10 steps with 300 atoms\n")
    log = read_log(_write(tmp_path, "log.preno", text))
    assert len(log.runs) == 2
    np.testing.assert_array_equal(log.thermo["Step"], [0, 10, 15, 20])
    hidden = text.replace("run             10 pre no post no\n", "")
    _expect(_write(tmp_path, "log.hidden", hidden), 12, read_log)  # its Loop time line


def test_ave_time_scalar_and_print_agree_with_log(run_dir):
    th = read_log(run_dir / "log.lammps").thermo
    av = read_ave_time(run_dir / "scalar.dat")
    assert not av.vector
    assert av.columns[0] == "TimeStep"
    np.testing.assert_array_equal(av.steps, np.arange(6))
    np.testing.assert_allclose(av["c_phi[3]"], th["c_phi[3]"], rtol=1e-5)
    pr = read_fix_print(run_dir / "print.dat")
    assert pr.columns == ["step", "phib", "z"]
    np.testing.assert_array_equal(pr["step"], np.arange(6))  # boundary duplicate dropped
    np.testing.assert_allclose(pr["phib"], th["c_phi[1]"], rtol=1e-7)
    # lateral and central means of the transversal profile are packing fractions
    assert np.all((av["c_tprof[5]"] > 0.3) & (av["c_tprof[5]"] < 0.75))


def _slab_fraction(z, r, z0, z1, area):
    """Exact volume of spheres inside z0 <= z <= z1 over the slab volume."""
    a = np.clip(z0 - z, -r, r)
    b = np.clip(z1 - z, -r, r)
    vol = np.pi * ((b - a) * r ** 2 - (b ** 3 - a ** 3) / 3.0)
    return vol.sum() / (area * (z1 - z0))


def test_ave_time_vector_matches_stereology_of_dump(run_dir):
    vec = read_ave_time(run_dir / "vector.dat")
    assert vec.vector
    assert vec.blocks.shape == (3, 16, 3)
    np.testing.assert_array_equal(vec.steps, [0, 2, 4])
    np.testing.assert_allclose(vec["c_vprof[1]"][0], 0.25 + 0.5 * np.arange(16))
    dump = read_dump(run_dir / "with_type.dump")
    for frame, bins in zip(dump.frames, vec["c_vprof[3]"]):
        z, r = frame.positions[:, 2], frame.radii
        area = np.prod(frame.box_hi[:2] - frame.box_lo[:2])
        expected = [_slab_fraction(z, r, k * 0.5, (k + 1) * 0.5, area) for k in range(16)]
        np.testing.assert_allclose(bins, expected, atol=2e-6)


def test_dumps_agree_across_formats_and_backends(run_dir):
    ref = read_dump(run_dir / "with_type.dump")
    th = read_log(run_dir / "log.lammps").thermo
    assert list(ref.steps) == [0, 2, 4]
    for frame in ref.frames:
        np.testing.assert_array_equal(frame.box_lo, [-2, -1.5, -1])
        np.testing.assert_array_equal(frame.periodic, [True, True, False])
        np.testing.assert_array_equal(frame.ids, np.arange(1, 151))
        assert frame.types is not None and np.all(frame.types == 1)
        np.testing.assert_array_equal(frame.radii, 0.5)
        # positions in the dump's own frame: x within the box, <Z> equals compute's
        assert frame.positions[:, 0].min() >= -2 and frame.positions[:, 0].max() <= 2
        z_mean = th["c_phi[3]"][list(th["Step"]).index(frame.step)]
        assert frame.positions[:, 2].mean() == pytest.approx(z_mean, rel=1e-8)
    import gzip
    with open(run_dir / "with_type.dump", "rb") as src, \
            gzip.open(run_dir / "compressed.dump.gz", "wb") as dst:
        dst.write(src.read())
    others = {
        "gzip native": read_dump(run_dir / "compressed.dump.gz"),
        "no_type native": read_dump(run_dir / "no_type.dump"),
        "no_type mda": read_dump(run_dir / "no_type.dump", backend="mdanalysis"),
        "with_type mda": read_dump(run_dir / "with_type.dump", backend="mdanalysis"),
        "atom native": read_dump(run_dir / "atom.dump", radius=0.5),
        "atom mda": read_dump(run_dir / "atom.dump", backend="mdanalysis"),
        # UNITS and TIME items: eleven header lines, which MDAnalysis alone cannot read
        "items native": read_dump(run_dir / "items.dump"),
        "items mda": read_dump(run_dir / "items.dump", backend="mdanalysis"),
    }
    for name, dump in others.items():
        assert len(dump) == 3, name
        for a, b in zip(ref.frames, dump.frames):
            assert a.step == b.step
            np.testing.assert_array_equal(a.ids, b.ids)
            # float32 in MDAnalysis, 6 digits in dump atom's scaled coordinates
            np.testing.assert_allclose(b.positions, a.positions, atol=2e-5 * 12, err_msg=name)
    assert others["no_type native"].frames[0].types is None
    np.testing.assert_array_equal(others["no_type native"].frames[0].radii, 0.5)
    assert others["atom mda"].frames[0].radii is None
    # without an id column: both parsers number the atoms 1 to N (MDAnalysis ended in KeyError)
    (run_dir / "no_id.dump").write_text(re.sub(r"ITEM: ATOMS id ", "ITEM: ATOMS ",
                                               re.sub(r"(?m)^\d+ (?=\d+ \S+ \S+ \S+)", "",
                                                      (run_dir / "with_type.dump").read_text())))
    for dump in (read_dump(run_dir / "no_id.dump"),
                 read_dump(run_dir / "no_id.dump", backend="mdanalysis")):
        assert len(dump) == 3
        np.testing.assert_array_equal(dump.frames[1].ids, np.arange(1, 151))
    assert read_dump(run_dir / "no_id.dump").universe().atoms.n_atoms == 150
    universe = others["no_type native"].universe()
    assert universe.atoms.n_atoms == 150 and len(universe.trajectory) == 3


# ---------------------------------------------------------------- broken files

def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def _expect(path, line, func, *args, **kw):
    with pytest.raises(TapmcFormatError) as info:
        obj = func(path, *args, **kw)
        if hasattr(obj, "frames"):
            obj.frames
    assert info.value.path == str(path)
    assert info.value.line == line
    assert str(info.value).startswith(f"{path}:{line}:" if line else f"{path}:")
    return info.value


DUMP_OK = """ITEM: TIMESTEP
0
ITEM: NUMBER OF ATOMS
2
ITEM: BOX BOUNDS pp pp fm
0 4
0 4
0 10
ITEM: ATOMS id x y z
1 0.5 0.5 0.5
2 1.5 0.5 0.5
"""


def test_broken_dumps(tmp_path):
    ok = read_dump(_write(tmp_path, "ok.dump", DUMP_OK))
    assert repr(ok) == f"<Dump {str(tmp_path / 'ok.dump')!r} (native): not read yet>"
    assert len(ok) == 1 and repr(ok).endswith("(native): 1 frames>")
    _expect(_write(tmp_path, "trunc.dump", DUMP_OK.rsplit("\n", 2)[0] + "\n"), 11, read_dump)
    _expect(_write(tmp_path, "nan.dump", DUMP_OK.replace("1.5 0.5 0.5", "1.5 x12 0.5")),
            11, read_dump)
    e = _expect(_write(tmp_path, "short.dump", DUMP_OK.replace("2 1.5 0.5 0.5", "2 1.5")),
                11, read_dump)
    assert "expected 4 fields" in str(e)
    # a long line and a short one make up the frame's total of fields: still the long line
    shifted = DUMP_OK.replace("1 0.5 0.5 0.5", "1 0.5 0.5 0.5 9.0").replace("2 1.5 0.5 0.5",
                                                                           "2 1.5 0.5")
    e = _expect(_write(tmp_path, "shifted.dump", shifted), 10, read_dump)
    assert "expected 4 fields (id x y z), found 5" in str(e)
    _expect(_write(tmp_path, "count.dump", DUMP_OK.replace("\n2\n", "\ntwo\n")), 4, read_dump)
    _expect(_write(tmp_path, "item.dump", DUMP_OK.replace("ITEM: BOX", "ITEM: BLOB")), 5,
            read_dump)
    _expect(_write(tmp_path, "nocoord.dump", DUMP_OK.replace("id x y z", "id a b c")), 9,
            read_dump)
    _expect(_write(tmp_path, "dup.dump", DUMP_OK.replace("\n2 1.5", "\n1 1.5")), 9, read_dump)
    _expect(_write(tmp_path, "garbage.dump", DUMP_OK + "hello\n"), 12, read_dump)
    # frames of different atom counts: the native parser reads them, MDAnalysis cannot
    fewer = DUMP_OK.replace("\n0\n", "\n5\n").replace("\n2\n", "\n1\n").rsplit("\n", 2)[0]
    grown = _write(tmp_path, "grown.dump", DUMP_OK + fewer + "\n")
    assert [f.n_atoms for f in read_dump(grown).frames] == [2, 1]
    e = _expect(grown, None, lambda p: read_dump(p, backend="mdanalysis").frames)
    assert "frames of 1 to 2 atoms (the first change at step 5)" in str(e)
    # Dump.universe() says the same (it ended in MDAnalysis's own ValueError)
    e = _expect(grown, None, lambda p: read_dump(p).universe())
    assert "frames of 1 to 2 atoms (the first change at step 5)" in str(e)
    for radius in (float("inf"), 0.0, float("nan")):
        with pytest.raises(ValueError, match="radius = .* must be finite and > 0"):
            read_dump(tmp_path / "ok.dump", radius=radius)
    # a folder, or a missing file, named as the path was given (not as a PosixPath repr)
    with pytest.raises(IsADirectoryError, match=f"dump file '{tmp_path}' is a directory"):
        read_dump(tmp_path)
    with pytest.raises(FileNotFoundError, match="dump file '.*no.dump' does not exist"):
        read_dump(tmp_path / "no.dump")


def test_dump_columns_the_reader_does_not_use_may_hold_text_or_nan(tmp_path):
    """``dump custom ... element`` and a per-atom variable that is NaN on some atoms: the frame
    is read, those columns kept as written (text as strings), in the order of the ids; a
    column the frame is made of (coordinates, radius, id, type) must still be a finite number,
    and its error names the column and the line."""
    extra = DUMP_OK.replace("id x y z", "element id x y z radius v_q").replace(
        "1 0.5 0.5 0.5", "Si 1 0.5 0.5 0.5 0.5 nan").replace("2 1.5 0.5 0.5",
                                                             "O 2 1.5 0.5 0.5 0.5 2.5")
    # unsorted ids: the text column follows its atom
    path = _write(tmp_path, "extra.dump", extra.replace(
        "Si 1 0.5 0.5 0.5 0.5 nan\nO 2 1.5 0.5 0.5 0.5 2.5",
        "O 2 1.5 0.5 0.5 0.5 2.5\nSi 1 0.5 0.5 0.5 0.5 nan"))
    frame = read_dump(path).frames[0]
    np.testing.assert_array_equal(frame.ids, [1, 2])
    np.testing.assert_array_equal(frame.positions, [[0.5, 0.5, 0.5], [1.5, 0.5, 0.5]])
    np.testing.assert_array_equal(frame.radii, [0.5, 0.5])
    assert list(frame.fields["element"]) == ["Si", "O"]
    np.testing.assert_array_equal(frame.fields["v_q"], [np.nan, 2.5])
    for bad, column in (("1.5 0.5 x", "z 'x'"), ("1.5 nan 0.5", "y 'nan'")):
        e = _expect(_write(tmp_path, "bad.dump", extra.replace("1.5 0.5 0.5", bad)), 11,
                    read_dump)
        assert column in str(e), str(e)
    e = _expect(_write(tmp_path, "badr.dump", extra.replace("0.5 2.5", "inf 2.5")), 11,
                read_dump)
    assert "radius 'inf' is not finite" in str(e)
    # the digits the coordinates were written with: the most over the column, at least %g's 6
    assert frame.digits == 6
    long = _write(tmp_path, "long.dump", extra.replace("1.5 0.5 0.5 0.5 2.5",
                                                       "1.500000000001 0.5 0.5 0.5 2.5"))
    assert read_dump(long).frames[0].digits == 13


def test_broken_log_ave_time_print(tmp_path):
    log = ("LAMMPS (29 Sep 2021)\nPer MPI rank memory allocation (min/avg/max) = 1 | 1 | 1\n"
           "Step Temp\n0 1.0\n1 abc\nLoop time of 0.1 on 1 procs\n")
    _expect(_write(tmp_path, "bad.log", log), 5, read_log)
    _expect(_write(tmp_path, "short.log", log.replace("1 abc", "1 2 3")), 5, read_log)
    _expect(_write(tmp_path, "empty.log", "LAMMPS (29 Sep 2021)\n"), None, read_log)
    printed = log.replace("1 abc\n", "tap 1 done\n1 2.0\n7 0.5 0.25\n")
    _expect(_write(tmp_path, "printed.log", printed), 5, read_log)
    lenient = read_log(tmp_path / "printed.log", strict=False)
    assert lenient.skipped == [(5, "tap 1 done"), (7, "7 0.5 0.25")]
    np.testing.assert_array_equal(lenient.thermo.data, [[0, 1.0], [1, 2.0]])
    _expect(_write(tmp_path, "bad2.log", printed.replace("1 2.0", "1 two")), 6, read_log,
            strict=False)
    multi = log.replace("Step Temp", "---------------- Step        0 ----- CPU = 0 (sec)")
    _expect(_write(tmp_path, "multi.log", multi), 3, read_log)
    killed = read_log(_write(tmp_path, "killed.log", log.replace("1 abc\nLoop time of 0.1 on "
                                                                "1 procs\n", "1 2.0\n")))
    assert not killed.runs[0].complete and len(killed.thermo) == 2
    vec = ("# Time-averaged data for fix v\n# TimeStep Number-of-rows\n# Row c_p[1] c_p[2]\n"
           "0 2\n1 0.25 0.5\n2 0.75 0.6\n10 2\n1 0.25 0.5\n")
    _expect(_write(tmp_path, "trunc.vec", vec), 7, read_ave_time)
    # a run killed inside its second block: killed=True reads the complete first block
    killed_vec = read_ave_time(tmp_path / "trunc.vec", killed=True)
    assert list(killed_vec.steps) == [0] and killed_vec.blocks.shape == (1, 2, 2)
    e = _expect(_write(tmp_path, "none.vec", vec.split("0 2\n")[0] + "0 2\n1 0.25 0.5\n"),
                None, read_ave_time, killed=True)
    assert "no complete data block" in str(e)
    _expect(_write(tmp_path, "bad.vec", vec.replace("2 0.75 0.6", "2 0.75 nope") + "2 1 1\n"),
            6, read_ave_time)
    _expect(_write(tmp_path, "rows.vec", vec.replace("10 2\n", "10 3\n") + "2 1 1\n3 1 1\n"),
            7, read_ave_time)
    _expect(_write(tmp_path, "bad.sca", "# t\n# TimeStep a b\n0 1 2\n1 2\n"), 4, read_ave_time)
    _expect(_write(tmp_path, "nohead.sca", "0 1 2\n"), 1, read_ave_time)
    _expect(_write(tmp_path, "bad.print", "# s a\n0 1\n1 1e-3x\n"), 3, read_fix_print)
    _expect(_write(tmp_path, "width.print", "0 1\n1 2 3\n"), 2, read_fix_print)


RESUMED_FIRST = """
units lj
atom_style sphere
boundary p p fm
region box block 0 4 0 4 0 12
create_box 1 box
create_packing 100 1 0.5 4928 floor 0.0
compute phi all stereo/profile floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 maxsweeps 100
fix pr all print 1 "$(step) $(c_phi[1]:%.8f) $(c_phi[3]:%.8f)" file print.dat screen no title "# step phib z"
restart 2 restart.*
run 4
"""

# the same run resumed from its restart at step 2, appending to the same file (as a job killed
# after step 4 and started again from its latest kept restart would)
RESUMED_AGAIN = RESUMED_FIRST.split("create_box")[0].replace(
    "region box block 0 4 0 4 0 12\n", "read_restart restart.2\n") + """
compute phi all stereo/profile floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 maxsweeps 100
fix pr all print 1 "$(step) $(c_phi[1]:%.8f) $(c_phi[3]:%.8f)" append print.dat screen no
run 3
"""


def test_fix_print_of_a_resumed_run_names_the_repeated_step(tmp_path):
    """A run resumed from its restart at step 2 with fix print ... append prints steps 2 to 4
    again: read by default, the repeat is an error at its line (counting those taps twice is
    silently wrong); repeats='last' keeps the continued run's print of each step, 'all' every
    row. The continued run restarts from the exact state: its step 2 is the first run's."""
    run_input(tmp_path, RESUMED_FIRST, "in.first")
    first = read_fix_print(tmp_path / "print.dat")
    np.testing.assert_array_equal(first["step"], np.arange(5))
    assert first.superseded == 0
    run_input(tmp_path, RESUMED_AGAIN, "in.again")
    # line 7: LAMMPS's own title of the appended run, no column names; line 8: step 2 again
    err = _expect(tmp_path / "print.dat", 8, read_fix_print)
    assert "step 2 printed after step 4" in str(err) and "repeats='last'" in str(err)
    last = read_fix_print(tmp_path / "print.dat", repeats="last")
    np.testing.assert_array_equal(last["step"], np.arange(6))
    assert last.superseded == 3
    np.testing.assert_array_equal(last.data[:3], first.data[:3])
    every = read_fix_print(tmp_path / "print.dat", repeats="all")
    np.testing.assert_array_equal(every["step"], [0, 1, 2, 3, 4, 2, 3, 4, 5])
    np.testing.assert_array_equal(every.data[5:], last.data[2:])
    with pytest.raises(ValueError, match="repeats = 'first'; allowed: 'error', 'last', 'all'"):
        read_fix_print(tmp_path / "print.dat", repeats="first")


def test_fix_print_without_a_step_column_keeps_every_tap(tmp_path):
    """An unchanged tap printed with 4 digits is a real row: it was dropped as a repeat (194
    of 201 taps read, row k no longer tap k). Without a step column every row is kept, with a
    warning naming how many equal the row before; a title after the data (a fix defined again,
    e.g. a resumed run appending) cannot be sorted out without steps and stops there."""
    text = "# phib phic\n0.5912 0.6015\n0.5912 0.6015\n0.5913 0.6015\n0.5913 0.6015\n"
    with pytest.warns(UserWarning, match="2 row\\(s\\) equal to the row before, kept"):
        table = read_fix_print(_write(tmp_path, "four.print", text))
    assert len(table) == 4 and table.columns == ["phib", "phic"]
    resumed = text + "# phib phic\n0.5912 0.6015\n"
    err = _expect(_write(tmp_path, "resumed.print", resumed), 6, read_fix_print)
    assert "a '#' line after the data" in str(err) and "print a step column" in str(err)
    with pytest.warns(UserWarning):
        assert len(read_fix_print(tmp_path / "resumed.print", repeats="all")) == 5


@pytest.mark.parametrize("name", ["tap", "Timestep", "step"])
def test_fix_print_step_column_by_any_of_its_names(tmp_path, name):
    """The quick start and the tutorial name their step column 'tap': a resumed run's
    repeated taps were counted twice without a word. 'tap' and 'timestep' count as 'step'."""
    text = f"# {name} phib\n0 0.5\n1 0.51\n2 0.52\n2 0.52\n# {name} phib\n1 0.515\n2 0.525\n"
    err = _expect(_write(tmp_path, "taps.dat", text), 7, read_fix_print)
    assert "step 1 printed after step 2" in str(err)
    last = read_fix_print(tmp_path / "taps.dat", repeats="last")
    np.testing.assert_array_equal(last[name], [0, 1, 2])
    np.testing.assert_array_equal(last["phib"], [0.5, 0.515, 0.525])


def test_fix_print_without_a_title_or_a_step_column(tmp_path):
    """LAMMPS's own title ("# Fix print output for fix ID", six words) names no column, even
    over six fields; without a column named step, steps are not checked."""
    six = "# Fix print output for fix pr\n1 2 3 4 5 6\n2 2 3 4 5 7\n1 0 0 0 0 0\n"
    table = read_fix_print(_write(tmp_path, "six.print", six))
    assert table.columns == [f"c{j}" for j in range(1, 7)] and len(table) == 3
    named = read_fix_print(tmp_path / "six.print", columns=["Step", "a", "b", "c", "d", "e"],
                           repeats="last")
    np.testing.assert_array_equal(named["Step"], [1])
    assert named.superseded == 2
