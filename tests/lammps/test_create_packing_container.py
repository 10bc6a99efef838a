# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# create_packing with 'container REGION-ID' (a vertical cylinder): every sphere inside the wall,
# none overlapping (independent all-pairs check), the same packing on 1 and 2 ranks and for the
# same seed, the interior volume fraction of a tube of 10 diameters in the range of random loose
# packings, and bad input stopping with a message that names the argument.
import os

import numpy as np
import pytest

from lmprun import min_gap, read_dump, run_lammps

CONTACT_TOL = 1e-10

TUBE = """units lj
atom_style sphere
boundary {boundary}
region box block 0 10 0 10 0 60
create_box 1 box
region tube cylinder z 5 5 5 INF INF
create_packing {n} 1 0.5 {seed} floor 0.0 container tube{extra}
dump d all custom 1 packing.dump id x y z radius
dump_modify d sort id format float %.17g
run 0
"""


def tube(n=1500, seed=77, nprocs=1, boundary="f f fm", extra=""):
    rc, out, wd = run_lammps(TUBE.format(n=n, seed=seed, boundary=boundary, extra=extra),
                             nprocs=nprocs)
    return rc, out, wd


def packing(**kw):
    rc, out, wd = tube(**kw)
    assert rc == 0, out
    step, box, _, cols = read_dump(os.path.join(wd, "packing.dump"))[-1]
    return out, box, cols


@pytest.mark.parametrize("nprocs", [1, 2])
def test_tube_packing_is_inside_the_wall_without_overlap(nprocs):
    out, box, cols = packing(nprocs=nprocs)
    assert len(cols["id"]) == 1500
    xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
    r = cols["radius"]
    gap, i, j = min_gap(xyz, r, box, (False, False), floor=0.0)
    assert gap >= -CONTACT_TOL * 2 * r.max(), (gap, i, j)
    wall_gap = (5.0 - r) - np.hypot(xyz[:, 0] - 5.0, xyz[:, 1] - 5.0)
    assert wall_gap.min() >= -CONTACT_TOL * 2 * r.max()
    assert (wall_gap < 1e-6).sum() > 100  # the wall is a support: many spheres touch it
    assert "sides: the wall of container 'tube' (radius 5, axis x = 5, y = 5)" in out
    # random loose packing in the interior of a tube of 10 diameters
    interior = next(ln for ln in out.splitlines() if ln.startswith("  interior volume fraction"))
    phi = float(interior.split()[3])
    assert 0.52 < phi < 0.60, interior


def test_same_packing_for_the_same_seed_on_any_rank_count():
    _, _, one = packing()
    _, _, two = packing(nprocs=2)
    _, _, other = packing(seed=78)
    for c in ("x", "y", "z"):
        np.testing.assert_array_equal(one[c], two[c])
    assert not np.array_equal(one["z"], other["z"])


@pytest.mark.parametrize("kw,message", [
    ({"boundary": "p f fm"}, "periodic"),
    ({"extra": " walls x"}, "walls"),
    ({"extra": " region tube"}, "region"),
    ({"n": 20000, "boundary": "f f f"}, "cannot hold"),
])
def test_bad_container_input_names_the_argument(kw, message):
    rc, out, _ = tube(**kw)
    assert rc != 0
    errors = [line for line in out.splitlines() if "ERROR" in line]
    assert errors and message in errors[0], out[-2000:]


def test_unknown_container_region_is_named():
    script = TUBE.format(n=100, seed=1, boundary="f f fm", extra="").replace(
        "container tube", "container pipe")
    rc, out, _ = run_lammps(script)
    assert rc != 0
    assert "pipe" in next(line for line in out.splitlines() if "ERROR" in line)


def test_printed_measures_are_the_compute_in_the_same_container():
    script = TUBE.format(n=1500, seed=77, boundary="f f fm", extra="").replace(
        "run 0", "compute phi all stereo/profile floor 0.0 container tube\n"
                 "thermo_style custom step c_phi[1] c_phi[2] c_phi[3]\nrun 0")
    rc, out, _ = run_lammps(script)
    assert rc == 0, out
    lines = out.splitlines()
    header = next(k for k, ln in enumerate(lines) if ln.split()[:1] == ["Step"])
    phi_b, phi_c, mean_z = (float(v) for v in lines[header + 1].split()[1:4])
    printed = next(ln for ln in lines if ln.startswith("  compute stereo/profile (defaults)"))
    words = printed.replace(",", "").split()
    values = [float(words[words.index(name) + 1]) for name in ("Phi_b", "<Phi^c>", "<Z>")]
    np.testing.assert_allclose(values, [phi_b, phi_c, mean_z], atol=6e-5)
    assert 0.45 < phi_b < 0.56  # over the disk's area, not the box's (that would read 0.40)
