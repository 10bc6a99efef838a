# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Shared helpers of the pore-tool pytest files: random packings, dump writing, running the tool.
import gzip
import os
import subprocess

import numpy as np

EXE = os.environ.get("TAPMC_PORES_EXE", "tapmc-pores")


def random_packing(n, side, periodic, seed, radius=0.5):
    """Random sequential addition of n hard spheres in [0, side)^3: uniform candidates in order,
    each accepted when it overlaps no sphere accepted before. Candidates are drawn in batches and
    tested against the accepted spheres with a k-d tree at once; the first free one is accepted,
    the rest of the batch cleared of its overlaps, and so on: the same packing as one candidate at
    a time, but fast near jamming (where millions of candidates are rejected)."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    lo = np.where(periodic, 0.0, radius)
    hi = np.where(periodic, side, side - radius)
    periodic = np.asarray(periodic, bool)
    boxsize = np.where(periodic, side, 1e9)  # no wrapping along non-periodic directions
    diameter = 2 * radius

    def separations(d):
        d = d.copy()
        d[..., periodic] -= side * np.round(d[..., periodic] / side)
        return np.sqrt(np.einsum("...k,...k->...", d, d))

    centres = np.empty((0, 3))
    attempts = 0
    while len(centres) < n:
        assert attempts < 10**8, "packing too dense for RSA"
        batch = lo + (hi - lo) * rng.random((65536, 3))
        attempts += len(batch)
        if len(centres):
            nearest, _ = cKDTree(centres, boxsize=boxsize).query(batch, k=1)
            batch = batch[nearest >= diameter]
        accepted = []
        while len(batch) and len(centres) + len(accepted) < n:
            accepted.append(batch[0])  # free: the rest of the batch is cleared of its overlaps
            batch = batch[1:][separations(batch[1:] - batch[0]) >= diameter]
        if accepted:
            centres = np.vstack([centres, accepted])
    return centres


def dump_text(centres, side, periodic, timestep=0, radius=0.5, columns="id type x y z radius", ids=None):
    flags = " ".join("pp" if p else "ff" for p in periodic)
    ids = np.arange(1, len(centres) + 1) if ids is None else ids
    lines = ["ITEM: TIMESTEP", str(timestep), "ITEM: NUMBER OF ATOMS", str(len(centres)),
             "ITEM: BOX BOUNDS " + flags] + [f"0 {side!r}"] * 3 + ["ITEM: ATOMS " + columns]
    for i, c in zip(ids, centres):
        values = {"id": str(i), "type": "1", "x": repr(c[0]), "y": repr(c[1]), "z": repr(c[2]),
                  "radius": repr(radius), "diameter": repr(2 * radius)}
        for k, axis in enumerate("xyz"):
            values[axis + "u"] = values[axis]
            values[axis + "s"] = repr(c[k] / side)
        lines.append(" ".join(values[name] for name in columns.split()))
    return "\n".join(lines) + "\n"


def write(path, text):
    if str(path).endswith(".gz"):
        with gzip.open(path, "wt") as f:
            f.write(text)
    else:
        with open(path, "w") as f:
            f.write(text)
    return str(path)


def run(*args, cwd=None):
    return subprocess.run([EXE, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600)


def read_csv(path):
    """CSV with '#' comment lines -> dict of column name -> numpy array (numbers) or list."""
    with open(path) as f:
        rows = [line.rstrip("\n") for line in f if not line.startswith("#")]
    header = rows[0].split(",")
    table = {h: [] for h in header}
    for row in rows[1:]:
        for h, v in zip(header, row.split(",")):
            table[h].append(v)
    out = {}
    for h, values in table.items():
        try:
            out[h] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            out[h] = values
    return out


def read_dump_frame(path):
    """First frame of a `dump custom` text file (plain or gzip): centres, bounds, periodic, text."""
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "rt") as f:
        text = f.read()
    lines = text.splitlines()
    n = int(lines[3])
    periodic = [flag == "pp" for flag in lines[4].split()[3:6]]
    bounds = np.array([[float(v) for v in lines[5 + k].split()[:2]] for k in range(3)])
    columns = lines[8].split()[2:]
    data = np.array([[float(v) for v in line.split()] for line in lines[9:9 + n]])
    centres = data[:, [columns.index(a) for a in "xyz"]]
    return centres, bounds, periodic, text


def surface_height(centres, radius, lo, hi, width):
    """Oracle of h_s: mean over the non-empty columns (width ~ `width`, tiling [lo, hi) in x and
    y) of the highest sphere top in the column (doc/tapmc-pores.rst, "Selection")."""
    n = [max(1, int(np.floor((hi[d] - lo[d]) / width))) for d in range(2)]
    tops = {}
    for c in centres:
        key = tuple(min(n[d] - 1, max(0, int(np.floor((c[d] - lo[d]) / ((hi[d] - lo[d]) / n[d]))))) for d in range(2))
        tops[key] = max(tops.get(key, -np.inf), c[2] + radius)
    return float(np.mean(list(tops.values())))
