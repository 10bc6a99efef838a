// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Dump reader: column orders, coordinate styles, gzip, many frames, and every bad input refused
// with the file, frame and line in the message.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "tapmc_pores/dump_reader.h"

namespace {

using tapmc::pores::DumpError;
using tapmc::pores::DumpReader;
using tapmc::pores::Frame;

std::string frame_text(long step, const std::string& bounds_flags, const std::string& columns,
                       const std::vector<std::string>& atoms, const std::string& bounds = "0 4\n0 4\n0 4\n") {
  std::string s = "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF ATOMS\n" + std::to_string(atoms.size()) +
                  "\nITEM: BOX BOUNDS " + bounds_flags + "\n" + bounds + "ITEM: ATOMS " + columns + "\n";
  for (const auto& a : atoms) s += a + "\n";
  return s;
}

Frame read_one(const std::string& text) {
  DumpReader reader = DumpReader::from_memory(text, "mem.dump");
  Frame f;
  EXPECT_TRUE(reader.next(f));
  return f;
}

// The message must name the file, the frame and the expected line.
void expect_error(const std::string& text, std::size_t line, const std::string& fragment) {
  DumpReader reader = DumpReader::from_memory(text, "bad.dump");
  Frame f;
  try {
    while (reader.next(f)) {
    }
    ADD_FAILURE() << "no error for input containing: " << fragment;
  } catch (const DumpError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), line) << what;
    EXPECT_NE(what.find("bad.dump:" + std::to_string(line)), std::string::npos) << what;
    EXPECT_NE(what.find("frame "), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(PoreDumpReader, AnyColumnOrderAndRadius) {
  const Frame f = read_one(frame_text(7, "pp pp ff", "radius z type y id x",
                                      {"0.5 1.5 1 2.5 10 3.5", "0.5 3 1 1 4 0.5"}));
  EXPECT_EQ(f.timestep, 7);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.ids[0], 10);
  EXPECT_EQ(f.ids[1], 4);
  EXPECT_DOUBLE_EQ(f.xyz[0], 3.5);
  EXPECT_DOUBLE_EQ(f.xyz[1], 2.5);
  EXPECT_DOUBLE_EQ(f.xyz[2], 1.5);
  EXPECT_EQ(f.radius, (std::vector<double>{0.5, 0.5}));
  EXPECT_TRUE(f.box.periodic[0] && f.box.periodic[1] && !f.box.periodic[2]);
  EXPECT_EQ(f.first_atom_line, 10u);
}

TEST(PoreDumpReader, CoordinateStylesAreWrappedIntoThePeriodicBox) {
  // Box [-2, 2]^3: scaled 0.75 -> 1; unwrapped 5 -> 1 (periodic); scaled unwrapped 1.25 -> -1.
  for (const auto& [columns, line] : std::vector<std::pair<std::string, std::string>>{
           {"id xs ys zs", "1 0.75 0.75 0.75"}, {"id xu yu zu", "1 5 5 5"}, {"id xsu ysu zsu", "1 0.75 1.75 -0.25"}}) {
    const Frame f = read_one(frame_text(0, "pp pp pp", columns, {line}, "-2 2\n-2 2\n-2 2\n"));
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(f.xyz[d], 1.0, 1e-12) << columns;
  }
  const Frame d = read_one(frame_text(0, "pp pp pp", "id x y z diameter", {"1 1 1 1 2.0"}));
  EXPECT_EQ(d.radius, std::vector<double>{1.0});
}

TEST(PoreDumpReader, ManyFramesTimeUnitsAndOldDumpAtom) {
  std::string text = "ITEM: UNITS\nlj\nITEM: TIME\n0.5\n" + frame_text(0, "pp pp pp", "id type x y z", {"1 1 1 1 1"}) +
                     "\n" + frame_text(100, "pp pp pp", "id type x y z", {"1 1 2 2 2", "2 1 3 3 3"});
  // Old 'dump atom' without column names and without boundary flags (periodicity given).
  text += "ITEM: TIMESTEP\n200\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS\n0 4\n0 4\n0 4\nITEM: ATOMS\n1 1 0.5 0.5 0.5\n";
  tapmc::pores::ReaderOptions options;
  options.override_periodic = true;
  DumpReader reader = DumpReader::from_memory(text, "multi.dump", options);
  Frame f;
  std::vector<long long> steps;
  while (reader.next(f)) steps.push_back(f.timestep);
  EXPECT_EQ(steps, (std::vector<long long>{0, 100, 200}));
  EXPECT_DOUBLE_EQ(f.xyz[0], 2.0);  // scaled 0.5 in [0, 4]
  EXPECT_EQ(f.index, 3u);
}

TEST(PoreDumpReader, GzipAndPlainFilesReadAlike) {
  const std::string text = frame_text(5, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 2 2"}) +
                           frame_text(6, "pp pp pp", "id x y z", {"1 1 1 1", "2 3 2 2"});
  const std::string plain = ::testing::TempDir() + "pores_plain.dump", packed = ::testing::TempDir() + "pores_packed.dump.gz";
  {
    FILE* out = std::fopen(plain.c_str(), "w");
    std::fwrite(text.data(), 1, text.size(), out);
    std::fclose(out);
    gzFile gz = gzopen(packed.c_str(), "wb");
    gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
    gzclose(gz);
  }
  for (const std::string& path : {plain, packed}) {
    DumpReader reader = DumpReader::open(path);
    Frame f;
    std::vector<double> x;
    while (reader.next(f)) x.push_back(f.xyz[3]);
    EXPECT_EQ(x, (std::vector<double>{2.0, 3.0})) << path;
  }
  EXPECT_THROW(DumpReader::open(::testing::TempDir() + "no_such_file.dump"), DumpError);
  std::remove(plain.c_str());
  std::remove(packed.c_str());
}

TEST(PoreDumpReader, ACutGzipFileIsNamedWhereItsDataEnds) {
  // A gzip file cut short (a copy or a run stopped mid-write): the frames before the cut are
  // read, and the error names the frame and line where the data ends (it said line 1, frame 1).
  std::string text;
  for (int step = 0; step < 40; ++step) {
    std::vector<std::string> atoms;
    for (int i = 1; i <= 50; ++i)
      atoms.push_back(std::to_string(i) + " " + std::to_string(i % 7) + ".25 " + std::to_string(i / 7) + ".5 " +
                      std::to_string(step) + ".75");
    text += frame_text(step, "pp pp pp", "id x y z", atoms, "0 8\n0 8\n0 48\n");
  }
  const std::string whole = ::testing::TempDir() + "pores_whole.dump.gz", cut = ::testing::TempDir() + "pores_cut.dump.gz";
  gzFile gz = gzopen(whole.c_str(), "wb");
  gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
  gzclose(gz);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  DumpReader reader = DumpReader::open(cut);
  Frame f;
  std::size_t frames = 0;
  try {
    while (reader.next(f)) ++frames;
    ADD_FAILURE() << "a cut gzip file was read to its end";
  } catch (const DumpError& e) {
    EXPECT_NE(std::string(e.what()).find("decompression error"), std::string::npos) << e.what();
    EXPECT_GT(frames, 0u) << e.what();
    EXPECT_LT(frames, 40u);
    EXPECT_GT(e.line(), 59 * frames) << e.what();  // 59 lines a frame: past the frames read
  }
  std::remove(whole.c_str());
  std::remove(cut.c_str());
}

TEST(PoreDumpReader, BadInputNamesFileFrameAndLine) {
  const std::string good = frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 2 2"});
  // Truncated frame: 3 atoms announced, 2 present (the file ends).
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 2 2"}).replace(39, 1, "3"), 11, "truncated");
  // Truncated frame followed by the next frame.
  expect_error(good.substr(0, good.size() - 8) + good, 11, "truncated");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 abc 2"}), 11, "non-numeric");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 nan 2"}), 11, "non-finite");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 inf 2"}), 11, "non-finite");
  expect_error(frame_text(0, "pp pp pp", "id type x y", {"1 1 1 1"}), 9, "no z coordinate");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {}), 4, "zero atoms");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "1 2 2 2"}), 11, "duplicate atom id 1");
  expect_error(frame_text(0, "pp pp ff", "id x y z", {"1 1 1 1", "2 2 2 4.5"}), 11, "outside the non-periodic box");
  expect_error(frame_text(0, "xy xz yz pp pp pp", "id x y z", {"1 1 1 1"}, "0 4 0\n0 4 0\n0 4 0\n"), 5, "triclinic");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1"}, "0 4 0.5\n0 4 0\n0 4 0\n"), 6, "triclinic");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 2"}), 11, "fields");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1.5 1 1 1"}), 10, "atom id");
  expect_error(frame_text(0, "pp pp pp", "id x y z radius", {"1 1 1 1 -0.5"}), 10, "radius must be positive");
  expect_error(frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1"}, "0 4\n4 0\n0 4\n"), 7, "lo < hi");
  expect_error("ITEM: TIMESTEP\nten\n", 2, "timestep");
  expect_error("ITEM: TIMESTEP\n", 1, "file ends");
  expect_error("garbage\n", 1, "expected an 'ITEM:'");
  expect_error(good + "ITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n", 14, "file ends");
  expect_error(good + "ITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n1\n", 15, "before 'ITEM: ATOMS'");
  expect_error("ITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS\n0 1\n0 1\n0 1\n", 5, "--boundary");
}

TEST(PoreDumpReader, ErrorsReportTheFrameNumber) {
  const std::string good = frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1"});
  DumpReader reader = DumpReader::from_memory(good + good + frame_text(20, "pp pp pp", "id x y z", {"1 1 x 1"}), "f.dump");
  Frame f;
  try {
    while (reader.next(f)) {
    }
    FAIL();
  } catch (const DumpError& e) {
    EXPECT_EQ(e.frame(), 3u);
    EXPECT_EQ(e.line(), 30u);
    // "FILE:LINE: frame N (timestep T): ", as the tool's other located messages (this used to
    // be "FILE:LINE: frame N: (timestep T) ").
    EXPECT_EQ(std::string(e.what()), "f.dump:30: frame 3 (timestep 20): non-numeric coordinate field 'x'");
    EXPECT_EQ(e.timestep(), std::optional<long long>(20));
  }
  // Before the frame's TIMESTEP item the timestep is unknown: "frame N: " alone.
  try {
    DumpReader early = DumpReader::from_memory(good + "garbage\n", "g.dump");
    while (early.next(f)) {
    }
    FAIL();
  } catch (const DumpError& e) {
    EXPECT_EQ(std::string(e.what()), "g.dump:11: frame 2: expected an 'ITEM:' line, found 'garbage'");
    EXPECT_FALSE(e.timestep().has_value());
  }
}

TEST(PoreDumpReader, RadiusAndDiameterColumnsMustAgree) {
  // Both columns: the radius is used, so a diameter that is not twice it is refused (it was
  // accepted silently), naming the atom and both values as written.
  const std::string columns = "id x y z radius diameter";
  expect_error(frame_text(0, "pp pp pp", columns, {"1 1 1 1 0.5 1", "7 3 3 3 0.5 1.2"}), 11,
               "frame 1 (timestep 0): atom 7: the radius and diameter columns disagree: radius 0.5, diameter 1.2 "
               "(|diameter - 2 radius| / diameter = 0.167, allowed range [0, 2e-05])");
  expect_error(frame_text(0, "pp pp pp", "diameter radius id x y z", {"0.5 0.5 3 1 1 1"}), 10,
               "atom 3: the radius and diameter columns disagree: radius 0.5, diameter 0.5 ");
  expect_error(frame_text(0, "pp pp pp", columns, {"1 1 1 1 0.5 0"}), 10, "radius 0.5, diameter 0 (");
  expect_error(frame_text(0, "pp pp pp", columns, {"1 1 1 1 0.5 nan"}), 10, "non-finite diameter value 'nan'");
  // Agreement up to the rounding of 6 printed digits (LAMMPS's %g) is accepted.
  const Frame f = read_one(frame_text(0, "pp pp pp", columns, {"1 1 1 1 0.333333 0.666667", "2 3 3 3 0.5 1"}));
  EXPECT_EQ(f.radius, (std::vector<double>{0.333333, 0.5}));
}

// The message of a DumpError raised at the first frame, or "" when the input reads cleanly.
std::string first_error(DumpReader reader) {
  Frame f;
  try {
    while (reader.next(f)) {
    }
  } catch (const DumpError& e) {
    return e.what();
  }
  return "";
}

TEST(PoreDumpReader, AnEmptyDumpIsNamedAsSuch) {
  // Empty input was a clean end of the dump: the tool then said only "no frame analysed".
  EXPECT_EQ(first_error(DumpReader::from_memory("", "empty.dump")), "empty.dump: empty file (no dump frame)");
  EXPECT_EQ(first_error(DumpReader::from_memory("\n  \n\t", "blank.dump")),
            "blank.dump: no dump frame: the file holds only blank lines");
  // The same from files, plain and gzip-compressed (an empty gzip stream is not an empty file).
  const std::string plain = ::testing::TempDir() + "pores_empty.dump", packed = ::testing::TempDir() + "pores_empty.dump.gz";
  std::fclose(std::fopen(plain.c_str(), "w"));
  gzclose(gzopen(packed.c_str(), "wb"));
  EXPECT_EQ(first_error(DumpReader::open(plain)), plain + ": empty file (no dump frame)");
  EXPECT_EQ(first_error(DumpReader::open(packed)), packed + ": empty file (no dump frame)");
  std::remove(plain.c_str());
  std::remove(packed.c_str());
  // After a frame, the end of the input (even after blank lines) still ends the dump cleanly.
  const std::string good = frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1"});
  EXPECT_EQ(first_error(DumpReader::from_memory(good + "\n  \n", "ok.dump")), "");
}

TEST(PoreDumpReader, ALastLineWithoutNewlineIsRefused) {
  // A run killed while writing the dump: "2 2 2 2.5" cut to "2 2 2 2" would still parse.
  const std::string good = frame_text(0, "pp pp pp", "id x y z", {"1 1 1 1", "2 2 2 2"});
  expect_error(good.substr(0, good.size() - 1), 11, "no newline");
  expect_error(good + "ITEM: TIME", 12, "no newline");
  EXPECT_EQ(first_error(DumpReader::from_memory(good + "  ", "spaces.dump")), "");
}

}  // namespace
