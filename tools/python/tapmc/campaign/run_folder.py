# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The folder of one run: what it holds and how it is repaired for a resume. Steps of the
per-tap file and restart files, trimming rows written after a restart, the title lines that a
resumed segment repeats, merging the ``fix ave/time`` segments of resumed runs, the checks of
a restart file and of the steps of a per-tap file, LAMMPS's error line, and setting damaged
files aside. The files it rewrites are replaced whole (:mod:`.atomic`)."""

import os
import re
from pathlib import Path

from ..readers import read_ave_time_blocks
from . import atomic

__all__ = ["RESTART_MARK", "restarts", "latest_restart", "restart_problem", "resume_restart",
           "keep_latest_restart", "trim_rows", "drop_repeated_titles", "step_rows_problem",
           "merge_ave_time_parts", "segments_after", "taps_done", "log_error",
           "restart_read_error", "keep_log_as_attempt", "remove_temporary_files",
           "output_files", "step_in_name", "set_aside"]

#: files that record how a run went rather than what it computed (never checksummed)
_RECORDS = re.compile(r"DONE\.json|screen\.txt|log\.lammps|log\.attempt\d+\.lammps")


#: LAMMPS's restart files (write_restart.cpp) start with this string and, from format
#: revision 1 on, end with it: read_restart's own check of a whole file (check_eof_magic)
RESTART_MARK = b"LammpS RestartT\0"


def restarts(run_dir):
    """[(step, path)] of the non-empty restart.STEP files of a run folder, latest first."""
    found = []
    for p in Path(run_dir).glob("restart.*"):
        m = re.fullmatch(r"restart\.(\d+)", p.name)
        if m and p.is_file() and p.stat().st_size > 0:
            found.append((int(m.group(1)), p))
    return sorted(found, key=lambda sp: -sp[0])


def latest_restart(run_dir):
    """(step, path) of the restart file of the largest step, or (None, None), whole or not
    (:func:`resume_restart` gives the one a run resumes from)."""
    found = restarts(run_dir)
    return found[0] if found else (None, None)


def restart_problem(path):
    """'' when the restart file ``path`` looks whole, else why not. A whole file starts with
    LAMMPS's restart mark and, when its format revision says LAMMPS writes the mark at the end
    too (revision 1 and later: every LAMMPS since 2019), ends with it. A file cut while LAMMPS
    wrote it (a kill, a SIGTERM, a full disk) lacks the end mark; LAMMPS itself stops reading
    such a file with "Unexpected end of file" (or, with a later LAMMPS, "Incomplete or
    corrupted LAMMPS restart file"), or reads a file cut in its last byte without a word."""
    n = len(RESTART_MARK)
    try:
        with open(path, "rb") as f:
            head = f.read(n + 8)
            size = f.seek(0, os.SEEK_END)
            f.seek(max(0, size - n))
            tail = f.read(n)
    except OSError as err:
        return f"cannot be read ({err.strerror})"
    if head[:n] != RESTART_MARK:
        return f"not a LAMMPS restart file ({size} bytes, without the restart mark it starts with)"
    if len(head) < n + 8:
        return f"{size} bytes: cut short in its header"
    endian = int.from_bytes(head[n:n + 4], "little")
    revision = int.from_bytes(head[n + 4:n + 8], "little")
    if endian == 1 and revision >= 1 and tail != RESTART_MARK:
        return (f"{size} bytes without LAMMPS's end mark: cut short while it was written (a "
                "kill, a stop or a full disk)")
    return ""


def resume_restart(run_dir, bad=None):
    """(step, path, cut): the latest restart file of a run that looks whole
    (:func:`restart_problem`) and is not one of ``bad`` (file name -> what is wrong with it:
    e.g. LAMMPS could not read it), or (None, None, cut) when there is none; ``cut``: [(path,
    why)] of the later ones (a resume sets them aside)."""
    bad = bad or {}
    cut = []
    for step, path in restarts(run_dir):
        why = bad.get(path.name) or restart_problem(path)
        if not why:
            return step, path, cut
        cut.append((path, why))
    return None, None, cut


def keep_latest_restart(run_dir, keep_every=None):
    """Delete every restart file but the latest (it continues the sequence) and, with
    ``keep_every``, those of the steps it divides (a ramp's level ends)."""
    last, _ = latest_restart(run_dir)
    for p in Path(run_dir).glob("restart.*"):
        m = re.fullmatch(r"restart\.(\d+)", p.name)
        if not m:
            continue
        step = int(m.group(1))
        if step != last and not (keep_every and step % keep_every == 0):
            p.unlink()


def _first_int(line):
    try:
        return int(line.split()[0])
    except (IndexError, ValueError):
        return None


def trim_rows(path, before_step):
    """Keep the comment lines and the rows of a per-step file whose step < before_step (the
    file replaced whole, :func:`atomic.write_text`, and only when a row goes)."""
    path = Path(path)
    if not path.exists():
        return
    text = path.read_text(errors="replace")
    kept = []
    for line in text.splitlines(keepends=True):
        if not line.endswith("\n"):
            break  # a row cut short by the kill
        step = _first_int(line)
        if line.startswith("#") or (step is not None and step < before_step):
            kept.append(line)
    if "".join(kept) != text:
        atomic.write_text(path, "".join(kept))


def drop_repeated_titles(path):
    """Remove the title line that each resumed segment appends again (fix print append); the
    file is replaced whole, and only when a line goes."""
    path = Path(path)
    if not path.exists():
        return
    seen, out, dropped = set(), [], False
    for line in path.read_text(errors="replace").splitlines(keepends=True):
        if line.startswith("#"):
            if line in seen:
                dropped = True
                continue
            seen.add(line)
        out.append(line)
    if dropped:
        atomic.write_text(path, "".join(out))


def step_rows_problem(path, last, starts=(0,), past_last=False):
    """'' when the data rows of the per-tap file ``path`` (one row per tap, the step first) are
    the steps first, first + 1, ..., ``last``, each once and in this order, with ``first`` one
    of ``starts``; else the first thing wrong, as a phrase. No rows at all is right when
    ``last + 1`` is one of ``starts`` (nothing written yet from that step). A missing file
    has no rows. A resume trims the rows past its restart, and a finish reads the whole run:
    a per-tap file emptied or rewritten by a kill, or written by two processes at once, is
    never taken for a finished run's. ``past_last``: rows after ``last`` are left unread (what
    a resume from step ``last + 1`` would trim), as a dry run reads a run it would resume."""
    path = Path(path)
    expected = None
    try:
        f = open(path, errors="replace")
    except FileNotFoundError:
        f = None
    except OSError as err:
        return f"{path.name} cannot be read ({err.strerror})"
    if f is not None:
        with f:
            for number, line in enumerate(f, start=1):
                if line.startswith("#") or not line.strip():
                    continue
                step = _first_int(line)
                if step is None:
                    return f"{path.name}:{number}: not a row of a step"
                if past_last and step > last and expected is not None and step >= expected:
                    break
                if expected is None:
                    if step not in starts:
                        return (f"{path.name} starts at step {step}, not at "
                                f"{' or '.join(map(str, sorted(set(starts))))}")
                elif step != expected:
                    what = "repeated" if step < expected else "missing"
                    return (f"{path.name}:{number}: step {step} where {expected} was due "
                            f"(rows {what})")
                expected = step + 1
    if expected is None:
        if last + 1 in starts:
            return ""
        return f"{path.name} has no rows (steps up to {last} expected)"
    if expected - 1 != last:
        return f"{path.name} ends at step {expected - 1}, expected {last}"
    return ""


def _segments(run_dir):
    """file name -> its ``name.from<step>`` segments [(step, path)], sorted by step."""
    parts = {}
    for p in Path(run_dir).glob("*.from*"):
        m = re.fullmatch(r"(.+)\.from(\d+)", p.name)
        if m:
            parts.setdefault(m.group(1), []).append((int(m.group(2)), p))
    return {base: sorted(segs) for base, segs in parts.items()}


def _joined_blocks(main, segs, finished):
    """(header, blocks) of ``main`` joined with its segments ``segs`` (see
    :func:`joined_ave_time`); ``finished``: the last file was written by a run that ended (a
    last block cut short raises), not by one still running or killed."""
    files = ([(0, main)] if main.exists() else []) + segs
    # A run killed before its first output leaves an empty segment: it holds no block, and
    # the blocks of the segment before it stay valid up to the next segment's start (a
    # resumed run repeats the same trajectory from its restart).
    files = [f for k, f in enumerate(files)
             if k + 1 == len(files) or f[1].stat().st_size > 0]
    header, blocks = None, []
    for k, (start, p) in enumerate(files):
        last = k + 1 == len(files)
        if last and not finished and p.stat().st_size == 0:
            break
        h, b = read_ave_time_blocks(p, killed=not (last and finished))
        header = header if header is not None else h
        end = None if last else files[k + 1][0]
        blocks += [blk for blk in b if blk[0] >= start and (end is None or blk[0] < end)]
    return header or [], blocks


def joined_ave_time(run_dir, name):
    """The fix ave/time file ``name`` of a run that may still be running or was killed, joined
    with the ``name.from<step>`` segments its resumed attempts wrote, as
    :func:`merge_ave_time_parts` would merge them, without touching a file: ``(header,
    blocks)`` as :func:`tapmc.readers.read_ave_time_blocks` gives them, a last block cut short
    left out; ``([], [])`` when the run has written none of them."""
    run_dir = Path(run_dir)
    main = run_dir / name
    segs = _segments(run_dir).get(name, [])
    if not main.exists() and not segs:
        return [], []
    return _joined_blocks(main, segs, finished=False)


def merge_ave_time_parts(run_dir):
    """Merge ``X.from<step>`` segments of fix ave/time files written by resumed runs into X.

    Each segment replaces the blocks of the earlier ones from its first step on; the merged
    file has the header of the first segment. The files are read by
    :func:`tapmc.readers.read_ave_time_blocks` (a malformed one raises its TapmcFormatError);
    every segment but the last was written by a killed run, so its last block may be cut
    short. Returns the list of merged file names."""
    run_dir = Path(run_dir)
    merged = []
    for base, segs in _segments(run_dir).items():
        main = run_dir / base
        header, blocks = _joined_blocks(main, segs, finished=True)
        # whole or not at all; a kill before the segments go leaves a merge that gives the
        # same file again
        text = "".join(header) + "".join("".join(lines) for _, lines in blocks)
        atomic.write_text(main, text)
        for _, p in segs:
            p.unlink()
        merged.append(base)
    return merged


def segments_after(run_dir, step):
    """Names of the profile segments ``X.from<s>`` of a run folder with s > ``step`` (all of
    them when ``step`` is None): an attempt that resumes from ``step`` writes their steps again,
    and kept, they would replace its blocks in the merge."""
    return sorted(p.name for segs in _segments(run_dir).values() for s, p in segs
                  if step is None or s > step)


#: ERROR as a word not quoted: a line of LAMMPS's own words (behind a prefix, such as an MPI
#: launcher's), not an echoed input line that prints one (``"print 'ERROR: ...'"``)
_UNQUOTED_ERROR = re.compile(r"""(?<!['"])\bERROR\b""")


def log_error(log):
    """The first ERROR line of a LAMMPS log (or screen file), or ''. LAMMPS's own error
    lines start with ERROR; failing those, a line with an unquoted ERROR in it. Echoed input
    lines of the paper's inputs check their variables with ``print 'ERROR: ...'``: a log that
    holds only those names no error (a run stopped from outside leaves such a log)."""
    log = Path(log)
    if not log.exists():
        return ""
    lines = log.read_text(errors="replace").splitlines()
    for line in lines:
        if line.startswith("ERROR"):
            return line.strip()
    return next((line.strip() for line in lines if _UNQUOTED_ERROR.search(line)), "")


#: LAMMPS's words when read_restart fails on its file: "Last command:" follows the error line
_READ_RESTART_FAILED = re.compile(r"^Last command:\s*read_restart\b", re.MULTILINE)


def restart_read_error(log):
    """LAMMPS's error line when the run of ``log`` stopped in its read_restart (a restart file
    cut short, or unreadable otherwise), else ''."""
    log = Path(log)
    if not log.exists():
        return ""
    if not _READ_RESTART_FAILED.search(log.read_text(errors="replace")):
        return ""
    return log_error(log) or "read_restart failed"


def taps_done(path):
    """Step of the last row of a per-tap file (cheap: reads its tail), or 0."""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            size = f.tell()
            f.seek(max(0, size - 4096))
            tail = f.read().decode(errors="replace").splitlines()
    except OSError:
        return 0
    for line in reversed(tail):
        step = _first_int(line)
        if step is not None and not line.startswith("#"):
            return step
    return 0


def keep_log_as_attempt(run_dir):
    """Rename the log.lammps of an attempt that did not finish to log.attemptK.lammps (K the
    next free number); returns the new name, or None when there is no log."""
    run_dir = Path(run_dir)
    if not (run_dir / "log.lammps").exists():
        return None
    kept = run_dir / f"log.attempt{len(list(run_dir.glob('log.attempt*.lammps'))) + 1}.lammps"
    (run_dir / "log.lammps").replace(kept)
    return kept.name


def remove_temporary_files(run_dir):
    """Remove the ``NAME.tmp`` files a rewrite of the run folder left when it was killed
    before they replaced their targets (:mod:`.atomic`); returns their names."""
    removed = []
    for p in Path(run_dir).iterdir():
        if p.is_file() and atomic.is_temporary(p.name):
            p.unlink()
            removed.append(p.name)
    return sorted(removed)


def output_files(run_dir):
    """Names of the files a run computed (per-tap file, profiles, dumps, restart): every file
    of its folder but DONE.json, the logs, screen.txt and the temporary files of the
    campaign's own writes (``NAME.tmp``, :mod:`.atomic`: DONE.json.tmp of a kill before its
    rename became an output, and the run's next check found it gone), sorted."""
    return sorted(p.name for p in Path(run_dir).iterdir()
                  if p.is_file() and not _RECORDS.fullmatch(p.name)
                  and not atomic.is_temporary(p.name))


def step_in_name(name):
    """The step a file is named for (``restart.4000``, ``dump.4000.lammpstrj``), or None."""
    m = re.search(r"(?:^|\.)(\d+)(?:\.|$)", name)
    return int(m.group(1)) if m else None


def set_aside(run_dir, names):
    """Move the files ``names`` of a run folder into a new subfolder damagedK (K the next
    free number) and return its path; raises OSError when they cannot be moved."""
    run_dir = Path(run_dir)
    k = 1
    while (run_dir / f"damaged{k}").exists():
        k += 1
    folder = run_dir / f"damaged{k}"
    folder.mkdir()
    for name in names:
        if (run_dir / name).exists():
            (run_dir / name).replace(folder / name)
    return folder
