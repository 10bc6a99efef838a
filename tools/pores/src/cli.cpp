// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// tapmc-pores command line: options, the frame loop over many dumps, CSV/JSON outputs (the
// --help text: usage.cpp).
#include "tapmc_pores/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "tapmc_pores/analysis.h"
#include "tapmc_pores/dump_reader.h"
#include "tapmc_pores/errors.h"
#include "tapmc_pores/json_writer.h"
#include "tapmc_pores/pores_config.h"
#include "tapmc_pores/tessellation.h"
#include "tapmc_pores/usage.h"

namespace tapmc {
namespace pores {
namespace {

struct Options {
  std::vector<std::string> files;
  double radius = 0.0;
  ReaderOptions reader;
  std::size_t skip = 0, every = 1, max_frames = std::numeric_limits<std::size_t>::max();
  RegionSpec region;
  double floor = std::numeric_limits<double>::quiet_NaN();  // NaN: the lowest sphere bottom
  HistogramSpec histogram;
  std::string prefix = "pores";
  bool help = false, version = false, frame_hist = false, pore_list = false, json = false, quiet = false;
  std::size_t p0_samples = 0;
  double sigma_max = config::kDefaultSigmaMax;
  std::size_t sigma_steps = config::kDefaultSigmaBins;
  std::uint64_t seed = 1;
  PoreOptions pores;
  bool merge_tolerance_given = false;  // else from the frame's written digits (merge_tolerance_for)
};

double to_double(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) throw UsageError(option + " expects a number, got '" + text + "'");
  return value;
}

std::size_t to_count(const std::string& option, const std::string& text, std::size_t minimum) {
  std::size_t used = 0;
  unsigned long long value = 0;
  try {
    value = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || text[0] == '-' || value < minimum)
    throw UsageError(option + " expects an integer >= " + std::to_string(minimum) + ", got '" + text + "'");
  return static_cast<std::size_t>(value);
}

// An integer in [minimum, maximum]; a value out of range, beyond 64 bits included, is named with
// the range, so that no huge value reaches an allocation (std::bad_alloc, exit code 3).
std::size_t to_count_in_range(const std::string& option, const std::string& text, std::size_t minimum,
                              std::size_t maximum) {
  const std::string range = "[" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]";
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    throw UsageError(option + " expects an integer in " + range + ", got '" + text + "'");
  // Digits only: more significant digits than the maximum is out of range without converting.
  const std::size_t first = text.find_first_not_of('0');
  const bool too_long = first != std::string::npos && text.size() - first > std::to_string(maximum).size();
  const std::size_t value = too_long ? 0 : static_cast<std::size_t>(std::stoull(text));
  if (too_long || value < minimum || value > maximum)
    throw UsageError(option + " = " + text + ": allowed range " + range);
  return value;
}

// A number in [minimum, maximum]; a value outside is named with the range (and `unit`, e.g. ", in R").
double to_double_in_range(const std::string& option, const std::string& text, double minimum, double maximum,
                          const std::string& unit = "") {
  const double value = to_double(option, text);
  if (!(value >= minimum && value <= maximum))
    throw UsageError(option + " = " + text + ": allowed range [" + number_text(minimum) + ", " + number_text(maximum) +
                     "]" + unit);
  return value;
}

// A number for which `allowed` holds; else UsageError naming `option`, the value given and the
// allowed range (an interval's text, e.g. "(0, inf)").
double to_double_where(const std::string& option, const std::string& text, bool (*allowed)(double),
                       const std::string& range, const std::string& unit = "") {
  const double value = to_double(option, text);
  if (!allowed(value)) throw UsageError(option + " = " + text + ": allowed range " + range + unit);
  return value;
}

// The value of the option being parsed (the next argument); UsageError when there is none.
using NextValue = std::function<const std::string&()>;

// `text` as LO:HI into the selection bounds along `d` (either side may be empty).
void set_range(RegionSpec& region, int d, const std::string& option, const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw UsageError(option + " expects LO:HI (either side may be empty), got '" + text + "'");
  const std::string lo = text.substr(0, colon), hi = text.substr(colon + 1);
  if (!lo.empty()) region.lo[d] = to_double(option, lo);
  if (!hi.empty()) region.hi[d] = to_double(option, hi);
  if (!lo.empty() && !hi.empty() && !(region.hi[d] > region.lo[d]))
    throw UsageError(option + " needs LO < HI, got '" + text + "'");
}

// `text` as CX:CY:RC, a vertical tube (the selection in x and y is a disk inside it).
void set_cylinder(RegionSpec& region, const std::string& option, const std::string& text) {
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ':') parts.emplace_back();
    else parts.back() += c;
  }
  if (parts.size() != 3 || parts[0].empty() || parts[1].empty() || parts[2].empty())
    throw UsageError(option + " expects CX:CY:RC (axis and radius of the tube), got '" + text + "'");
  RegionSpec::Cylinder& tube = region.cylinder;
  tube.given = true;
  tube.text = text;
  tube.centre_x = to_double(option, parts[0]);
  tube.centre_y = to_double(option, parts[1]);
  tube.radius = to_double(option, parts[2]);
  if (!(tube.radius > 0)) throw UsageError(option + " = " + text + ": the radius RC = " + parts[2] + " must be > 0");
}

// Options without a value; false when `a` is none of them.
bool set_flag(Options& o, const std::string& a) {
  if (a == "-h" || a == "--help") o.help = true;
  else if (a == "--version") o.version = true;
  else if (a == "--radii") o.region.units.fill(RegionSpec::Units::kRadiiFromLo);
  else if (a == "--paper-window") {
    o.region.units.fill(RegionSpec::Units::kRadiiFromLo);
    o.region.lo[2] = 2.0;   // 2R above the floor ...
    o.region.hi[2] = 20.0;  // ... 18R high (Fig. 10)
  } else if (a == "--frame-hist") o.frame_hist = true;
  else if (a == "--pores") o.pore_list = true;
  else if (a == "--json") o.json = true;
  else if (a == "-q" || a == "--quiet") o.quiet = true;
  else return false;
  return true;
}

// Options of the input and of the selection; false when `a` is none of them.
bool set_input_option(Options& o, const std::string& a, const NextValue& value) {
  if (a == "-r" || a == "--radius") {
    o.radius = to_double_where(a, value(), [](double v) { return v > 0; }, "(0, inf)");
  } else if (a == "--boundary") {
    const std::string text = value();
    if (text.size() != 3 || text.find_first_not_of("pf") != std::string::npos)
      throw UsageError("--boundary expects three letters p or f (e.g. ppf), got '" + text + "'");
    o.reader.override_periodic = true;
    for (int d = 0; d < 3; ++d) o.reader.periodic[d] = text[d] == 'p';
  } else if (a == "--skip") o.skip = to_count(a, value(), 0);
  else if (a == "--every") o.every = to_count(a, value(), 1);
  else if (a == "--max-frames") o.max_frames = to_count(a, value(), 1);
  else if (a == "--x" || a == "--y" || a == "--z") set_range(o.region, a[2] - 'x', a, value());
  else if (a == "--cylinder") set_cylinder(o.region, a, value());
  else if (a == "--wall-gap")
    o.region.wall_gap_over_radius = to_double_where(a, value(), [](double v) { return v >= 0; }, "[0, inf)", ", in R");
  else if (a == "--surface-gap")
    o.region.surface_gap_over_radius = to_double_where(a, value(), [](double v) { return v >= 0; }, "[0, inf)", ", in R");
  else if (a == "--floor") o.floor = to_double(a, value());
  else return false;
  return true;
}

// Options of the analysis and of the outputs; false when `a` is none of them.
bool set_analysis_option(Options& o, const std::string& a, const NextValue& value) {
  if (a == "--bins") o.histogram.bins = to_count_in_range(a, value(), 1, config::kMaxBins);
  else if (a == "--xi-max")
    o.histogram.xi_max = to_double_in_range(a, value(), config::kMinXiMax, config::kMaxXiMax, " (a pore radius over R)");
  else if (a == "-o" || a == "--output") {
    o.prefix = value();
    if (o.prefix.empty()) throw UsageError(a + " expects a file prefix (e.g. out/pores), got ''");
  }
  else if (a == "--p0") o.p0_samples = to_count_in_range(a, value(), 1, config::kMaxP0Samples);
  else if (a == "--sigma-max")
    o.sigma_max = to_double_where(a, value(), [](double v) { return v > 1 && v <= config::kMaxSigmaMax; },
                                  "(1, " + message_number(config::kMaxSigmaMax) + "] (in R)");
  else if (a == "--sigma-steps") o.sigma_steps = to_count_in_range(a, value(), 2, config::kMaxSigmaSteps);
  else if (a == "--seed") o.seed = to_count(a, value(), 0);
  else if (a == "--overlap-tol")
    o.pores.overlap_tolerance = to_double_where(a, value(), [](double v) { return v >= 0 && v < 1; }, "[0, 1)");
  else if (a == "--merge-tol")
  {
    o.pores.merge_tolerance = to_double_where(a, value(), [](double v) { return v >= 0 && v < 0.1; }, "[0, 0.1)");
    o.merge_tolerance_given = true;
  }
  else if (a == "--padding")
    o.pores.padding_over_radius = to_double_in_range(a, value(), config::kMinPaddingOverRadius, config::kMaxPaddingOverRadius, ", in R");
  else return false;
  return true;
}

Options parse(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const NextValue value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (set_flag(o, a) || set_input_option(o, a, value) || set_analysis_option(o, a, value)) continue;
    if (a.size() > 1 && a[0] == '-') throw UsageError("unknown option '" + a + "'");
    o.files.push_back(a);
  }
  if (o.help || o.version) return o;
  if (o.files.empty()) throw UsageError("no dump file given");
  for (int d = 0; d < 2; ++d)
    if (o.region.cylinder.given && (!std::isnan(o.region.lo[d]) || !std::isnan(o.region.hi[d])))
      throw UsageError(std::string("--cylinder ") + o.region.cylinder.text + " sets the selection in x and y: --" +
                       "xy"[d] + " cannot be given with it (use --z for the height)");
  try {
    (void)PoreStatistics(o.histogram);  // validates the bins
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return o;
}

// An output file written as PATH.partial and renamed to PATH by commit(): a refused run removes
// it (destructor), so that no partial output ever carries a final name.
class OutputFile {
 public:
  explicit OutputFile(std::string path) : path_(std::move(path)), partial_(path_ + ".partial") {
    stream_.open(partial_);
    if (!stream_) throw OutputError("cannot write '" + partial_ + "'");
    stream_ << std::setprecision(kOutputDigits);
  }
  ~OutputFile() {
    if (!committed_) {
      stream_.close();
      std::remove(partial_.c_str());
    }
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  std::ofstream& stream() { return stream_; }
  const std::string& path() const { return path_; }
  // Throws when the final name cannot take the file (a directory of that name): checked for
  // every output before any is renamed, so that a refused run leaves no output at all.
  void check_destination() const {
    std::error_code ec;
    if (std::filesystem::is_directory(path_, ec))
      throw OutputError("cannot write '" + path_ + "': a directory of that name exists");
  }
  void commit() {
    stream_.close();
    if (!stream_) throw OutputError("writing '" + partial_ + "' failed (disk full?)");
    if (std::rename(partial_.c_str(), path_.c_str()) != 0)
      throw OutputError("cannot rename '" + partial_ + "' to '" + path_ + "'");
    committed_ = true;
  }

 private:
  std::string path_, partial_;
  std::ofstream stream_;
  bool committed_ = false;
};

// A warning raised by some frames, printed once at the end with the first frame concerned.
struct Warning {
  std::size_t frames = 0;
  std::string first_frame;  // location and details of the first frame concerned
};

// Numbers for CSV: NaN becomes an empty field.
std::string csv_number(double v) { return std::isnan(v) ? "" : number_text(v); }

// A text field of a CSV row (a file name): quoted when it holds a comma, a quote or a line
// break, its quotes doubled (RFC 4180, as Python's csv module reads it).
std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

struct FrameSummary {
  std::string file;
  std::size_t frame = 0;
  long long timestep = 0;
  std::size_t atoms = 0, pores = 0, tetrahedra = 0, unresolved = 0;
  double radius = 0, region_volume = 0, tetrahedra_volume = 0, phi_p0 = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0;
  PoreStatistics stats;
};

void write_histogram_rows(std::ostream& out, const PoreStatistics& s, const std::string& row_prefix) {
  for (std::size_t i = 0; i < s.xi.bins(); ++i) {
    const double xi = s.xi.bin_centre(i), p = s.xi.density(i);
    out << row_prefix << i << "," << csv_number(s.xi.bin_lo(i)) << "," << csv_number(s.xi.bin_lo(i) + s.xi.width()) << ","
        << csv_number(xi) << "," << s.xi.count(i) << "," << csv_number(p) << "," << csv_number(xi * xi * xi * p) << ","
        << csv_number(s.v.bin_lo(i)) << "," << csv_number(s.v.bin_lo(i) + s.v.width()) << "," << csv_number(s.v.bin_centre(i))
        << "," << s.v.count(i) << "," << csv_number(s.v.density(i)) << "," << csv_number(s.v.weighted_density(i))
        << "\n";
  }
}
// n_v: number density of v (integral 1); rho_v: the paper's v n_v(v) (integral nu, section IV.B).
const char* kHistogramColumns = "bin,xi_lo,xi_hi,xi,count_xi,P_xi,xi3_P_xi,v_lo,v_hi,v,count_v,n_v,rho_v";

void write_json_statistics(JsonWriter& json, const PoreStatistics& s, bool with_histograms) {
  json.begin_object();
  json.key("pores").value(s.pores).key("degenerate_pores").value(s.degenerate).key("nu").value(s.nu());
  json.key("mean_xi").value(s.mean_xi()).key("xi_underflow").value(s.xi.underflow());
  json.key("xi_overflow").value(s.xi.overflow());
  if (with_histograms) {
    auto array = [&](const char* name, std::size_t n, auto value) {
      json.key(name).begin_array();
      for (std::size_t i = 0; i < n; ++i) json.value(value(i));
      json.end_array();
    };
    array("xi_edges", s.xi.bins() + 1, [&](std::size_t i) { return s.xi.lo() + s.xi.width() * double(i); });
    array("count_xi", s.xi.bins(), [&](std::size_t i) { return s.xi.count(i); });
    array("P_xi", s.xi.bins(), [&](std::size_t i) { return s.xi.density(i); });
    array("xi3_P_xi", s.xi.bins(), [&](std::size_t i) {
      const double xi = s.xi.bin_centre(i);
      return xi * xi * xi * s.xi.density(i);
    });
    array("v_edges", s.v.bins() + 1, [&](std::size_t i) { return s.v.lo() + s.v.width() * double(i); });
    array("count_v", s.v.bins(), [&](std::size_t i) { return s.v.count(i); });
    array("n_v", s.v.bins(), [&](std::size_t i) { return s.v.density(i); });
    array("rho_v", s.v.bins(), [&](std::size_t i) { return s.v.weighted_density(i); });
  }
  json.end_object();
}

// PREFIX.json: the aggregate, every frame and the P0 curves (when sampled), for Python.
void write_json(std::ostream& out, std::size_t analysed, const PoreStatistics& total,
                const std::vector<FrameSummary>& summaries, bool frame_histograms, const P0Statistics* p0) {
  JsonWriter json(out);
  json.begin_object().key("tool").value("tapmc-pores").key("frames_analysed").value(analysed);
  json.break_line(1).key("aggregate");
  write_json_statistics(json, total, true);
  json.break_line(1).key("frames").begin_array();
  for (const FrameSummary& f : summaries) {
    json.break_line(2).begin_object();
    json.key("file").value(f.file).key("frame").value(f.frame).key("timestep").value(f.timestep);
    json.key("atoms").value(f.atoms).key("radius").value(f.radius).key("pores_total").value(f.pores);
    json.key("tetrahedra").value(f.tetrahedra).key("unresolved").value(f.unresolved);
    json.key("region_volume").value(f.region_volume).key("tetrahedra_volume").value(f.tetrahedra_volume);
    json.key("phi_p0").value(f.phi_p0).key("seconds").value(f.seconds).key("statistics");
    write_json_statistics(json, f.stats, frame_histograms);
    json.end_object();
  }
  json.end_array();
  if (p0) {
    const double phi = p0->phi();
    std::vector<double> sigma, measured, percus_yevick;
    for (std::size_t k = 0; k < p0->steps(); ++k) {
      sigma.push_back(p0->sigma(k));
      measured.push_back(p0->p0(k));
      // No Percus-Yevick curve outside 0 < phi < 1: NaN, written as null.
      percus_yevick.push_back(phi > 0 && phi < 1 ? gotoh_p0(p0->sigma(k), phi) : std::numeric_limits<double>::quiet_NaN());
    }
    json.break_line(1).key("p0").begin_object().key("samples").value(p0->samples).key("phi").value(phi);
    json.key("sigma").array(sigma).key("measured").array(measured).key("percus_yevick").array(percus_yevick);
    json.end_object();
  }
  json.end_object();
  out << "\n";
}

// The --overlap-tol that accepts an overlap of `depth` (of a diameter): rounded up to two
// significant digits; 0 when no tolerance below 1 does (coincident centres).
double accepting_tolerance(double depth) {
  if (!(depth > 0)) return 0.0;
  const double unit = std::pow(10.0, std::floor(std::log10(depth)) - 1.0);
  const double tolerance = (std::floor(depth / unit) + 1.0) * unit;
  return tolerance < 1.0 ? tolerance : 0.0;
}

// "FILE:LINE: frame N (timestep T): ", the place of a message about `frame`.
std::string where(const Frame& frame, std::size_t line) {
  std::ostringstream s;
  s << frame.source << ":" << line << ": frame " << frame.index << " (timestep " << frame.timestep << "): ";
  return s.str();
}

// The message refusing overlapping spheres: the deepest pair, its atom lines, and the
// --overlap-tol that would accept it.
std::string overlap_message(const Frame& frame, const OverlapError& e) {
  std::ostringstream what;
  what << where(frame, frame.first_atom_line + e.index_a) << e.what() << " (atom lines "
       << frame.first_atom_line + e.index_a << " and " << frame.first_atom_line + e.index_b << "). ";
  const double tolerance = accepting_tolerance(e.depth);
  if (e.index_a == e.index_b)
    what << "The periodic box is shorter than a diameter.";
  else if (tolerance > 0)
    what << "To accept overlapping spheres (e.g. a DEM dump), give --overlap-tol above the deepest overlap, "
            "here --overlap-tol "
         << tolerance << " (pores whose empty sphere is squeezed by overlaps get xi < 0, counted below range).";
  else if (e.distance > 0)
    what << "The centres nearly coincide: this is not a packing of spheres.";
  else
    what << "The centres coincide (a sphere written twice?): this is not a packing of spheres.";
  return what.str();
}

std::string region_text(const Region& region) {
  std::ostringstream text;
  text.precision(6);
  if (region.disk) {
    text << "disk of radius " << region.disk_radius << " about (" << region.centre_x << ", " << region.centre_y
         << ") x [" << region.lo[2] << ", " << region.hi[2] << ")";
    return text.str();
  }
  text << "[" << region.lo[0] << ", " << region.hi[0] << ") x [" << region.lo[1] << ", " << region.hi[1] << ") x ["
       << region.lo[2] << ", " << region.hi[2] << ")";
  return text.str();
}

// The packing of one frame and the selection of its pores.
struct Selection {
  double radius = 0;
  PackingBounds packing;
  Region region;
};

// One run of the program: its output files (removed unless the run succeeds), the warnings, and
// the totals over the frames analysed.
class PoreRun {
 public:
  PoreRun(const Options& options, std::ostream& err);
  // Analyses the chosen frames of one file, up to --max-frames in total.
  void analyse_file(const std::string& path);
  // Writes the aggregate outputs, renames every output to its final name, prints the warnings.
  void finish();

 private:
  std::ofstream& output(const std::string& suffix);
  void warn(const std::string& kind, const std::string& location, const std::string& details);
  void analyse_frame(const Frame& frame);
  Selection select(const Frame& frame);
  void warn_about_packing(const Frame& frame, const Selection& selection);
  std::unique_ptr<Tessellation> tessellate(const Frame& frame, const Selection& selection) const;
  void warn_about_pores(const Frame& frame, const Region& region, const PoreResult& result, const PoreStatistics& s);
  void write_frame(const Frame& frame, const FrameSummary& summary, const Region& region, const PoreResult& result);
  void write_p0_csv();

  const Options& o_;
  std::ostream& err_;
  std::vector<std::unique_ptr<OutputFile>> outputs_;
  std::vector<std::pair<std::string, Warning>> warnings_;  // by kind, in the order first raised
  std::ofstream* frames_csv_ = nullptr;
  std::ofstream* frame_hist_csv_ = nullptr;
  std::ofstream* pores_csv_ = nullptr;
  PoreStatistics total_;
  P0Statistics p0_total_;
  std::vector<FrameSummary> summaries_;
  std::size_t analysed_ = 0;
};

PoreRun::PoreRun(const Options& options, std::ostream& err)
    : o_(options), err_(err), total_(options.histogram), p0_total_(options.sigma_max, options.sigma_steps) {
  frames_csv_ = &output(".frames.csv");
  *frames_csv_ << "file,frame,timestep,atoms,radius,pores,tetrahedra,unresolved,selected,degenerate_selected,nu,mean_xi,"
                  "region_volume,tetrahedra_volume,phi_p0,seconds\n";
  if (o_.frame_hist) {
    frame_hist_csv_ = &output(".frame_hist.csv");
    *frame_hist_csv_ << "file,frame,timestep," << kHistogramColumns << "\n";
  }
  if (o_.pore_list) {
    pores_csv_ = &output(".pores.csv");
    *pores_csv_ << std::setprecision(15) << "file,frame,timestep,x,y,z,xi,id1,id2,id3,id4,tetrahedra,volume,selected\n";
  }
}

std::ofstream& PoreRun::output(const std::string& suffix) {
  outputs_.push_back(std::make_unique<OutputFile>(o_.prefix + suffix));
  return outputs_.back()->stream();
}

void PoreRun::warn(const std::string& kind, const std::string& location, const std::string& details) {
  auto it = std::find_if(warnings_.begin(), warnings_.end(), [&](const auto& w) { return w.first == kind; });
  if (it == warnings_.end()) {
    warnings_.emplace_back(kind, Warning{});
    it = std::prev(warnings_.end());
    it->second.first_frame = location + details;
  }
  ++it->second.frames;
}

void PoreRun::analyse_file(const std::string& path) {
  if (analysed_ >= o_.max_frames) return;  // the files after the last frame wanted are not opened
  Frame frame;  // outside the try: an unforeseen error names the frame being analysed
  bool analysing = false;
  try {
    DumpReader reader = DumpReader::open(path, o_.reader);
    std::size_t seen = 0;
    while (analysed_ < o_.max_frames && reader.next(frame)) {
      ++seen;
      if (seen <= o_.skip || (seen - o_.skip - 1) % o_.every != 0) continue;
      analysing = true;
      analyse_frame(frame);
      analysing = false;
    }
  } catch (const RunRefused&) {
    throw;
  } catch (const std::exception& e) {  // unforeseen: still say where, as located messages do
    throw InputError((analysing ? where(frame, frame.first_line) : path + ": ") + e.what());
  }
}

// Every centre inside the tube: a centre beyond RC from the axis means the wrong --cylinder.
void check_tube(const Frame& frame, const RegionSpec::Cylinder& tube) {
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const double dx = frame.xyz[3 * i] - tube.centre_x, dy = frame.xyz[3 * i + 1] - tube.centre_y;
    const double distance = std::sqrt(dx * dx + dy * dy);
    if (distance > tube.radius) {
      std::ostringstream what;
      what.precision(10);
      what << where(frame, frame.first_atom_line + i) << "--cylinder " << tube.text << ": atom " << frame.ids[i]
           << " is centred " << distance << " from the axis, outside the tube of radius " << tube.radius
           << " (is the axis or the radius wrong?)";
      throw InputError(what.str());
    }
  }
}

Selection PoreRun::select(const Frame& frame) {
  Selection selection;
  try {
    selection.radius = common_radius(frame, o_.radius).radius;
  } catch (const RadiusError& e) {
    throw InputError(where(frame, frame.first_atom_line + e.index) + e.what());
  }
  try {
    selection.packing = find_packing(frame.box, frame.xyz, selection.radius, o_.floor);
    selection.region = make_region(frame.box, selection.packing, selection.radius, o_.region);
  } catch (const std::invalid_argument& e) {
    throw InputError(where(frame, frame.first_line) + e.what());
  }
  if (o_.region.cylinder.given) check_tube(frame, o_.region.cylinder);
  return selection;
}

// Spheres below --floor, and a selection reaching the free surface.
void PoreRun::warn_about_packing(const Frame& frame, const Selection& selection) {
  const PackingBounds& packing = selection.packing;
  const Region& region = selection.region;
  const double r = selection.radius;
  if (!packing.free_surface) return;
  if (!std::isnan(o_.floor) && packing.lowest_bottom < o_.floor - 2.0 * r * o_.pores.overlap_tolerance) {
    std::ostringstream details;
    details.precision(6);
    details << "spheres reach below --floor " << o_.floor << " (lowest sphere bottom " << packing.lowest_bottom
            << "): is the floor right?";
    warn("below floor", where(frame, frame.first_line), details.str());
  }
  if (region.hi[2] > packing.hi[2] - o_.region.surface_gap_over_radius * r + 1e-9 * r) {
    std::ostringstream details;
    details.precision(6);
    const double below = (packing.hi[2] - region.hi[2]) / r;
    details << "the selection reaches z = " << region.hi[2] << ", ";
    if (below > 0) details << "only " << below << " R below";
    else details << -below << " R above";
    details << " the free surface h_s = " << packing.hi[2] << " (--surface-gap " << o_.region.surface_gap_over_radius
            << " R): pores near and above the free surface are larger than those of the bulk";
    warn("surface", where(frame, frame.first_line), details.str());
  }
}

// The merge tolerance of a frame (in R) without --merge-tol: kMergeTolerance, or more when the
// dump's digits round the coordinates coarser (pores_config.h, kMergeRoundingFactor).
double merge_tolerance_for(const Frame& frame, double radius) {
  if (frame.coordinate_digits <= 0) return config::kMergeTolerance;
  double largest = 0.0;
  for (const double v : frame.xyz) largest = std::max(largest, std::abs(v));
  for (int d = 0; d < 3; ++d) largest = std::max({largest, std::abs(frame.box.lo[d]), std::abs(frame.box.hi[d])});
  if (!(largest > 0.0)) return config::kMergeTolerance;
  const double half_unit = 0.5 * std::pow(10.0, std::floor(std::log10(largest)) + 1 - frame.coordinate_digits);
  return std::min(std::max(config::kMergeTolerance, config::kMergeRoundingFactor * half_unit / radius),
                  config::kMaxMergeTolerance);
}

std::unique_ptr<Tessellation> PoreRun::tessellate(const Frame& frame, const Selection& selection) const {
  PoreOptions pore_options = o_.pores;
  pore_options.radius = selection.radius;
  if (!o_.merge_tolerance_given) pore_options.merge_tolerance = merge_tolerance_for(frame, selection.radius);
  pore_options.focus_lo = selection.region.lo;  // wider paddings only for pores that are analysed
  pore_options.focus_hi = selection.region.hi;
  try {
    return std::make_unique<Tessellation>(frame.box, frame.xyz, frame.ids, pore_options);
  } catch (const OverlapError& e) {
    throw InputError(overlap_message(frame, e));
  } catch (const std::exception& e) {
    throw InputError(where(frame, frame.first_line) + e.what());
  }
}

// A selection without pores, with many unresolved pores, or with many beyond --xi-max.
void PoreRun::warn_about_pores(const Frame& frame, const Region& region, const PoreResult& result,
                               const PoreStatistics& s) {
  std::ostringstream details;
  details.precision(3);
  if (s.pores == 0 && result.unresolved_in_focus == 0) {
    details << "no pore in the selection " << region_text(region) << " (check --x/--y/--z, --floor, --radii)";
    warn("no pores", where(frame, frame.first_line), details.str());
  } else if (static_cast<double>(result.unresolved_in_focus) >
             config::kUnresolvedWarningFraction * static_cast<double>(s.pores + result.unresolved_in_focus)) {
    details << result.unresolved_in_focus << " of the " << s.pores + result.unresolved_in_focus
            << " pores centred in the selection " << region_text(region)
            << " are unresolved (empty spheres wider than the padding " << result.padding
            << ", left out): the selection reaches beyond the packing (open space above a free surface?), "
               "or raise --padding";
    warn("unresolved", where(frame, frame.first_line), details.str());
  } else if (static_cast<double>(s.xi.overflow()) > config::kOverflowWarningFraction * static_cast<double>(s.pores)) {
    details << s.xi.overflow() << " of the " << s.pores << " selected pores (" << 100.0 * s.xi.overflow() / s.pores
            << " %) have xi >= --xi-max " << o_.histogram.xi_max << " (counted in the normalisation, not in "
            << "the histogram): the selection " << region_text(region)
            << " reaches open space (a free surface or a wall?), or raise --xi-max";
    warn("overflow", where(frame, frame.first_line), details.str());
  }
}

void PoreRun::analyse_frame(const Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  const Selection selection = select(frame);
  const Region& region = selection.region;
  warn_about_packing(frame, selection);
  const std::unique_ptr<Tessellation> tessellation = tessellate(frame, selection);
  const PoreResult& result = tessellation->result();
  FrameSummary summary;
  summary.file = frame.source;
  summary.frame = frame.index;
  summary.timestep = frame.timestep;
  summary.atoms = frame.size();
  summary.radius = selection.radius;
  summary.pores = result.pore_count;
  summary.tetrahedra = result.tetrahedra;
  summary.unresolved = result.unresolved;
  summary.region_volume = region.volume();
  summary.tetrahedra_volume = result.tetrahedra_volume;
  summary.stats = PoreStatistics(o_.histogram);
  tessellation->for_each_pore([&](const Pore& pore) {
    const bool selected = region.contains(pore.centre);
    if (selected) summary.stats.add(pore);
    if (pores_csv_)
      *pores_csv_ << csv_text(frame.source) << "," << frame.index << "," << frame.timestep << "," << pore.centre[0] << ","
                  << pore.centre[1] << "," << pore.centre[2] << "," << pore.xi << "," << pore.ids[0] << ","
                  << pore.ids[1] << "," << pore.ids[2] << "," << pore.ids[3] << "," << pore.tetrahedra << ","
                  << pore.volume << "," << (selected ? 1 : 0) << "\n";
  });
  warn_about_pores(frame, region, result, summary.stats);
  if (o_.p0_samples > 0) {
    P0Statistics p0(o_.sigma_max, o_.sigma_steps);
    const auto points = random_points(region, o_.p0_samples, o_.seed, analysed_);
    for (double d : tessellation->nearest_centre_distances(points)) p0.add_distance(d / selection.radius);
    summary.phi_p0 = p0.phi();
    p0_total_.merge(p0);
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  total_.merge(summary.stats);
  write_frame(frame, summary, region, result);
  if (!o_.json) summary.stats = PoreStatistics(HistogramSpec{1.0, 1});  // keep memory flat
  summaries_.push_back(std::move(summary));
  ++analysed_;
}

// The frame's line of PREFIX.frames.csv, its histograms (--frame-hist) and its progress line.
void PoreRun::write_frame(const Frame& frame, const FrameSummary& summary, const Region& region,
                          const PoreResult& result) {
  const PoreStatistics& s = summary.stats;
  *frames_csv_ << csv_text(frame.source) << "," << frame.index << "," << frame.timestep << "," << summary.atoms << ","
               << csv_number(summary.radius) << "," << summary.pores << "," << summary.tetrahedra << ","
               << summary.unresolved << "," << s.pores << "," << s.degenerate << "," << csv_number(s.nu()) << ","
               << csv_number(s.mean_xi()) << "," << csv_number(summary.region_volume) << ","
               << csv_number(summary.tetrahedra_volume) << "," << csv_number(summary.phi_p0) << ","
               << csv_number(summary.seconds) << "\n";
  if (frame_hist_csv_) {
    std::ostringstream row;
    row << csv_text(frame.source) << "," << frame.index << "," << frame.timestep << ",";
    write_histogram_rows(*frame_hist_csv_, s, row.str());
  }
  if (!o_.quiet)
    err_ << "tapmc-pores: " << frame.source << " frame " << frame.index << " (timestep " << frame.timestep << "): "
         << summary.atoms << " spheres, " << summary.pores << " pores, " << s.pores << " selected in z ["
         << csv_number(region.lo[2]) << ", " << csv_number(region.hi[2]) << "), nu = " << csv_number(s.nu()) << " ("
         << std::setprecision(3) << summary.seconds << " s: Delaunay " << result.triangulation_seconds << " s, pores "
         << result.pore_seconds << " s, " << result.attempts << " triangulation(s))\n";
}

void PoreRun::write_p0_csv() {
  std::ofstream& p0_csv = output(".p0.csv");
  const double phi = p0_total_.phi();
  p0_csv << "# tapmc-pores: " << p0_total_.samples << " random points, phi seen by the points = " << csv_number(phi)
         << "\nsigma,P0_measured,P0_percus_yevick\n";
  for (std::size_t k = 0; k < p0_total_.steps(); ++k)
    p0_csv << csv_number(p0_total_.sigma(k)) << "," << csv_number(p0_total_.p0(k)) << ","
           << (phi > 0 && phi < 1 ? csv_number(gotoh_p0(p0_total_.sigma(k), phi)) : "") << "\n";
}

void PoreRun::finish() {
  if (analysed_ == 0) throw InputError("no frame analysed (check --skip/--every and the files)");
  std::ofstream& hist_csv = output(".hist.csv");
  hist_csv << "# tapmc-pores: " << analysed_ << " frames, " << total_.pores << " selected pores, nu = "
           << csv_number(total_.nu()) << ", xi below range " << total_.xi.underflow() << ", above "
           << total_.xi.overflow() << "\n"
           << kHistogramColumns << "\n";
  write_histogram_rows(hist_csv, total_, "");
  if (o_.p0_samples > 0) write_p0_csv();
  if (o_.json)
    write_json(output(".json"), analysed_, total_, summaries_, o_.frame_hist, o_.p0_samples > 0 ? &p0_total_ : nullptr);
  std::string written;
  for (const auto& file : outputs_) file->check_destination();
  for (const auto& file : outputs_) {
    file->commit();
    written += (written.empty() ? "" : ", ") + file->path();
  }
  for (const auto& [kind, warning] : warnings_)
    err_ << "tapmc-pores: warning: " << warning.first_frame
         << (warning.frames > 1 ? " (and in " + std::to_string(warning.frames - 1) + " more of the " +
                                      std::to_string(analysed_) + " frames)"
                                : std::string())
         << "\n";
  if (!o_.quiet)
    err_ << "tapmc-pores: " << analysed_ << " frames, " << total_.pores << " selected pores, nu = "
         << csv_number(total_.nu()) << "; wrote " << written << "\n";
}

}  // namespace

void run_cli(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
  const Options o = parse(arguments);
  if (o.help) {
    out << usage_text();
    return;
  }
  if (o.version) {
    out << "tapmc-pores " << TAPMC_VERSION << "\n";
    return;
  }
  PoreRun run(o, err);
  for (const std::string& path : o.files) run.analyse_file(path);
  run.finish();
}

}  // namespace pores
}  // namespace tapmc
