// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// LAMMPS text dump reader: items, column roles, coordinate styles, wrapping, input validation.
#include "tapmc_pores/dump_reader.h"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "tapmc_math.h"
#include "tapmc_pores/pores_config.h"

namespace tapmc {
namespace pores {

DumpError::DumpError(const std::string& file, std::size_t frame, std::size_t line,
                     const std::string& what, std::optional<long long> timestep)
    : InputError([&] {
        std::ostringstream out;
        out << file;
        if (line > 0) out << ":" << line;
        out << ": ";
        if (frame > 0) {
          out << "frame " << frame;
          if (timestep) out << " (timestep " << *timestep << ")";
          out << ": ";
        }
        out << what;
        return out.str();
      }()),
      file_(file),
      frame_(frame),
      line_(line),
      timestep_(timestep) {}

// ---- byte sources ---------------------------------------------------------------------------
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Fills up to n bytes; returns the count (0 at the end). Throws std::runtime_error on I/O error.
  virtual std::size_t read(char* destination, std::size_t n) = 0;
};

namespace {

class GzipFileSource : public ByteSource {
 public:
  explicit GzipFileSource(const std::string& path) : file_(gzopen(path.c_str(), "rb")) {
    if (!file_) throw DumpError(path, 0, 0, std::string("cannot open: ") + std::strerror(errno));
    gzbuffer(file_, 1 << 17);
  }
  ~GzipFileSource() override { gzclose(file_); }
  std::size_t read(char* destination, std::size_t n) override {
    if (!pending_error_.empty()) throw std::runtime_error(pending_error_);
    const int count = gzread(file_, destination, static_cast<unsigned>(std::min<std::size_t>(n, 1u << 30)));
    int code = Z_OK;
    const char* message = gzerror(file_, &code);
    if (count < 0 || (code != Z_OK && code != Z_STREAM_END)) {
      // A cut file (Z_BUF_ERROR) still yields what came before the cut: those bytes are read
      // first, so that the error names the line where the data ends, not line 1.
      const std::string error = std::string("read/decompression error: ") + message;
      if (count <= 0) throw std::runtime_error(error);
      pending_error_ = error;
    }
    return static_cast<std::size_t>(count);
  }

 private:
  gzFile file_;
  std::string pending_error_;  // the error that ended the last read, given at the next one
};

class MemorySource : public ByteSource {
 public:
  explicit MemorySource(std::string data) : data_(std::move(data)) {}
  std::size_t read(char* destination, std::size_t n) override {
    const std::size_t count = std::min(n, data_.size() - position_);
    std::memcpy(destination, data_.data() + position_, count);
    position_ += count;
    return count;
  }

 private:
  std::string data_;
  std::size_t position_ = 0;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
}

bool blank(std::string_view line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return is_space(c); });
}

bool parse_double(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

// Significant digits of a number as written: "-1.50e+01" -> 3, "0.000123" -> 3.
int significant_digits(std::string_view text) {
  int digits = 0;
  bool leading = true;
  for (const char c : text) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;  // sign, point
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return digits;
}

bool parse_integer(std::string_view text, long long& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

std::string quoted(std::string_view text) {
  std::string shown(text.substr(0, 40));
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + shown + (text.size() > 40 ? "...'" : "'");
}

// Coordinate styles in order of preference: wrapped, unwrapped, scaled, scaled unwrapped.
enum class CoordinateStyle { kBox, kUnwrapped, kScaled, kScaledUnwrapped };

}  // namespace

struct DumpReader::Columns {
  int id = -1;
  int radius = -1;
  int diameter = -1;
  std::array<int, 3> coordinate{{-1, -1, -1}};
  std::array<CoordinateStyle, 3> style{};
  std::size_t count = 0;
};

namespace {

DumpReader::Columns assign_columns(const std::vector<std::string>& names, std::string& problem) {
  DumpReader::Columns columns;
  columns.count = names.size();
  static const char* kAxes[3] = {"x", "y", "z"};
  static const std::pair<const char*, CoordinateStyle> kSuffixes[4] = {
      {"", CoordinateStyle::kBox}, {"u", CoordinateStyle::kUnwrapped},
      {"s", CoordinateStyle::kScaled}, {"su", CoordinateStyle::kScaledUnwrapped}};
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    const std::string& name = names[c];
    if (name == "id") columns.id = c;
    if (name == "radius") columns.radius = c;
    if (name == "diameter") columns.diameter = c;
  }
  for (int d = 0; d < 3; ++d) {
    for (const auto& [suffix, style] : kSuffixes) {
      const auto it = std::find(names.begin(), names.end(), std::string(kAxes[d]) + suffix);
      if (it != names.end()) {
        columns.coordinate[d] = static_cast<int>(it - names.begin());
        columns.style[d] = style;
        break;
      }
    }
    if (columns.coordinate[d] < 0) {
      problem = std::string("no ") + kAxes[d] +
                " coordinate column (need one of x/xu/xs/xsu for each axis); the ATOMS header names:";
      for (const auto& n : names) problem += " " + n;
      return columns;
    }
  }
  return columns;
}

}  // namespace

// ---- reader ---------------------------------------------------------------------------------
DumpReader::DumpReader(std::unique_ptr<ByteSource> source, std::string name,
                       const ReaderOptions& options)
    : source_(std::move(source)), name_(std::move(name)), options_(options), buffer_(1 << 16) {}
DumpReader::DumpReader(DumpReader&&) noexcept = default;
DumpReader& DumpReader::operator=(DumpReader&&) noexcept = default;
DumpReader::~DumpReader() = default;

DumpReader DumpReader::open(const std::string& path, const ReaderOptions& options) {
  return DumpReader(std::make_unique<GzipFileSource>(path), path, options);
}

DumpReader DumpReader::from_memory(std::string data, const std::string& name,
                                   const ReaderOptions& options) {
  return DumpReader(std::make_unique<MemorySource>(std::move(data)), name, options);
}

void DumpReader::fail(std::size_t line, const std::string& what) const {
  throw DumpError(name_, frames_read_ + 1, line, what,
                  have_timestep_ ? std::optional<long long>(current_timestep_) : std::nullopt);
}

bool DumpReader::next_line(std::string_view& line) {
  for (;;) {
    const char* start = buffer_.data() + begin_;
    const void* newline = std::memchr(start, '\n', end_ - begin_);
    if (newline) {
      const std::size_t length = static_cast<const char*>(newline) - start;
      line = std::string_view(start, length);
      begin_ += length + 1;
      ++line_number_;
      return true;
    }
    if (eof_) {
      if (begin_ == end_) return false;
      // A last line without its newline is a write cut short (a run killed while LAMMPS wrote
      // the dump): its last number may be cut too and would still parse, so it is refused.
      const std::string_view rest(start, end_ - begin_);
      begin_ = end_;
      ++line_number_;
      if (blank(rest)) return false;
      fail(line_number_, "the file ends inside this line (no newline): cut short while being written?");
    }
    // Move the partial line to the front, grow if one line fills the buffer, then refill.
    std::memmove(buffer_.data(), start, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    std::size_t count = 0;
    try {
      count = source_->read(buffer_.data() + end_, buffer_.size() - end_);
    } catch (const std::runtime_error& error) {
      fail(line_number_ + 1, error.what());
    }
    if (count == 0) eof_ = true;
    end_ += count;
  }
}

// The value line after 'ITEM: <item>', split into `fields`.
std::string_view DumpReader::value_line(const char* item, std::vector<std::string_view>& fields) {
  std::string_view line;
  if (!next_line(line)) fail(line_number_, std::string("file ends after 'ITEM: ") + item + "'");
  split_fields(line, fields);
  return line;
}

// The one integer of the value line of 'ITEM: <item>', refused below `minimum` with `refusal`.
long long DumpReader::read_integer(const char* item, const char* refusal, long long minimum) {
  std::vector<std::string_view> fields;
  const std::string_view line = value_line(item, fields);
  long long value = 0;
  if (fields.size() != 1 || !parse_integer(fields[0], value) || value < minimum)
    fail(line_number_, refusal + quoted(line));
  return value;
}

// 'ITEM: BOX BOUNDS <flags>' (`flags_text`) and its three lines 'lo hi'.
void DumpReader::read_box(std::string_view item, std::string_view flags_text, Box& box) {
  std::vector<std::string_view> flags;
  split_fields(flags_text, flags);
  if (!flags.empty() && (flags[0] == "xy" || flags[0] == "xz" || flags[0] == "yz"))
    fail(line_number_, "triclinic box ('" + std::string(item) + "'): tapmc-pores handles orthogonal boxes only");
  std::array<bool, 3> periodic{{true, true, true}};
  if (flags.size() == 3) {
    for (int d = 0; d < 3; ++d) {
      const std::string_view f = flags[d];
      const bool valid = f.size() == 2 && std::string_view("pfsm").find(f[0]) != std::string_view::npos &&
                         std::string_view("pfsm").find(f[1]) != std::string_view::npos &&
                         ((f[0] == 'p') == (f[1] == 'p'));
      if (!valid) fail(line_number_, "invalid boundary flag " + quoted(f) + " (expected pp, ff, fs, sm, ...)");
      periodic[d] = f[0] == 'p';
    }
  } else if (!flags.empty()) {
    fail(line_number_, "BOX BOUNDS carries " + std::to_string(flags.size()) +
                           " boundary flags, expected 3 (e.g. 'pp pp fm')");
  } else if (!options_.override_periodic) {
    fail(line_number_, "BOX BOUNDS carries no boundary flags (old dump): give the periodicity "
                       "with --boundary, e.g. --boundary ppf");
  }
  if (options_.override_periodic) periodic = options_.periodic;
  std::vector<std::string_view> fields;
  for (int d = 0; d < 3; ++d) {
    const std::string_view line = value_line("BOX BOUNDS", fields);
    double lo = 0, hi = 0;
    if (fields.size() == 3)
      fail(line_number_, "box bounds line has a tilt factor (triclinic box): tapmc-pores handles "
                         "orthogonal boxes only");
    if (fields.size() != 2 || !parse_double(fields[0], lo) || !parse_double(fields[1], hi))
      fail(line_number_, "box bounds line must hold two numbers 'lo hi': " + quoted(line));
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
      fail(line_number_, "box bounds must be finite with lo < hi: " + quoted(line));
    box.lo[d] = lo;
    box.hi[d] = hi;
  }
  box.periodic = periodic;
}

// 'ITEM: ATOMS <names>' (`names_text`) and its `count` atom lines; old 'dump atom' files name no
// columns and are recognised by their number of fields.
void DumpReader::read_atoms(std::string_view names_text, std::size_t count, Frame& frame) {
  std::vector<std::string> names;
  {
    std::vector<std::string_view> views;
    split_fields(names_text, views);
    for (auto v : views) names.emplace_back(v);
  }
  const std::size_t header_line = line_number_;
  frame.first_atom_line = line_number_ + 1;
  frame.ids.reserve(std::min<std::size_t>(count, 1u << 22));
  frame.xyz.reserve(3 * std::min<std::size_t>(count, 1u << 22));
  Columns columns;
  bool columns_known = false;
  auto set_columns = [&](const std::vector<std::string>& column_names) {
    std::string problem;
    columns = assign_columns(column_names, problem);
    if (!problem.empty()) fail(header_line, problem);
    columns_known = true;
  };
  if (!names.empty()) set_columns(names);
  std::string_view line;
  std::vector<std::string_view> fields;
  for (std::size_t i = 0; i < count; ++i) {
    if (!next_line(line))
      fail(line_number_, "truncated frame: expected " + std::to_string(count) + " atom lines, the file ends after " +
                             std::to_string(i));
    split_fields(line, fields);
    if (!columns_known) {
      // Old 'dump atom' without column names: id type xs ys zs [ix iy iz].
      if (fields.size() == 5) set_columns({"id", "type", "xs", "ys", "zs"});
      else if (fields.size() == 8) set_columns({"id", "type", "xs", "ys", "zs", "ix", "iy", "iz"});
      else fail(header_line, "'ITEM: ATOMS' names no columns and the lines do not look like 'dump atom'");
    }
    if (fields.size() != columns.count) {
      if (!fields.empty() && fields[0].substr(0, 5) == "ITEM:")
        fail(line_number_, "truncated frame: expected " + std::to_string(count) + " atom lines, found " +
                               std::to_string(i) + " before the next ITEM");
      fail(line_number_, "atom line has " + std::to_string(fields.size()) + " fields, the ATOMS header names " +
                             std::to_string(columns.count));
    }
    read_atom(fields, columns, i, frame);
  }
}

double DumpReader::field_number(std::string_view field, const char* role) const {
  double value = 0;
  if (!parse_double(field, value)) fail(line_number_, std::string("non-numeric ") + role + " field " + quoted(field));
  if (!std::isfinite(value)) fail(line_number_, std::string("non-finite ") + role + " value " + quoted(field));
  return value;
}

// One atom line: its id (i + 1 without an id column), its centre in the box, its radius.
void DumpReader::read_atom(const std::vector<std::string_view>& fields, const Columns& columns, std::size_t i,
                           Frame& frame) const {
  if (columns.id >= 0) {
    long long id = 0;
    if (!parse_integer(fields[columns.id], id)) fail(line_number_, "atom id is not an integer: " + quoted(fields[columns.id]));
    frame.ids.push_back(id);
  } else {
    frame.ids.push_back(static_cast<std::int64_t>(i + 1));
  }
  for (int d = 0; d < 3; ++d) {
    const CoordinateStyle style = columns.style[d];
    const bool scaled = style == CoordinateStyle::kScaled || style == CoordinateStyle::kScaledUnwrapped;
    const std::string_view field = fields[columns.coordinate[d]];
    frame.xyz.push_back(place(field_number(field, "coordinate"), d, scaled, frame));
    if (i < config::kDigitsSample)
      frame.coordinate_digits = std::max({frame.coordinate_digits, config::kLeastDumpDigits,
                                          significant_digits(field)});
  }
  if (columns.radius >= 0) frame.radius.push_back(field_number(fields[columns.radius], "radius"));
  else if (columns.diameter >= 0) frame.radius.push_back(0.5 * field_number(fields[columns.diameter], "diameter"));
  if (!frame.radius.empty() && !(frame.radius.back() > 0))
    fail(line_number_, "radius must be positive, found " + message_number(frame.radius.back()));
  // With both columns the radius is used: a diameter that is not twice it means the dump does
  // not say which size the spheres have.
  if (columns.radius >= 0 && columns.diameter >= 0) {
    const double diameter = field_number(fields[columns.diameter], "diameter"), radius = frame.radius.back();
    const double mismatch = std::abs(diameter - 2.0 * radius) / std::abs(diameter);
    if (!(mismatch <= config::kRadiusDiameterTolerance)) {
      std::ostringstream what;
      what.precision(3);
      what << "atom " << frame.ids.back() << ": the radius and diameter columns disagree: radius "
           << fields[columns.radius] << ", diameter " << fields[columns.diameter] << " (|diameter - 2 radius| / diameter = "
           << mismatch << ", allowed range [0, " << config::kRadiusDiameterTolerance << "])";
      fail(line_number_, what.str());
    }
  }
}

// Coordinate `value` along `d` in box units: wrapped into a periodic box, checked against the
// faces of a non-periodic one (the atom is the last one read).
double DumpReader::place(double value, int d, bool scaled, const Frame& frame) const {
  const double lo = frame.box.lo[d], length = frame.box.length(d);
  if (scaled) value = lo + value * length;
  if (!std::isfinite(value))
    fail(line_number_, "atom " + std::to_string(frame.ids.back()) + " has a scaled coordinate along " + "xyz"[d] +
                           " beyond the double range");
  if (frame.box.periodic[d]) {
    value = wrap_periodic(value, lo, frame.box.hi[d]);
  } else {
    const double slack = config::kBoxTolerance * length;
    if (value < lo - slack || value > frame.box.hi[d] + slack) {
      std::ostringstream what;
      what.precision(17);
      what << "atom " << frame.ids.back() << " lies outside the non-periodic box along " << "xyz"[d] << ": " << value
           << " not in [" << lo << ", " << frame.box.hi[d] << "]";
      fail(line_number_, what.str());
    }
  }
  return value;
}

// Duplicate ids: sort a copy (O(N log N), negligible next to the triangulation).
void DumpReader::check_unique_ids(const Frame& frame) const {
  std::vector<std::int64_t> sorted(frame.ids);
  std::sort(sorted.begin(), sorted.end());
  const auto duplicate = std::adjacent_find(sorted.begin(), sorted.end());
  if (duplicate == sorted.end()) return;
  const std::size_t at = std::find(frame.ids.begin(), frame.ids.end(), *duplicate) - frame.ids.begin();
  const std::size_t again = std::find(frame.ids.begin() + at + 1, frame.ids.end(), *duplicate) - frame.ids.begin();
  fail(frame.first_atom_line + again, "duplicate atom id " + std::to_string(*duplicate) + " (first on line " +
                                          std::to_string(frame.first_atom_line + at) + ")");
}

bool DumpReader::next(Frame& frame) {
  std::string_view line;
  have_timestep_ = false;

  // Skip blank lines before the frame; a clean end of input here ends the dump, unless no frame
  // came before: an empty dump is named as such rather than found later as "no frame analysed".
  do {
    if (!next_line(line)) {
      if (frames_read_ > 0) return false;
      throw DumpError(name_, 0, 0, line_number_ == 0 ? "empty file (no dump frame)"
                                                     : "no dump frame: the file holds only blank lines");
    }
  } while (blank(line));

  frame.source = name_;
  frame.index = frames_read_ + 1;
  frame.first_line = line_number_;
  frame.timestep = 0;
  frame.ids.clear();
  frame.xyz.clear();
  frame.radius.clear();
  frame.coordinate_digits = 0;

  long long atom_count = -1;
  bool have_box = false;
  for (;;) {
    if (line.substr(0, 6) != "ITEM: ") fail(line_number_, "expected an 'ITEM:' line, found " + quoted(line));
    const std::string_view item = line.substr(6);
    if (item.substr(0, 8) == "TIMESTEP") {
      frame.timestep = current_timestep_ =
          read_integer("TIMESTEP", "timestep is not an integer: ", std::numeric_limits<long long>::min());
      have_timestep_ = true;
    } else if (item.substr(0, 4) == "TIME" || item.substr(0, 5) == "UNITS") {
      std::vector<std::string_view> fields;
      value_line("TIME/UNITS", fields);  // informational items written by dump_modify time/units
    } else if (item.substr(0, 15) == "NUMBER OF ATOMS") {
      atom_count = read_integer("NUMBER OF ATOMS", "number of atoms is not a non-negative integer: ", 0);
      if (atom_count == 0) fail(line_number_, "the frame has zero atoms (nothing to analyse)");
    } else if (item.substr(0, 10) == "BOX BOUNDS") {
      read_box(item, item.substr(10), frame.box);
      have_box = true;
    } else if (item.substr(0, 5) == "ATOMS") {
      if (atom_count < 0) fail(line_number_, "'ITEM: ATOMS' before 'ITEM: NUMBER OF ATOMS'");
      if (!have_box) fail(line_number_, "'ITEM: ATOMS' before 'ITEM: BOX BOUNDS'");
      read_atoms(item.substr(5), static_cast<std::size_t>(atom_count), frame);
      check_unique_ids(frame);
      ++frames_read_;
      return true;
    } else {
      fail(line_number_, "unknown item " + quoted(line));
    }
    // Next item of this frame.
    do {
      if (!next_line(line)) fail(line_number_, "truncated frame: the file ends before 'ITEM: ATOMS'");
    } while (blank(line));
  }
}

}  // namespace pores
}  // namespace tapmc
