# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Helpers for process-level tests: run lmp_tapmc (optionally under mpirun) on an input text,
# read dumps and check hard-sphere geometry with an independent all-pairs oracle; an FCC lattice
# input, a reader of thermo tables, and readers of print lines and fix ave/time files for the
# compute tests.
import os
import subprocess
import tempfile

import numpy as np

LMP = os.environ.get("TAPMC_LMP", os.path.join(os.environ.get("TAPMC_BUILD_DIR", "../../build"),
                                                "lmp_tapmc"))
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]


def run_lammps(script, nprocs=1, workdir=None, variables=None, timeout=600):
    """Run lmp_tapmc on the input text `script` in `workdir` (a new temporary directory when
    None). Returns (returncode, combined output, workdir)."""
    workdir = workdir or tempfile.mkdtemp(prefix="tapmc_")
    path = os.path.join(workdir, "in.test")
    with open(path, "w") as f:
        f.write(script)
    cmd = [LMP, "-in", "in.test", "-log", "log.lammps", "-nocite"]
    for name, value in (variables or {}).items():
        cmd += ["-var", name, str(value)]
    if nprocs > 1:
        cmd = MPIRUN + ["-np", str(nprocs)] + cmd
    proc = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    return proc.returncode, proc.stdout, workdir


def written_restart(scene, tap, settle, taps=1):
    """Run ``scene`` with ``fix tap all <tap>`` and ``fix settle all <settle>`` for ``taps``
    taps and write a.restart: (its folder, the input that reads it back, defines the same
    fixes and taps once). A test changes that input and reads what fix mc/settle says."""
    rc, out, workdir = run_lammps(f"{scene}fix tap all {tap}\nfix settle all {settle}\n"
                                  f"run {taps}\nwrite_restart a.restart\n")
    assert rc == 0, out
    return workdir, f"read_restart a.restart\nfix tap all {tap}\nfix settle all {settle}\nrun 1\n"


def thermo_table(out, second="c_phi[1]"):
    """The first thermo table of a LAMMPS output or log text whose header reads 'Step <second>
    ...': (column names, rows as a 2-d float array, step 0 included). The warnings LAMMPS writes
    between the rows are skipped."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.split()[:2] == ["Step", second])
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("Loop time"):
            break
        if not line.startswith("WARNING"):
            rows.append([float(v) for v in line.split()])
    return lines[start].split(), np.array(rows)


def dump_atoms_text(workdir, name="final.dump"):
    """The atom lines of a one-frame dump, as text: two runs that should have ended in the same
    state compare equal bit for bit (write the dump with format float %.17g)."""
    with open(os.path.join(workdir, name)) as f:
        return f.read().split("ITEM: ATOMS")[1]


def read_dump(path):
    """All frames of a LAMMPS text dump written with `dump custom ... id ... ` and
    `dump_modify sort id`. Returns a list of (timestep, box (3x2 array), boundary strings,
    {column: array})."""
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        assert lines[k].startswith("ITEM: TIMESTEP"), lines[k]
        step = int(lines[k + 1])
        n = int(lines[k + 3])
        bounds_header = lines[k + 4].split()[3:]
        box = np.array([[float(v) for v in lines[k + 5 + d].split()[:2]] for d in range(3)])
        columns = lines[k + 8].split()[2:]
        data = np.array([[float(v) for v in line.split()] for line in lines[k + 9:k + 9 + n]])
        data = data.reshape(n, len(columns))
        frames.append((step, box, bounds_header, {c: data[:, i] for i, c in enumerate(columns)}))
        k += 9 + n
    return frames


def min_gap(xyz, radius, box, periodic_xy, floor=None):
    """Smallest surface gap over all pairs (periodic images in x / y by minimum image, valid
    for boxes wider than two diameters), and optionally to the floor. Negative = overlap.
    Returns (gap, i, j) with j = -1 for the floor."""
    xyz = np.asarray(xyz, dtype=float)
    n = len(xyz)
    lengths = box[:, 1] - box[:, 0]
    best = (np.inf, -1, -1)
    for i in range(n - 1):
        d = xyz[i + 1:] - xyz[i]
        for dim in range(2):
            if periodic_xy[dim]:
                d[:, dim] -= lengths[dim] * np.round(d[:, dim] / lengths[dim])
        gap = np.sqrt((d * d).sum(axis=1)) - (radius[i] + radius[i + 1:])
        j = int(np.argmin(gap))
        if gap[j] < best[0]:
            best = (float(gap[j]), i, i + 1 + j)
    if floor is not None:
        fg = xyz[:, 2] - radius - floor
        i = int(np.argmin(fg))
        if fg[i] < best[0]:
            best = (float(fg[i]), i, -1)
    return best


def free_drops(xyz, radius, box, periodic_xy, floor):
    """How far each sphere could fall straight down before it touches another sphere or the
    floor (brute force over all pairs, minimum image in periodic x / y): a redeposited bed
    leaves no sphere with room beneath it for another sphere (a drop of a diameter or more
    means a sphere hangs over a hole). Returns an array, one drop per sphere."""
    xyz = np.asarray(xyz, dtype=float)
    radius = np.asarray(radius, dtype=float)
    lengths = box[:, 1] - box[:, 0]
    drops = xyz[:, 2] - radius - floor
    for i in range(len(xyz)):
        d = xyz - xyz[i]
        for dim in range(2):
            if periodic_xy[dim]:
                d[:, dim] -= lengths[dim] * np.round(d[:, dim] / lengths[dim])
        reach = radius + radius[i]
        horizontal2 = d[:, 0] ** 2 + d[:, 1] ** 2
        below = (d[:, 2] < 0) & (horizontal2 < reach ** 2)
        below[i] = False
        if below.any():
            gaps = -d[below, 2] - np.sqrt(reach[below] ** 2 - horizontal2[below])
            drops[i] = min(drops[i], gaps.min())
    return drops


# A 4 x 4 x 8 FCC lattice of cells of side 2 (spheres at contact, R = 1/sqrt(2)), layers
# z = 0 .. 15 (region "0 4 0 4 0 7.9", in lattice units) in a box 8 x 8 x 20; the region may
# shift the lattice points off the box faces. Used by the compute tests (stereo/profile,
# contacts).
FCC_LATTICE = """units metal
atom_style sphere
boundary {boundary}
lattice fcc 2.0
region box block 0 4 0 4 0 10
create_box 1 box
region latt block {region}
create_atoms 1 region latt
set group all diameter 1.4142135623730951
set group all density 1.0
"""


def fcc_lattice(boundary="p p f", region="0 4 0 4 0 7.9"):
    """The LAMMPS commands of FCC_LATTICE with the given boundary and region."""
    return FCC_LATTICE.format(boundary=boundary, region=region)


def printed(out, tag):
    """Numbers of the last line `tag v1 v2 ...` that LAMMPS's `print` wrote to `out`."""
    lines = [l for l in out.splitlines() if l.startswith(tag + " ")]
    assert lines, out[-2000:]
    return np.array([float(v) for v in lines[-1].split()[1:]])


def ave_time_rows(path):
    """Last block of a fix ave/time mode vector file: rows of (index, c1, c2, ...)."""
    with open(path) as f:
        lines = [l for l in f.read().splitlines() if not l.startswith("#")]
    blocks, k = [], 0
    while k < len(lines):
        step, nrows = (int(v) for v in lines[k].split())
        blocks.append(np.array([[float(v) for v in l.split()] for l in lines[k + 1:k + 1 + nrows]]))
        k += 1 + nrows
    return blocks[-1]
