#pragma once
// A first pass over a parameter file, before deal.II reads it: checks the structure
// (subsection/end balance, 'set name = value' lines) and that every entry exists, so an
// unknown entry is reported with its file and line and the list of entries that do exist; a
// subsection opened twice or an entry set twice is refused with both lines, and a file that
// sets nothing is refused (docs/input.md).
#include <string>

namespace upgrain::coupling {

// Throws upgrain::Error "<file>:<line>: ..." on the first problem.
void check_prm_syntax(const std::string& text, const std::string& filename);

}  // namespace upgrain::coupling
