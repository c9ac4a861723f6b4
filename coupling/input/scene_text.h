#pragma once
// The text of a scene file, before its syntax is checked (docs/input.md, "What is read"):
// only a regular file is opened (a FIFO without a writer blocks in open(), a device such as
// /dev/zero never ends, a folder is no file), a read error is an error, and the bytes are
// taken as UTF-8: a byte-order mark is dropped, Windows line ends are read as Unix ones, and
// bytes that are not UTF-8 (or NUL) are refused with their line.
#include <string>

namespace upgrain::coupling {

// Scene files are a few kilobytes; anything much larger is not one.
inline constexpr long kMaxSceneBytes = 1L << 20;

// The bytes of the scene file `path` (decoded by parse_scene_text); throws upgrain::Error
// naming it.
std::string read_scene_bytes(const std::string& path);

// `bytes` as scene text: the mark dropped, CR LF as LF; throws upgrain::Error "<source>:<line>:
// ..." at the first byte that is not UTF-8 or is NUL.
std::string decode_scene_text(const std::string& bytes, const std::string& source);

}  // namespace upgrain::coupling
