# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Fuzz test of tapmc.readers (read_log, read_ave_time, read_fix_print, read_dump): real files cut
# at many offsets, random bytes, mutated files, empty and binary files, a wrong column count. The
# only outcomes allowed are the documented ones: a valid parse (for a cut, exactly the complete
# rows or frames before it) or TapmcFormatError whose message names the file and, where it has
# one, a line of the file. Any other exception fails the test. Seeded, deterministic, a few s.
#
# The real files: the reference logs of examples/, the pore tool's test dump, and the outputs of
# a tiny run of lmp_tapmc written here (fix ave/time in both modes, fix print, dumps, a log of
# two runs).
import gzip
import os
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

SEED = 20260520
READERS = {"log": read_log, "ave_time": read_ave_time, "fix_print": read_fix_print,
           "dump": read_dump}
LOGS = sorted(SOURCE.glob("examples/*/log.*"))
PORE_DUMP = SOURCE / "tests" / "pores" / "data" / "small_tapped.dump.gz"
SEED_DUMPS = sorted((SOURCE / "tests" / "pores" / "fuzz" / "seeds").glob("*.dump"))
PNG = SOURCE / "doc" / "validation" / "fig2.png"

# Two runs (the second prints other columns), every file the readers read, 60 spheres.
INPUT = """
units lj
atom_style sphere
boundary p p fm
region box block 0 4 0 4 0 12
create_box 1 box
create_packing 60 1 0.5 4928 floor 0.0
compute phi all stereo/profile floor 0.0
compute vprof all stereo/profile floor 0.0 planes 0.0 4.0 4
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 maxsweeps 50
fix avs all ave/time 1 1 1 c_phi[1] c_phi[2] c_phi[3] file scalar.dat
fix avv all ave/time 1 1 1 c_vprof[*] mode vector file vector.dat
fix pr all print 1 "$(step) $(c_phi[1]:%.8f) $(c_phi[3]:%.8f)" file print.dat screen no title "# step phib z"
dump d1 all custom 1 custom.dump id type x y z radius
dump_modify d1 format float %.10g
dump d2 all atom 2 atom.dump
thermo_style custom step c_phi[1] c_phi[2] c_phi[3]
thermo 1
run 3
thermo_style custom step c_phi[1] c_phi[3]
run 2
"""




@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    return run_input(tmp_path_factory.mktemp("tiny_run"), INPUT, "in.tiny")


def parse(reader, path):
    """The reader's result, with a dump's frames read (a Dump parses lazily)."""
    result = READERS[reader](path)
    if reader == "dump":
        result.frames
    return result


def assert_names_file(err, path, n_lines=None):
    """The error names the file and, when it has a line, one that exists (or the one after the
    last, where the file ends too early)."""
    assert err.path == str(path)
    where = f"{path}:{err.line}:" if err.line is not None else f"{path}:"
    assert str(err).startswith(where), str(err)
    if err.line is not None:
        assert isinstance(err.line, (int, np.integer)) and err.line >= 1, str(err)
        if n_lines is not None:
            assert err.line <= n_lines + 1, str(err)


def expect_error(reader, path, line="any", n_lines=None):
    with pytest.raises(TapmcFormatError) as info:
        parse(reader, path)
    assert_names_file(info.value, path, n_lines)
    if line != "any":
        assert info.value.line == line, str(info.value)
    return info.value


def documented_outcome(reader, path, case):
    """Parse or TapmcFormatError naming the file; anything else fails, naming the case."""
    data = path.read_bytes()
    try:
        return parse(reader, path)
    except TapmcFormatError as err:
        # a gzip file's lines are those of its content, unknown when it is damaged
        assert_names_file(err, path, None if data[:2] == b"\x1f\x8b" else data.count(b"\n") + 1)
        return err
    except Exception as err:  # noqa: BLE001 - the point of the test
        pytest.fail(f"{reader} on {case}: {type(err).__name__}: {err}")


def cut_offsets(data, rng, n_random):
    """Offsets at which to cut `data`: 0, every line boundary (sampled when there are many),
    a few bytes before some of them (a line cut short) and random ones."""
    ends = [i + 1 for i, b in enumerate(data) if b == 0x0A]
    if len(ends) > 80:
        ends = sorted(rng.choice(ends, 80, replace=False).tolist())
    offsets = {0, len(data)} | set(ends)
    offsets |= {max(0, e - int(rng.integers(1, 6))) for e in ends[::3]}
    offsets |= set(rng.integers(0, len(data) + 1, n_random).tolist())
    return sorted(offsets)


def complete_lines(data, offset):
    """Number of complete lines in data[:offset], and whether a non-blank piece follows them."""
    head = data[:offset]
    return head.count(b"\n"), head.rsplit(b"\n", 1)[-1].strip() != b""


# ---- the expected result of a cut, from the layout of the uncut file --------------------------

def log_layout(lines):
    """Per run of a LAMMPS log: (header line index, row line indices, 'Loop time' index or None).
    The header follows the memory line; rows are the numeric lines before 'Loop time'."""
    runs = []
    i = 0
    while i < len(lines):
        if lines[i].lstrip().startswith(("Per MPI rank memory", "Memory usage per processor")):
            header, rows, loop = i + 1, [], None
            i += 2
            while i < len(lines) and not lines[i].startswith(("Loop time", "ERROR")):
                fields = lines[i].split()
                if fields and fields[0].replace(".", "", 1).lstrip("-").isdigit():
                    rows.append(i)
                i += 1
            if i < len(lines) and lines[i].startswith("Loop time"):
                loop = i
            runs.append((header, rows, loop))
        i += 1
    return runs


def check_log_cut(full, layout, path, data, offset):
    n, _ = complete_lines(data, offset)
    runs = [(h, [r for r in rows if r < n], loop is not None and loop < n)
            for h, rows, loop in layout if h < n]
    if not runs:
        expect_error("log", path, line=None)
        return
    log = parse("log", path)
    assert len(log.runs) == len(runs), offset
    for got, ref, (_, rows, complete) in zip(log.runs, full.runs, runs):
        assert got.columns == ref.columns
        np.testing.assert_array_equal(got.data, ref.data[:len(rows)], err_msg=str(offset))
        assert got.complete == complete, offset


def check_ave_time_cut(full, path, data, offset, vector):
    n, _ = complete_lines(data, offset)
    header = 3 if vector else 2
    if offset == 0:
        expect_error("ave_time", path, line=None)
    elif n < header:
        expect_error("ave_time", path, line=n + 1)
    elif not vector:
        table = parse("ave_time", path)
        assert table.columns == full.columns
        np.testing.assert_array_equal(table.data, full.data[:n - header], err_msg=str(offset))
    else:
        block = full.blocks.shape[1] + 1
        done, rest = divmod(n - header, block)
        if rest:  # the cut falls inside a block: named at the block's first line
            expect_error("ave_time", path, line=header + done * block + 1)
        elif done == 0:
            expect_error("ave_time", path, line=None)
        else:
            table = parse("ave_time", path)
            np.testing.assert_array_equal(table.blocks, full.blocks[:done], err_msg=str(offset))
            np.testing.assert_array_equal(table.steps, full.steps[:done])


def check_fix_print_cut(full, lines, path, data, offset):
    n, _ = complete_lines(data, offset)
    rows = [t for t in lines[:n] if t.strip() and not t.startswith("#")]
    distinct = sum(1 for j, t in enumerate(rows) if j == 0 or t != rows[j - 1])
    if distinct == 0:
        expect_error("fix_print", path, line=None)
        return
    table = parse("fix_print", path)
    assert table.columns == full.columns
    np.testing.assert_array_equal(table.data, full.data[:distinct], err_msg=str(offset))


def check_dump_cut(full, lines, path, data, offset):
    n, partial = complete_lines(data, offset)
    starts = [i for i, t in enumerate(lines) if t.startswith("ITEM: TIMESTEP")]
    ends = starts[1:] + [data.count(b"\n")]
    if offset == 0:
        expect_error("dump", path, line=None)
    elif partial or n not in ends:  # inside a frame: the line after the last complete one
        err = expect_error("dump", path, line=n + 1)
        assert "end" in str(err), str(err)
    else:
        dump = parse("dump", path)
        done = ends.index(n) + 1
        assert [f.step for f in dump.frames] == [f.step for f in full.frames[:done]]
        for got, ref in zip(dump.frames, full.frames):
            np.testing.assert_array_equal(got.positions, ref.positions)
            np.testing.assert_array_equal(got.ids, ref.ids)


# ---- the real files ---------------------------------------------------------------------------

def real_files(run_dir):
    """(reader, path of an uncut valid file, kind) for every real file."""
    files = [("log", p, "log") for p in LOGS] + [("log", run_dir / "log.lammps", "log")]
    files += [("ave_time", run_dir / "scalar.dat", "scalar"),
              ("ave_time", run_dir / "vector.dat", "vector"),
              ("fix_print", run_dir / "print.dat", "print"),
              ("dump", run_dir / "custom.dump", "dump"), ("dump", run_dir / "atom.dump", "dump")]
    pore_dump = run_dir / "small_tapped.dump"
    pore_dump.write_bytes(gzip.decompress(PORE_DUMP.read_bytes()))
    files.append(("dump", pore_dump, "dump"))
    files += [("dump", p, "dump") for p in SEED_DUMPS]
    return files


def test_the_real_files_are_what_the_cuts_assume(run_dir):
    """The oracles below rely on these shapes: a fuzz over files that never parse proves nothing."""
    assert len(LOGS) >= 5 and len(SEED_DUMPS) >= 2
    log = read_log(run_dir / "log.lammps")
    assert [len(r) for r in log.runs] == [4, 3] and all(r.complete for r in log.runs)
    assert len(read_ave_time(run_dir / "scalar.dat")) == 6
    vec = read_ave_time(run_dir / "vector.dat")
    assert vec.vector and vec.blocks.shape[:2] == (6, 4)
    assert len(read_fix_print(run_dir / "print.dat")) == 6  # step 3 printed twice, kept once
    assert len(read_dump(run_dir / "custom.dump")) == 6
    assert len(read_dump(run_dir / "atom.dump")) == 3


def test_cuts_of_real_files_keep_the_complete_rows_or_name_the_file(run_dir, tmp_path):
    rng = np.random.default_rng(SEED)
    checked = 0
    for reader, source, kind in real_files(run_dir):
        data = source.read_bytes()
        lines = data.decode().split("\n")
        full = None
        try:
            full = parse(reader, source)
        except TapmcFormatError:  # examples/deposition's log has no run: every cut must fail
            assert reader == "log"
        layout = log_layout(lines) if reader == "log" else None
        cut = tmp_path / f"cut_{source.name}"
        for offset in cut_offsets(data, rng, 30):
            cut.write_bytes(data[:offset])
            if reader == "log":
                check_log_cut(full, layout, cut, data, offset)
            elif reader == "ave_time":
                check_ave_time_cut(full, cut, data, offset, kind == "vector")
            elif reader == "fix_print":
                check_fix_print_cut(full, lines, cut, data, offset)
            else:
                check_dump_cut(full, lines, cut, data, offset)
            checked += 1
    assert checked > 1500


def test_a_killed_log_keeps_the_rows_before_a_line_cut_short(tmp_path):
    """The issue's case: killed in the middle of a row, even one whose cut still parses."""
    log = ("LAMMPS (29 Sep 2021)\nPer MPI rank memory allocation (min/avg/max) = 1 | 1 | 1\n"
           "Step Phi\n0 0.55\n1 0.5612345\n")
    for tail in ("2 0.56", "2 0.", "2", "Loop ti"):
        path = tmp_path / "killed.log"
        path.write_text(log + tail)
        killed = read_log(path)
        assert not killed.runs[0].complete
        np.testing.assert_array_equal(killed.thermo["Phi"], [0.55, 0.5612345])


def test_gzip_cut_or_damaged_names_the_file(run_dir, tmp_path):
    rng = np.random.default_rng(SEED + 1)
    cases = [("dump", PORE_DUMP.read_bytes()),
             ("log", gzip.compress((run_dir / "log.lammps").read_bytes())),
             ("ave_time", gzip.compress((run_dir / "vector.dat").read_bytes())),
             ("fix_print", gzip.compress((run_dir / "print.dat").read_bytes()))]
    for reader, data in cases:
        path = tmp_path / f"cut.{reader}.gz"
        path.write_bytes(data)
        parse(reader, path)  # the uncut gzip file reads
        for offset in sorted(set(rng.integers(2, len(data), 25).tolist())):
            path.write_bytes(data[:offset])  # the stream ends before its end marker
            expect_error(reader, path)
        for _ in range(10):
            damaged = bytearray(data)
            at = int(rng.integers(10, len(data) - 8))
            damaged[at] ^= 0xFF
            path.write_bytes(bytes(damaged))
            documented_outcome(reader, path, f"gzip with byte {at} flipped")


def test_empty_blank_and_binary_files(tmp_path):
    rng = np.random.default_rng(SEED + 2)
    for reader in READERS:
        for name, data in (("empty", b""), ("empty.gz", gzip.compress(b""))):
            path = tmp_path / f"{name}.{reader}"
            path.write_bytes(data)
            err = expect_error(reader, path, line=None)
            assert "empty file" in str(err), str(err)
        blank = tmp_path / f"blank.{reader}"
        blank.write_bytes(b"\n  \n\t\n")
        expect_error(reader, blank, n_lines=3)
        binaries = {"png": PNG.read_bytes(), "all_bytes": bytes(range(256)) * 8,
                    "random": rng.integers(0, 256, 3000, dtype=np.uint8).tobytes()}
        for name, data in binaries.items():
            path = tmp_path / f"{name}.{reader}"
            path.write_bytes(data)
            err = expect_error(reader, path, n_lines=data.count(b"\n") + 1)
            if name == "png":  # the first line already holds a byte that is not UTF-8
                assert err.line == 1 and "not UTF-8" in str(err), str(err)


def test_random_bytes_and_mutations_only_parse_or_name_the_file(run_dir, tmp_path):
    rng = np.random.default_rng(SEED + 3)
    alphabet = np.frombuffer(b"0123456789.-+eE \n\tnaifITEM:#xyzRow", dtype=np.uint8)
    files = real_files(run_dir)
    path = tmp_path / "fuzz.in"
    for trial in range(1000):
        reader, source, _ = files[trial % len(files)]
        data = source.read_bytes()
        choice = trial % 5
        if choice == 0:    # random bytes
            new = rng.integers(0, 256, int(rng.integers(1, 2000)), dtype=np.uint8).tobytes()
        elif choice == 1:  # random text made of the formats' own characters
            new = rng.choice(alphabet, int(rng.integers(1, 2000))).tobytes()
        elif choice == 2:  # a few bytes of a valid file replaced
            buf = bytearray(data)
            for at in rng.integers(0, len(buf), int(rng.integers(1, 8))):
                buf[at] = int(rng.choice(alphabet))
            new = bytes(buf)
        elif choice == 3:  # lines of a valid file deleted, repeated or swapped
            lines = data.split(b"\n")
            for _ in range(int(rng.integers(1, 4))):
                i, j = rng.integers(0, len(lines), 2)
                op = int(rng.integers(3))
                if op == 0:
                    del lines[i]
                elif op == 1:
                    lines.insert(i, lines[j])
                else:
                    lines[i], lines[j] = lines[j], lines[i]
            new = b"\n".join(lines)
        else:              # a field of a line added, dropped or replaced by a non-number
            lines = data.split(b"\n")
            i = int(rng.integers(len(lines)))
            fields = lines[i].split()
            k = int(rng.integers(len(fields) + 1))
            token = [b"", b"nan", b"1e999", b"x", b"-", b"1.5", b"99999999999999999999"][
                int(rng.integers(7))]
            fields[k:k + int(rng.integers(2))] = [token] if token else []
            lines[i] = b" ".join(fields)
            new = b"\n".join(lines)
        path.write_bytes(new)
        documented_outcome(reader, path, f"trial {trial} (mutation {choice} of {source.name})")


def _drop_or_add_field(line, rng):
    fields = line.split()
    return " ".join(fields[:-1] if rng.integers(2) else fields + ["1.0"])


def test_a_wrong_column_count_is_named_at_its_line(run_dir, tmp_path):
    rng = np.random.default_rng(SEED + 4)
    for reader, source, kind in real_files(run_dir):
        if source.parent != run_dir:  # the tiny run's files suffice; their rows are known
            continue
        lines = source.read_text().split("\n")
        if reader == "log":
            rows = [r for _, rs, _ in log_layout(lines) for r in rs]
        elif reader == "dump":
            rows, i = [], 0
            while i < len(lines):  # atom lines: after 'ITEM: ATOMS', as many as announced
                if lines[i].startswith("ITEM: NUMBER OF ATOMS"):
                    count = int(lines[i + 1])
                if lines[i].startswith("ITEM: ATOMS"):
                    rows += range(i + 1, i + 1 + count)
                    i += count
                i += 1
        else:  # the data lines after the header; fix print: not the first (it sets the width)
            header = {"scalar": 2, "vector": 3, "print": 2}[kind]
            rows = [i for i in range(header, len(lines)) if lines[i].strip()]
        for i in rng.choice(rows, min(8, len(rows)), replace=False):
            bad = list(lines)
            bad[i] = _drop_or_add_field(bad[i], rng)
            path = tmp_path / f"columns_{source.name}"
            path.write_text("\n".join(bad))
            err = expect_error(reader, path, line=i + 1)
            assert "fields" in str(err), str(err)


def test_fields_that_once_escaped_as_other_exceptions(tmp_path):
    """Inputs that raised OverflowError, ValueError from int() or a silent cast before: each is
    named at its line now."""
    vec = "# t\n# TimeStep Number-of-rows\n# Row c_p[1]\n0 {}\n1 0.5\n"
    dump = ("ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS pp pp pp\n0 1\n"
            "0 1\n0 1\nITEM: ATOMS id type x y z\n{} 1 0.5 0.5 0.5\n")
    cases = [("ave_time", vec.format("inf"), 4), ("ave_time", vec.format("nan"), 4),
             ("ave_time", "# t\n#\n0\n", 2), ("ave_time", "# t\n# TimeStep Number-of-rows\n", 3),
             ("ave_time", "# t\n# TimeStep Number-of-rows\n# Row\n0 1\n1\n", 3),
             ("dump", dump.format("--5", 1, 1), 2), ("dump", dump.format(0, "\u00b2", 1), 4),
             ("dump", dump.format(0, "\u0661", 1), 4), ("dump", dump.format(0, 1, "1.5"), 10),
             ("dump", dump.format(0, 1, "1e30"), 10), ("dump", dump.format(0, 1, 1)[:-1], 10)]
    for reader, text, line in cases:
        path = tmp_path / f"case.{reader}"
        path.write_text(text, encoding="utf-8")
        expect_error(reader, path, line=line)
