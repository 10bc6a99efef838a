// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Reader of LAMMPS text dumps (dump custom / dump atom, plain or gzip), one frame at a time.
#ifndef TAPMC_PORES_DUMP_READER_H
#define TAPMC_PORES_DUMP_READER_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "tapmc_pores/errors.h"

namespace tapmc {
namespace pores {

// Orthogonal simulation box; periodic[d] from the dump header's boundary flags ("pp pp fm").
struct Box {
  std::array<double, 3> lo{{0.0, 0.0, 0.0}};
  std::array<double, 3> hi{{1.0, 1.0, 1.0}};
  std::array<bool, 3> periodic{{true, true, true}};
  double length(int dim) const { return hi[dim] - lo[dim]; }
  double volume() const { return length(0) * length(1) * length(2); }
};

// One frame. Centres are in box coordinates, wrapped into [lo, hi) along periodic directions
// (whatever the dump's coordinate style: x, xu, xs or xsu).
struct Frame {
  std::string source;               // file name (or the name given to from_memory)
  std::size_t index = 0;            // 1-based frame number within the source
  std::size_t first_line = 0;       // line of the frame's first ITEM
  std::size_t first_atom_line = 0;  // line of the first atom; atom i is on first_atom_line + i
  long long timestep = 0;
  Box box;
  std::vector<std::int64_t> ids;    // atom ids (1..N when the dump has no id column)
  std::vector<double> xyz;          // 3 N centre coordinates
  std::vector<double> radius;       // N radii, empty when the dump has no radius/diameter column
  int coordinate_digits = 0;        // significant digits the coordinates were written with
                                    // (>= config::kLeastDumpDigits; 0: not read from text)
  std::size_t size() const { return ids.size(); }
};

// An input error, with the place where it was found (file, frame, line; 0 when unknown; the
// frame's timestep once read). The message starts "FILE:LINE: frame N (timestep T): ", the form
// of every located message of the tool.
class DumpError : public InputError {
 public:
  DumpError(const std::string& file, std::size_t frame, std::size_t line, const std::string& what,
            std::optional<long long> timestep = std::nullopt);
  const std::string& file() const { return file_; }
  std::size_t frame() const { return frame_; }
  std::size_t line() const { return line_; }
  const std::optional<long long>& timestep() const { return timestep_; }

 private:
  std::string file_;
  std::size_t frame_;
  std::size_t line_;
  std::optional<long long> timestep_;
};

struct ReaderOptions {
  // Overrides the header's boundary flags (needed for old dumps without them); unset: use them.
  bool override_periodic = false;
  std::array<bool, 3> periodic{{true, true, true}};
};

class ByteSource;  // gzip/plain file or memory block (dump_reader.cpp)

class DumpReader {
 public:
  // Opens a plain or gzip-compressed dump (detected from the content, not from the name).
  static DumpReader open(const std::string& path, const ReaderOptions& options = {});
  // Reads a dump held in memory (tests, fuzzing).
  static DumpReader from_memory(std::string data, const std::string& name,
                                const ReaderOptions& options = {});

  DumpReader(DumpReader&&) noexcept;
  DumpReader& operator=(DumpReader&&) noexcept;
  ~DumpReader();

  // Reads the next frame into `frame`; false at the end of the input. Throws DumpError on any
  // malformed, truncated or physically invalid frame (never returns a partial frame), on an
  // input without any frame (empty or blank) and on a last line without its newline.
  bool next(Frame& frame);

  struct Columns;  // where id, centre and radius sit in an atom line (defined in dump_reader.cpp)

 private:
  DumpReader(std::unique_ptr<ByteSource> source, std::string name, const ReaderOptions& options);
  bool next_line(std::string_view& line);
  [[noreturn]] void fail(std::size_t line, const std::string& what) const;
  // The steps of next(), each reading one item of the frame.
  std::string_view value_line(const char* item, std::vector<std::string_view>& fields);
  long long read_integer(const char* item, const char* refusal, long long minimum);
  void read_box(std::string_view item, std::string_view flags_text, Box& box);
  void read_atoms(std::string_view names_text, std::size_t count, Frame& frame);
  void read_atom(const std::vector<std::string_view>& fields, const Columns& columns, std::size_t i,
                 Frame& frame) const;
  double field_number(std::string_view field, const char* role) const;
  double place(double value, int d, bool scaled, const Frame& frame) const;
  void check_unique_ids(const Frame& frame) const;

  std::unique_ptr<ByteSource> source_;
  std::string name_;
  ReaderOptions options_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
  std::size_t line_number_ = 0;
  std::size_t frames_read_ = 0;
  long long current_timestep_ = 0;
  bool have_timestep_ = false;
};

}  // namespace pores
}  // namespace tapmc

#endif
