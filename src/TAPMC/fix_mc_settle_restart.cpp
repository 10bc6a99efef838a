// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle's restart record: the settings that shape the trajectory and the last
// diagnostics, written by write_restart() and compared by restart() (fix_mc_settle.cpp runs the
// redeposition).
#include "fix_mc_settle.h"

#include "tapmc_defaults.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "utils.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

// Random numbers are keyed by (seed, timestep, trial): the run continues exactly from a restart
// without stored generator state. The restart record keeps every setting that shapes the
// trajectory (compared after read_restart: a change gives one warning naming old and new values)
// and the last diagnostics [1]-[6]. Its layouts, told apart by the first double:
// - kLayoutSettings (today's): the marker, the seed as two exact 32-bit halves, the values of
//   restart_settings() in its order, the diagnostics in the order of restart_diagnostics();
// - kLayoutSettingsNoGrid (written before the processor grid was kept): the same without the
//   grid, which such files do not tell (it is then not compared);
// - kLayoutSettingsNoLaw (written before 'theta_law' existed): the same without theta_law; such
//   runs had 'theta_law angle';
// - kLayoutSettingsNoStop (written before 'stop' and 'window' existed): the same without the
//   settings that came with the stop rule and theta_law; such runs had 'stop change' and the
//   default window;
// - seed only (the first runs; the first double is the seed itself, >= 1): seed, diagnostics.
// Files of all five are read: no release has been cut yet, but runs of every layout may exist.
// Markers are negative (they cannot be the seed of the seed-only layout) and decrease with each
// new layout, so that a setting added with layout m is stored in every layout <= m.
namespace {
constexpr double kLayoutSettings = -5.0;
constexpr double kLayoutSettingsNoGrid = -4.0;
constexpr double kLayoutSettingsNoLaw = -3.0;
constexpr double kLayoutSettingsNoStop = -2.0;
}  // namespace

// One setting in the restart record: its name in the changed-settings warning, this fix's value
// and, for a setting added after the first settings layout, the layout that added it and the
// value a file of an older layout (without it) implies (NaN: unknown, not compared). `meaning`: what the value stands for
// when it is the setting's "not given" (dmax 0: R/5 of the radii; walls NaN: the box faces), so
// that a default and the value it stands for, written either way, compare equal.
struct FixMCSettle::RestartSetting {
  enum class Meaning { Itself, DMax, XLo, XHi, YLo, YHi };
  const char *name;
  double value;
  double added_in_layout = kLayoutSettingsNoStop;
  double implied_before = 0.0;
  Meaning meaning = Meaning::Itself;
};

std::vector<FixMCSettle::RestartSetting> FixMCSettle::restart_settings() const
{
  auto wall = [this](int dim, int side) { return walls_given[dim] ? wall_pos[dim][side] : NAN; };
  // scheme domain: the grid shapes the trajectory (sub-domains redeposit in rounds); scheme
  // gather gives the same trajectory on any grid, stored as 0
  auto grid = [this](int dim) { return decomposed ? static_cast<double>(comm->procgrid[dim]) : 0.0; };
  using Meaning = RestartSetting::Meaning;
  return {
      {"dmax (0 = default R/5)", d_max, kLayoutSettingsNoStop, 0.0, Meaning::DMax},
      {"theta0", theta0},
      {"eta", eta},
      {"check", static_cast<double>(check_interval)},
      {"maxsweeps", static_cast<double>(max_sweeps)},
      {"floor", z_floor},
      {"diameter/2 (0 = per-atom radii)", fixed_radius},
      {"order (0 random, 1 sweep)", sweep_order ? 1.0 : 0.0},
      {"xwalls lo", wall(0, 0), kLayoutSettingsNoStop, 0.0, Meaning::XLo},  // NaN: not given
      {"xwalls hi", wall(0, 1), kLayoutSettingsNoStop, 0.0, Meaning::XHi},
      {"ywalls lo", wall(1, 0), kLayoutSettingsNoStop, 0.0, Meaning::YLo},
      {"ywalls hi", wall(1, 1), kLayoutSettingsNoStop, 0.0, Meaning::YHi},
      {"stop (0 change, 1 drift)", stop_drift ? 1.0 : 0.0, kLayoutSettingsNoLaw, 0.0},
      {"window", static_cast<double>(drift_window), kLayoutSettingsNoLaw,
       static_cast<double>(tapmc::defaults::kSettleDriftWindow)},
      {"theta_law (0 angle, 1 solid, 2 exponential, 3 linear)",
       static_cast<double>(static_cast<int>(theta_law)), kLayoutSettingsNoGrid, 0.0},
      {"processors x (0 = scheme gather, any grid)", grid(0), kLayoutSettings, NAN},
      {"processors y", grid(1), kLayoutSettings, NAN},
      {"processors z", grid(2), kLayoutSettings, NAN},
  };
}

// The diagnostics kept in the record: the output vector's [1]-[6].
std::array<double *, 6> FixMCSettle::restart_diagnostics()
{
  return {&last_sweeps, &last_acceptance, &last_mean_z, &last_hit_cap, &last_trials,
          &last_mean_z0};
}

void FixMCSettle::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const auto useed = static_cast<std::uint64_t>(seed);
  std::vector<double> record = {kLayoutSettings, static_cast<double>(useed >> 32),
                                static_cast<double>(useed & 0xFFFFFFFFu)};
  for (const RestartSetting &setting : restart_settings()) record.push_back(setting.value);
  for (const double *diagnostic : restart_diagnostics()) record.push_back(*diagnostic);
  const int size = static_cast<int>(record.size() * sizeof(double));
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(record.data(), sizeof(double), record.size(), fp);
}

void FixMCSettle::restart(char *buf)
{
  const auto *next = reinterpret_cast<const double *>(buf);
  const double layout = *next++;
  auto text = [](double v) { return std::isnan(v) ? std::string("none") : fmt::format("{}", v); };
  // What a "not given" value stands for now (collective: every rank reads the record): the
  // radii and the box are those the restart file brought.
  using Meaning = RestartSetting::Meaning;
  const double default_step = tapmc::defaults::kMaxStepOverRadius * group_radius_extreme(false);
  // in a container no flat walls stand anywhere: "not given" stays none
  auto face = [this](int dim, int side) -> double {
    if (domain->periodicity[dim] || !container_region_id.empty()) return NAN;
    return side == 0 ? domain->boxlo[dim] : domain->boxhi[dim];
  };
  auto resolved = [&](Meaning meaning, double v) {
    switch (meaning) {
      case Meaning::DMax: return v == 0.0 ? default_step : v;
      case Meaning::XLo: return std::isnan(v) ? face(0, 0) : v;
      case Meaning::XHi: return std::isnan(v) ? face(0, 1) : v;
      case Meaning::YLo: return std::isnan(v) ? face(1, 0) : v;
      case Meaning::YHi: return std::isnan(v) ? face(1, 1) : v;
      default: return v;
    }
  };
  std::string changed;
  auto compare = [&](const char *name, double old_value, double new_value, Meaning meaning) {
    const double a = resolved(meaning, old_value), b = resolved(meaning, new_value);
    const bool same = a == b || (std::isnan(a) && std::isnan(b));
    if (!same)
      changed += fmt::format("{}{} {} -> {}", changed.empty() ? "" : ", ", name, text(old_value),
                             text(new_value));
  };
  if (layout == kLayoutSettings || layout == kLayoutSettingsNoGrid ||
      layout == kLayoutSettingsNoLaw || layout == kLayoutSettingsNoStop) {
    const auto old_seed = static_cast<std::int64_t>((static_cast<std::uint64_t>(next[0]) << 32) |
                                                    static_cast<std::uint64_t>(next[1]));
    next += 2;
    if (old_seed != seed) changed += fmt::format("seed {} -> {}", old_seed, seed);
    for (const RestartSetting &setting : restart_settings()) {
      const bool stored = layout <= setting.added_in_layout;
      if (!stored && std::isnan(setting.implied_before)) continue;  // the file does not tell
      compare(setting.name, stored ? *next++ : setting.implied_before, setting.value,
              setting.meaning);
    }
  } else {
    const auto old_seed = static_cast<std::int64_t>(layout);
    if (old_seed != seed) changed += fmt::format("seed {} -> {}", old_seed, seed);
  }
  if (!changed.empty() && comm->me == 0)
    error->warning(FLERR, "fix mc/settle: settings differ from the restart file (restart -> now): "
                   "{}; the run will not continue the original trajectory", changed);
  for (double *diagnostic : restart_diagnostics()) *diagnostic = *next++;
}
