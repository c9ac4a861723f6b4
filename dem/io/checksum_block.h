#pragma once
// A checksum of an HDF5 file's bytes, kept in the file's first kChecksumBlockBytes: an HDF5
// user block, which the library reserves for the application and skips (H5Pset_userblock).
// A checkpoint is stamped before its bytes are written under their temporary name
// (atomic_file.h); a restart verifies it before the HDF5 library parses a byte, so a file cut
// short, a flipped bit on disk or a patched byte is refused with its file name and the next
// older checkpoint is used (docs/restart.md).
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

namespace upgrain::dem::io {

inline constexpr hsize_t kChecksumBlockBytes = 512;

// Fills the first kChecksumBlockBytes of `image` (a file's bytes, made with that user block)
// with the checksum of the rest.
void stamp_checksum(std::vector<unsigned char>& image);

// Throws upgrain::Error "<kind> <file>: ..." when the block is missing or the bytes after it
// do not match it.
void verify_checksum(const std::filesystem::path& file, const std::string& kind);

}  // namespace upgrain::dem::io
