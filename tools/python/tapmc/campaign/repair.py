# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Repairs of a campaign's run folders, each said on the progress stream and recorded under the
run's "damaged" in the manifest (when it was found, the files and what was wrong with each,
the damagedK/ folder they went to, the step the run goes on from): a finished run whose
outputs changed since, an unfinished run whose per-tap file lost or repeated rows, restart
files cut short or that LAMMPS cannot read. The runner (:mod:`.runner`) decides when; the
files themselves are :mod:`.run_folder`'s."""

from . import provenance, run_folder
from .errors import CampaignError

__all__ = ["RunRepairs", "first_steps"]


def first_steps(rec, resume_step=None):
    """The steps a run's per-tap file may start at, from its manifest record ``rec``: 0, or
    the restart its first attempt resumed from (a run started from another run's restart file,
    as tapmc-paper question does); for a run with no attempt yet, ``resume_step``, the restart
    it resumes from. The start of an attempt killed with its campaign (``running_attempt``)
    counts as an attempt."""
    attempts = rec.get("attempts") or ([rec["running_attempt"]]
                                       if isinstance(rec.get("running_attempt"), dict) else [])
    first = attempts[0].get("resumed_from_step") if attempts else resume_step
    return {0, first} if first else {0}


class RunRepairs:
    """The repairs of the runs of one campaign. ``run_dir``: run name -> its folder;
    ``records``: run name -> its manifest record (changed under ``lock``); ``stream``: where
    the lines go."""

    def __init__(self, run_dir, records, lock, stream):
        self._run_dir = run_dir
        self._records = records
        self._lock = lock
        self._stream = stream

    def _record(self, name, files, aside, step):
        with self._lock:
            self._records[name].setdefault("damaged", []).append(
                {"found": provenance.now(), "files": files, "set_aside": aside.name,
                 "rerun_from_step": step})

    def _say(self, line):
        print(f"[campaign] {line}", file=self._stream, flush=True)

    def unfinish_if_damaged(self, spec, done_file):
        """Check the outputs of a finished run against its DONE.json (one written before
        TAPMC recorded them is trusted as it is). A damaged or missing output makes the run
        unfinished: DONE.json, its log, the damaged files and any file made from the outputs
        after the run finished go to runs/NAME/damagedK/ (every file when the run must start
        again), and the run resumes from its latest restart when that restart is intact and
        no damaged file is named for an earlier step, else from the start. Returns the names
        of the damaged files (the re-run must write each again), or None when the run stays
        finished."""
        recorded = provenance.read_done(done_file).get("outputs")
        if recorded is None:
            return None
        run_dir = done_file.parent
        damaged = provenance.damaged_outputs(run_dir, recorded)
        if not damaged:
            return None
        step, restart = run_folder.latest_restart(run_dir)
        if restart is not None and (restart.name not in recorded or restart.name in damaged):
            step = None
        steps = [run_folder.step_in_name(name) for name in damaged]
        resume = step is not None and all(s is not None and s >= step for s in steps)
        if resume:  # what the resumed run writes again, its log, and files made later
            derived = [n for n in run_folder.output_files(run_dir) if n not in recorded]
            moved = ["DONE.json", "log.lammps", "screen.txt"] + sorted(damaged) + derived
        else:
            moved = [p.name for p in run_dir.iterdir() if p.is_file()]
        try:
            aside = run_folder.set_aside(run_dir, moved)
        except OSError as err:
            files = ", ".join(f"{n} ({what})" for n, what in damaged.items())
            raise CampaignError(
                f"run {spec.name!r}: damaged since it finished: {files} in {run_dir}; it "
                f"cannot be re-run: {err.strerror}: {err.filename}") from None
        start = f"from its restart at step {step}" if resume else "from the start"
        for name, what in damaged.items():
            self._say(f"run {spec.name!r}: {run_dir / name}: {what}; the run goes again "
                      f"{start} (DONE.json and the files it replaces moved to {aside.name}/)")
        self._record(spec.name, damaged, aside, step if resume else 0)
        return sorted(damaged)

    def start_over(self, spec, why):
        """Set every file of a damaged unfinished run aside (runs/NAME/damagedK/): the run
        goes again from the start. ``why``: what is wrong with its per-tap file. Returns the
        folder the files went to."""
        run_dir = self._run_dir(spec.name)
        aside = run_folder.set_aside(run_dir, [p.name for p in run_dir.iterdir() if p.is_file()])
        self._say(f"run {spec.name!r}: {run_dir / spec.taps_file}: {why}; the run goes again "
                  f"from the start (its files moved to {aside.name}/)")
        self._record(spec.name, {spec.taps_file: why}, aside, 0)
        return aside

    def set_cut_restarts_aside(self, spec, bad=None):
        """Move the restart files of a run later than its latest whole one
        (run_folder.resume_restart: cut while LAMMPS wrote them, or in ``bad``, file name ->
        what is wrong), with the profile segments of later steps, into runs/NAME/damagedK/,
        one line each. Returns (step, path) of the restart the run resumes from, (None, None)
        for none."""
        run_dir = self._run_dir(spec.name)
        step, path, cut = run_folder.resume_restart(run_dir, bad)
        if not cut:
            return step, path
        aside = run_folder.set_aside(run_dir, [p.name for p, _ in cut]
                                     + run_folder.segments_after(run_dir, step))
        then = f"the run resumes from {path.name}" if path is not None else \
            "the run starts again from tap 0"
        for p, why in cut:
            self._say(f"run {spec.name!r}: {p}: {why}; moved to {aside.name}/, {then}")
        self._record(spec.name, {p.name: why for p, why in cut}, aside, step or 0)
        return step, path
