# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix tapdilate + fix mc/settle on 1, 2 and 4 ranks (child processes under mpirun), PBC and FBC:
# hard-sphere invariants after every tap (independent all-pairs oracle, periodic images
# included), atom conservation, continuous unwrapped positions, and with 'scheme gather' the same
# trajectory on any rank count. The scene and its helpers are those of test_mc_settle.py; the
# domain-decomposed scheme has its own tests (test_mc_settle_domain.py).
import numpy as np
import pytest

from test_mc_settle import check_frames, serial_run, tapping_run


@pytest.mark.parametrize("nprocs", [1, 2, 4])
@pytest.mark.parametrize("boundary", ["p p fm", "f f fm"])
def test_no_overlap_after_every_tap_and_same_trajectory_on_any_rank_count(boundary, nprocs):
    periodic = boundary.startswith("p")
    frames = (serial_run(boundary, 100) if nprocs == 1
              else tapping_run(boundary, nprocs, scheme="gather")[0])
    assert len(frames) == 101
    check_frames(frames, (periodic, periodic), (not periodic, not periodic))
    # Unwrapped positions follow the spheres (check_frames: no jump by a box length).
    if periodic:
        drift = np.hypot(frames[-1][3]["xu"] - frames[0][3]["xu"],
                         frames[-1][3]["yu"] - frames[0][3]["yu"])
        assert drift.max() < 10.0
    # Compaction or at least settling happened: the mean height fell from the dilute lattice.
    z0 = frames[0][3]["z"].mean()
    z_end = frames[-1][3]["z"].mean()
    assert z_end < 0.8 * z0
    # The trajectory does not depend on the number of ranks (every rank settles all spheres in
    # tag order with the same counter-based random numbers).
    if nprocs > 1:
        serial = serial_run(boundary, 100)
        for (s1, _, _, a), (s2, _, _, b) in zip(frames, serial):
            assert s1 == s2
            for c in ("x", "y", "z"):
                np.testing.assert_array_equal(a[c], b[c])
