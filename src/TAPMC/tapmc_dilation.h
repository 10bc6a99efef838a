// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The tap (paper, section II): homothetic vertical dilation about the floor.
#ifndef TAPMC_DILATION_H
#define TAPMC_DILATION_H

namespace tapmc {

// The parameters of the tap (fix tapdilate).
struct DilationParams {
  double eps = 0.0;     // relative dilation of the heights above the floor, in [0, kMaxTapEps]
  long every = 1;       // tap on the timesteps that are multiples of `every`, >= 1
  double z_floor = 0.0; // the floor the heights are measured from
};

// Throws std::invalid_argument naming the first bad parameter, its value and its allowed range.
void validate(const DilationParams &params);

// z -> z_floor + (z - z_floor)(1 + eps) for the n positions x[3i+2] whose mask[i] is nonzero
// (mask == nullptr: all). Heights above the floor grow by the factor 1 + eps; x and y are
// untouched. Returns the largest dilated z among the moved positions (-inf if none moved).
double dilate_about_floor(double *xyz, const int *mask, int groupbit, int n, double z_floor,
                          double eps);

// The dilated height of one position (the formula above, for checks and tests).
inline double dilated_height(double z, double z_floor, double eps)
{
  return z_floor + (z - z_floor) * (1.0 + eps);
}

}  // namespace tapmc

#endif
