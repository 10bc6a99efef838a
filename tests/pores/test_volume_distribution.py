# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The two distributions of the pore volume v = xi^3 written by tapmc-pores, on a real TAPMC packing
# (tests/pores/data/small_tapped.dump.gz): n_v, the number density of v, integrates to 1, and
# rho_v, the paper's rho_v(v) = (xi/3) P(xi) = v n_v(v) (section IV.B: rho_v(v) dv = xi^3 P(xi) dxi),
# integrates to the tool's own nu, "nu = int xi^3 P(xi) dxi = int rho_v(v) dv". Each bin is checked
# against the pores themselves (PREFIX.pores.csv), and the JSON against the CSV.
#
# Tolerances. The tool's rho_v is, bin by bin, the sum of the v of the pores in the bin over N w (N
# selected pores, w the bin width), not v at the bin centre times n_v: its integral is the sum of
# the in-range v over N, which is nu exactly when no pore is out of range (checked from the '#'
# line). What is left is rounding: the CSV has 12 significant digits (kOutputDigits, json_writer.h),
# so a sum of 150 terms is within 150 x 5e-12 < 1e-9 of its exact value: rel. tolerance 1e-9. The
# approximations that do depend on the binning are bounded exactly: a v in a bin is within w/2 of
# its centre, so |rho_v - v_centre n_v| <= (w/2) n_v per bin; an xi in [xi_lo, xi_hi) has
# |xi^3 - xi_centre^3| <= xi_hi^3 - xi_centre^3, which bounds how far the integral of xi3_P_xi
# (evaluated at the bin centres) is from nu.
import json
import math
import os
import re

import numpy as np

from pores_py_util import read_csv, run

DATA = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "."), "tests/pores/data/small_tapped.dump.gz")
ROUNDING = 1e-9  # relative: 150 CSV terms of 12 significant digits (see above)


def summary_line(prefix):
    """nu and the pores below / above the histogram range, from the '#' line of PREFIX.hist.csv."""
    with open(f"{prefix}.hist.csv") as f:
        line = f.readline()
    match = re.search(r"nu = ([-+0-9.eE]+), xi below range (\d+), above (\d+)", line)
    assert match, line
    return float(match.group(1)), int(match.group(2)), int(match.group(3))


def selected_v(prefix):
    pores = read_csv(f"{prefix}.pores.csv")
    return pores["xi"][pores["selected"] == 1] ** 3


def test_rho_v_integrates_to_nu_and_n_v_to_one_on_a_real_packing(tmp_path):
    prefix = tmp_path / "real"
    result = run("-q", "--json", "--frame-hist", "--pores", "-o", prefix, DATA)
    assert result.returncode == 0, result.stderr
    nu, below, above = summary_line(prefix)
    assert below == 0 and above == 0  # every pore in range: the integral is all of nu
    frames = read_csv(f"{prefix}.frames.csv")
    assert frames["nu"][0] == nu and frames["selected"][0] > 1500
    hist = read_csv(f"{prefix}.hist.csv")
    w = hist["v_hi"] - hist["v_lo"]
    assert math.isclose(np.sum(hist["rho_v"] * w), nu, rel_tol=ROUNDING)
    assert math.isclose(np.sum(hist["n_v"] * w), 1.0, rel_tol=ROUNDING)
    assert 0.08 < nu < 0.16  # a packing's nu, far from 1: the two integrals are told apart

    # Bin by bin, from the pores: n_v counts them, rho_v sums their v.
    v = selected_v(prefix)
    assert v.size == frames["selected"][0]
    assert math.isclose(np.mean(v), nu, rel_tol=ROUNDING)
    edges = np.append(hist["v_lo"], hist["v_hi"][-1])
    counts, _ = np.histogram(v, edges)
    volumes, _ = np.histogram(v, edges, weights=v)
    np.testing.assert_array_equal(hist["count_v"], counts)
    np.testing.assert_allclose(hist["n_v"], counts / (v.size * w), rtol=ROUNDING, atol=0)
    np.testing.assert_allclose(hist["rho_v"], volumes / (v.size * w), rtol=ROUNDING, atol=0)
    # rho_v = v n_v within the bin: at most (w/2) n_v from the centre value, and not equal to it
    # (the bins are 0.0225 wide: the pores of a bin are not at its centre).
    deviation = np.abs(hist["rho_v"] - hist["v"] * hist["n_v"])
    assert np.all(deviation <= 0.5 * w * hist["n_v"] * (1 + ROUNDING) + 1e-300)
    assert np.max(deviation) > 0.01 * np.max(hist["rho_v"])

    # xi^3 P(xi) (the paper's rho_v(xi)) integrates to nu within its bin-centre bound.
    xw = hist["xi_hi"] - hist["xi_lo"]
    bound = np.sum(hist["count_xi"] / v.size * (hist["xi_hi"] ** 3 - hist["xi"] ** 3))
    assert abs(np.sum(hist["xi3_P_xi"] * xw) - nu) <= bound

    # The JSON and the per-frame histograms carry the same columns.
    data = json.load(open(f"{prefix}.json"))
    aggregate = data["aggregate"]
    for name in ("count_v", "n_v", "rho_v"):
        np.testing.assert_allclose(aggregate[name], hist[name], rtol=ROUNDING, atol=0)
        np.testing.assert_allclose(data["frames"][0]["statistics"][name], hist[name], rtol=ROUNDING, atol=0)
    per_frame = read_csv(f"{prefix}.frame_hist.csv")
    for name in ("n_v", "rho_v"):
        np.testing.assert_array_equal(per_frame[name], hist[name])


def test_pores_beyond_the_range_count_in_n_but_carry_no_volume(tmp_path):
    # --xi-max 0.5: v on [0, 0.125), so the largest pores of the packing overflow. Both integrals
    # then fall short by exactly the overflowing pores: n_v by their number, rho_v by their v.
    prefix = tmp_path / "short"
    result = run("-q", "--xi-max", "0.5", "--pores", "-o", prefix, DATA)
    assert result.returncode == 0, result.stderr
    nu, below, above = summary_line(prefix)
    v = selected_v(prefix)
    inside = v < 0.5 ** 3
    assert below == 0 and above == np.sum(~inside) > 0
    hist = read_csv(f"{prefix}.hist.csv")
    w = hist["v_hi"] - hist["v_lo"]
    assert math.isclose(np.sum(hist["n_v"] * w), np.mean(inside), rel_tol=ROUNDING)
    assert math.isclose(np.sum(hist["rho_v"] * w), np.sum(v[inside]) / v.size, rel_tol=ROUNDING)
    assert np.sum(hist["rho_v"] * w) < nu * (1 - 1e-3)  # the missing part is seen, not rounding
