// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// libFuzzer target: arbitrary bytes through the dump reader must give frames or DumpError only
// (no crash, no hang, no sanitizer report); an input without any frame (empty, blank) must be a
// DumpError too, and every DumpError names the file. Built with clang when available (tests/pores).
#include <cstddef>
#include <cstdint>
#include <string>

#include "tapmc_pores/dump_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The first byte picks the periodicity override (old dumps without boundary flags).
  tapmc::pores::ReaderOptions options;
  if (size > 0 && (data[0] & 1)) {
    options.override_periodic = true;
    options.periodic = {bool(data[0] & 2), bool(data[0] & 4), bool(data[0] & 8)};
  }
  try {
    auto reader = tapmc::pores::DumpReader::from_memory(std::string(reinterpret_cast<const char*>(data), size),
                                                        "fuzz.dump", options);
    tapmc::pores::Frame frame;
    int frames = 0;
    for (; frames < 64 && reader.next(frame); ++frames) {
      if (frame.xyz.size() != 3 * frame.ids.size()) __builtin_trap();
      if (!frame.radius.empty() && frame.radius.size() != frame.ids.size()) __builtin_trap();
      for (int d = 0; d < 3; ++d)
        if (!(frame.box.hi[d] > frame.box.lo[d])) __builtin_trap();
    }
    if (frames == 0) __builtin_trap();  // a dump without a frame ended cleanly: it must be named
  } catch (const tapmc::pores::DumpError& error) {
    if (error.file() != "fuzz.dump" || std::string(error.what()).rfind("fuzz.dump:", 0) != 0) __builtin_trap();
  }
  return 0;
}
