# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Independent cross-check: the pores of tapmc-pores (CGAL, canonical periodic cells) against
# scipy's Qhull Delaunay of explicitly replicated images, on random packings and several seeds.
import itertools

import numpy as np
import pytest
from scipy.spatial import Delaunay

from pores_py_util import dump_text, random_packing, read_csv, run, write

R = 0.5


def qhull_pores(centres, side, periodic):
    """Pores (sorted id quadruple -> (xi, centre)) with the circumcentre in the primary box."""
    shifts = [s for s in itertools.product(*[(-1, 0, 1) if p else (0,) for p in periodic])]
    images = np.vstack([centres + side * np.array(s) for s in shifts])
    ids = np.tile(np.arange(1, len(centres) + 1), len(shifts))
    tri = Delaunay(images)
    p = images[tri.simplices]
    a = p[:, 1:] - p[:, :1]
    det = np.linalg.det(a)
    ok = np.abs(det) > 1e-12
    centre = np.linalg.solve(a[ok], 0.5 * np.einsum("nij,nij->ni", a[ok], a[ok])) + p[ok, 0]
    radius = np.linalg.norm(centre - p[ok, 0], axis=1)
    simplices = tri.simplices[ok]
    inside = np.ones(len(centre), bool)
    for k in range(3):
        inside &= (centre[:, k] >= 0) & (centre[:, k] < side)
    out = {}
    for s, c, r in zip(simplices[inside], centre[inside], radius[inside]):
        out[tuple(sorted(ids[s]))] = (r / R - 1, c)
    return out


@pytest.mark.parametrize("periodic", [(True, True, True), (True, True, False)])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_pores_match_qhull(tmp_path, periodic, seed):
    side = 7.0
    centres = random_packing(220, side, periodic, seed)
    dump = write(tmp_path / "p.dump", dump_text(centres, side, periodic))
    # The whole box is the selection, so every pore centred in it is resolved.
    result = run("-q", "--pores", "--wall-gap", "0", "--z", f"0:{side}", "-o", tmp_path / "out", dump)
    assert result.returncode == 0, result.stderr
    mine = read_csv(tmp_path / "out.pores.csv")
    ours = {}
    for k in range(len(mine["xi"])):
        key = tuple(int(mine[f"id{j}"][k]) for j in range(1, 5))
        ours[key] = (mine["xi"][k], np.array([mine["x"][k], mine["y"][k], mine["z"][k]]))
    theirs = qhull_pores(centres, side, periodic)

    # Compare well-posed pores: away from the seams (no circumcentre rounding ambiguity) and, in
    # the slab, inside the box in z with a moderate size (free-surface hull cells excluded).
    def comparable(xi, c):
        margin = 1e-6
        if np.any((c < margin) | (c > side - margin)):
            return False
        return all(periodic) or xi < 2.0

    a = {k: v for k, v in ours.items() if comparable(*v)}
    b = {k: v for k, v in theirs.items() if comparable(*v)}
    assert len(a) > 1000
    assert set(a) == set(b)
    for key, (xi, c) in a.items():
        assert abs(xi - b[key][0]) < 1e-9
        assert np.allclose(c, b[key][1], atol=1e-9)
    if all(periodic):  # every periodic Delaunay cell once: total count equal too
        assert len(ours) == len(theirs)
