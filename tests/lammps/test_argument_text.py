# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The text of a number: every numeric argument of the TAPMC styles that is not a number ("abc",
# "nan", "inf", "1.5x"), or not a whole number where one is needed ("1.5", "1e3"), stops with a
# message naming the style, the argument and the text, and a non-zero exit. LAMMPS 2021's own
# readers (utils::numeric, bnumeric) named neither the argument nor its range ("Expected
# floating point parameter instead of 'abc'"), read 99999999999999999999 sweeps silently, and a
# number's range is still the kernels' to check (test_bad_input.py).
import pytest

from lmprun import run_lammps
from test_bad_input import BOX

LONG_RANGE = "[-9223372036854775808, 9223372036854775807]"

CASES = [
    ("fix s all mc/settle 1 dmax abc", "fix mc/settle: dmax = abc is not a finite number"),
    ("fix s all mc/settle 1 eta nan", "fix mc/settle: eta = nan is not a finite number"),
    ("fix s all mc/settle 1 floor inf", "fix mc/settle: floor = inf is not a finite number"),
    ("fix s all mc/settle 1 theta0 1.5x", "fix mc/settle: theta0 = 1.5x is not a finite number"),
    ("fix s all mc/settle 1 diameter -inf",
     "fix mc/settle: diameter = -inf is not a finite number"),
    ("fix s all mc/settle 1 check 1.5", "fix mc/settle: check = 1.5 is not a whole number"),
    ("fix s all mc/settle 1 maxsweeps 1e3",
     "fix mc/settle: maxsweeps = 1e3 is not a whole number"),
    ("fix s all mc/settle 1 maxsweeps 99999999999999999999",
     "fix mc/settle: maxsweeps = 99999999999999999999 is outside the allowed range " + LONG_RANGE),
    ("fix s all mc/settle 1 stop drift window 2.5",
     "fix mc/settle: window = 2.5 is not a whole number"),
    ("fix s all mc/settle abc", "fix mc/settle: seed = abc is not a whole number"),
    ("fix t all tapdilate nan", "fix tapdilate: eps = nan is not a finite number"),
    ("fix t all tapdilate 0.1 floor abc", "fix tapdilate: floor = abc is not a finite number"),
    ("fix t all tapdilate v_\nrun 1", "fix tapdilate: eps = v_ names no variable"),
    ("fix t all tapdilate 0.1 every 1e3",
     "fix tapdilate: every = 1e3 is not a whole number (allowed range [1, 2147483647]"),
    ("create_packing abc 1 0.5 7", "create_packing: N = abc is not a whole number"),
    ("create_packing 20 1.0 0.5 7", "create_packing: type = 1.0 is not a whole number"),
    ("create_packing 20 1 abc 7", "create_packing: radius = abc is not a finite number"),
    ("create_packing 20 1 0.5 7 dispersity abc",
     "create_packing: dispersity = abc is not a finite number"),
    ("create_packing 20 1 0.5 7 density inf",
     "create_packing: density = inf is not a finite number"),
    ("create_packing 20 1 0.5 7 floor 1,5", "create_packing: floor = 1,5 is not a finite number"),
    ("compute p all stereo/profile floor abc",
     "compute stereo/profile: floor = abc is not a finite number"),
    ("compute p all stereo/profile lateral nan",
     "compute stereo/profile: lateral = nan is not a finite number"),
    ("compute p all stereo/profile window 1 x",
     "compute stereo/profile: window hi = x is not a finite number"),
    ("compute p all stereo/profile planes 0 5 2.5",
     "compute stereo/profile: planes n = 2.5 is not a whole number"),
]


@pytest.mark.parametrize("body,message", CASES)
def test_a_number_that_is_no_number_is_named(body, message):
    rc, out, _ = run_lammps(BOX.format(boundary="p p fm") + body)
    assert rc != 0 and "ERROR: " + message in out, out
    assert "Expected floating point" not in out and "Expected integer" not in out, out


def test_xwalls_name_the_bound_that_is_no_number():
    rc, out, _ = run_lammps(BOX.format(boundary="f f fm") + "fix s all mc/settle 1 xwalls 0 8a")
    assert rc != 0 and "ERROR: fix mc/settle: xwalls hi = 8a is not a finite number" in out, out


def test_walls_none_followed_by_an_axis_is_named():
    """'walls none x' read 'x' as the next keyword: "keyword 'x' needs a value"."""
    rc, out, _ = run_lammps(BOX.format(boundary="f f fm")
                            + "create_packing 20 1 0.5 7 walls none x")
    assert rc != 0 and "create_packing: walls none x: 'none' stands alone" in out, out


def test_numbers_in_every_notation_are_still_read():
    """The readers take what a number's text may be: exponents, a sign, a leading point."""
    rc, out, _ = run_lammps(BOX.format(boundary="p p fm")
                            + "fix s all mc/settle +7 dmax 5e-2 eta .001 check 0002 floor -0.0\n"
                            "fix t all tapdilate 1E-2 every +1\n"
                            "compute p all stereo/profile lateral 2.0e0\nrun 1\n")
    assert rc == 0 and "Loop time" in out, out
