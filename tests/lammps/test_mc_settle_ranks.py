# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix tapdilate + fix mc/settle on 1, 2 and 4 ranks (child processes under mpirun), PBC and FBC:
# hard-sphere invariants after every tap (independent all-pairs oracle, periodic images
# included), atom conservation, continuous unwrapped positions, and with 'scheme gather' the same
# trajectory on any rank count (the invariants checked on the serial run, the other rank counts
# equal to it bit for bit). The scene and its helpers are those of test_mc_settle.py; the
# domain-decomposed scheme has its own tests (test_mc_settle_domain.py).
import numpy as np
import pytest

from test_mc_settle import check_frames, serial_run, tapping_run


@pytest.mark.parametrize("nprocs", [1, 2, 4])
@pytest.mark.parametrize("boundary", ["p p fm", "f f fm"])
def test_no_overlap_after_every_tap_and_same_trajectory_on_any_rank_count(boundary, nprocs):
    periodic = boundary.startswith("p")
    serial = serial_run(boundary, 100)
    if nprocs > 1:
        # The trajectory does not depend on the number of ranks (every rank settles all spheres
        # in tag order with the same counter-based random numbers): every dumped column (ids,
        # positions, unwrapped positions, radii) and the box of every frame equal the serial
        # run's, bit for bit, so the invariants checked on it below hold here too.
        frames = tapping_run(boundary, nprocs, scheme="gather")[0]
        assert len(frames) == len(serial)
        for (s1, box1, _, a), (s2, box2, _, b) in zip(frames, serial):
            assert s1 == s2
            np.testing.assert_array_equal(np.asarray(box1), np.asarray(box2))
            assert sorted(a) == sorted(b)
            for c in a:
                np.testing.assert_array_equal(a[c], b[c], err_msg=f"step {s1}: column {c}")
        return
    assert len(serial) == 101
    check_frames(serial, (periodic, periodic), (not periodic, not periodic))
    # Unwrapped positions follow the spheres (check_frames: no jump by a box length).
    if periodic:
        drift = np.hypot(serial[-1][3]["xu"] - serial[0][3]["xu"],
                         serial[-1][3]["yu"] - serial[0][3]["yu"])
        assert drift.max() < 10.0
    # Compaction or at least settling happened: the mean height fell from the dilute lattice.
    assert serial[-1][3]["z"].mean() < 0.8 * serial[0][3]["z"].mean()
