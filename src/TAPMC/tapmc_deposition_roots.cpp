// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The closed-form root finding of the deposition's events (tapmc_deposition_roots.h): the sign
// changes of a trigonometric polynomial of degree 2 (a quartic in tan(u / 2) on each quarter
// turn, its roots separated by those of its derivatives and found by bisection).
#include "tapmc_deposition_roots.h"

#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>

namespace tapmc {
namespace deposition_detail {

namespace {

inline double horner(const double *c, int deg, double x)
{
  double v = c[deg];
  for (int i = deg - 1; i >= 0; --i) v = v * x + c[i];
  return v;
}

// Where the polynomial c[0] + c[1] x + ... + c[deg] x^deg changes sign in [lo, hi], ascending
// (at most deg points). Its critical points (the same search on the derivative) split [lo, hi]
// into monotone pieces, each holding at most one sign change, found by bisection to the last
// bit: close pairs of roots are separated whatever their distance.
int polynomial_sign_changes(const double *c, int deg, double lo, double hi, double *roots)
{
  if (deg <= 0) return 0;
  double dc[4];
  for (int i = 1; i <= deg; ++i) dc[i - 1] = i * c[i];
  double ends[6];
  int n_ends = 0;
  ends[n_ends++] = lo;
  n_ends += polynomial_sign_changes(dc, deg - 1, lo, hi, ends + 1);
  ends[n_ends++] = hi;
  int n = 0;
  double a = ends[0], fa = horner(c, deg, a);
  for (int q = 1; q < n_ends; ++q) {
    const double b = ends[q], fb = horner(c, deg, b);
    if ((fa < 0.0) != (fb < 0.0)) {
      double x0 = a, x1 = b;
      const bool negative_at_x0 = fa < 0.0;
      for (;;) {
        const double mid = 0.5 * (x0 + x1);
        if (!(mid > x0 && mid < x1)) break;
        if ((horner(c, deg, mid) < 0.0) == negative_at_x0) {
          x0 = mid;
        } else {
          x1 = mid;
        }
      }
      roots[n++] = x0;
    }
    a = b;
    fa = fb;
  }
  return n;
}
}  // namespace

// Where f changes sign in [0, t_max] (t_max <= 2 pi), ascending, at most 4 a quarter turn (the
// array holds 16). On the quarter turn t = s + u, u in [0, pi / 2], f (1 + x^2)^2 with
// x = tan(u / 2) in [0, 1] is a quartic in x of the same sign as f.
int trig2_sign_changes(const Trig2 &f, double t_max, double *roots)
{
  static constexpr double kCos[4] = {1, 0, -1, 0}, kSin[4] = {0, 1, 0, -1};
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    const double s = k * (0.5 * kPi);
    if (s >= t_max) break;
    const double a1 = f.a1 * kCos[k] + f.b1 * kSin[k], b1 = f.b1 * kCos[k] - f.a1 * kSin[k];
    const double c2 = kCos[(2 * k) % 4], s2 = kSin[(2 * k) % 4];
    const double a2 = f.a2 * c2 + f.b2 * s2, b2 = f.b2 * c2 - f.a2 * s2;
    const double c[5] = {f.a0 + a1 + a2, 2.0 * b1 + 4.0 * b2, 2.0 * f.a0 - 6.0 * a2,
                         2.0 * b1 - 4.0 * b2, f.a0 - a1 + a2};
    const double x_max = std::min(1.0, std::tan(0.5 * (t_max - s)));
    double x[4];
    const int m = polynomial_sign_changes(c, 4, 0.0, x_max, x);
    for (int q = 0; q < m; ++q) roots[n++] = std::min(t_max, s + 2.0 * std::atan(x[q]));
  }
  return n;
}

}  // namespace deposition_detail
}  // namespace tapmc
