// libFuzzer target: the checkpoint reader on arbitrary bytes (docs/input.md, "Fuzzing"). The
// bytes are written to a temporary file and read as a restart reads a checkpoint; any input
// must end in upgrain::Error naming the file, or in a checkpoint.
//
// A checkpoint's checksum block (dem/io/checksum_block.h) refuses almost every changed file
// before the HDF5 library parses it, which would leave the readers behind it unexplored. So
// the first byte chooses: odd, the rest is the whole file (the checksum's own check); even,
// the rest is the file after its block, and the harness writes a block that matches it, as if
// the file had been written so (the HDF5 library and the readers of every part).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/run/checkpoint.h"
#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/io/checksum_block.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace io = upgrain::dem::io;
  static const std::string path = "/tmp/upgrain-fuzz-checkpoint-" + std::to_string(::getpid()) + ".h5";
  if (size == 0) return 0;
  const bool stamped = data[0] % 2 == 0;
  std::vector<unsigned char> bytes(stamped ? io::kChecksumBlockBytes : 0, 0);
  bytes.insert(bytes.end(), data + 1, data + size);
  try {
    if (stamped) io::stamp_checksum(bytes);
    io::write_bytes(path, bytes.data(), bytes.size(), path);
    (void)upgrain::coupling::read_checkpoint(path);
  } catch (const upgrain::Error&) {
  }
  return 0;
}
