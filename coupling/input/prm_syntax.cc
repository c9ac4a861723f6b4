#include "coupling/input/prm_syntax.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "coupling/input/scene_sections.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Collapses runs of blanks, as deal.II does for names.
std::string normalise(const std::string& s) {
  std::string out;
  bool blank = false;
  for (char c : trim(s)) {
    if (c == ' ' || c == '\t') {
      blank = true;
      continue;
    }
    if (blank && !out.empty()) out += ' ';
    blank = false;
    out += c;
  }
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (std::size_t k = 0; k < v.size(); ++k) out += (k ? "', '" : "'") + v[k];
  return out + "'";
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw Error(file + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

void check_prm_syntax(const std::string& text, const std::string& filename) {
  std::istringstream in(text);
  std::string raw, line;
  std::vector<std::string> stack;
  int line_no = 0, start_line = 0;
  // Where each subsection was opened and each entry set: deal.II would let the last value
  // win without a word, so a second one is refused with both lines.
  std::map<std::string, int> opened, set_at;
  while (std::getline(in, raw)) {
    ++line_no;
    if (line.empty()) start_line = line_no;
    // Comments start at '#' (deal.II has no escape for it in values).
    const auto hash = raw.find('#');
    std::string part = hash == std::string::npos ? raw : raw.substr(0, hash);
    part = trim(part);
    if (!part.empty() && part.back() == '\\') {  // continuation line
      line += part.substr(0, part.size() - 1) + " ";
      continue;
    }
    line += part;
    const std::string l = normalise(line);
    line.clear();
    if (l.empty()) continue;
    std::istringstream words(l);
    std::string keyword;
    words >> keyword;
    if (keyword == "subsection") {
      const std::string name = normalise(l.substr(keyword.size()));
      if (!stack.empty())
        fail(filename, start_line,
             "subsection '" + name + "' inside '" + stack.back() +
                 "': Upgrain's parameter files have one level of subsections");
      const auto known = input::section_names();
      if (std::find(known.begin(), known.end(), name) == known.end())
        fail(filename, start_line, "unknown subsection '" + name + "'; the subsections are " + join(known));
      if (const auto [first, fresh] = opened.emplace(name, start_line); !fresh)
        fail(filename, start_line,
             "subsection '" + name + "' again (first at line " + std::to_string(first->second) +
                 "): put its entries in one subsection");
      stack.push_back(name);
    } else if (keyword == "end") {
      if (l != "end") fail(filename, start_line, "malformed line '" + l + "': 'end' stands alone");
      if (stack.empty()) fail(filename, start_line, "'end' without a matching 'subsection'");
      stack.pop_back();
    } else if (keyword == "set") {
      const auto eq = l.find('=');
      if (eq == std::string::npos)
        fail(filename, start_line, "malformed line '" + l + "': expected 'set <name> = <value>'");
      const std::string name = normalise(l.substr(3, eq - 3));
      if (name.empty()) fail(filename, start_line, "malformed line '" + l + "': the entry has no name");
      if (stack.empty())
        fail(filename, start_line,
             "entry '" + name + "' outside any subsection; the subsections are " +
                 join(input::section_names()));
      const auto known = input::entry_names(stack.back());
      if (std::find(known.begin(), known.end(), name) == known.end())
        fail(filename, start_line,
             "unknown entry '" + name + "' in subsection '" + stack.back() + "'; its entries are " +
                 join(known));
      const std::string key = stack.back() + "/" + name;
      if (const auto [first, fresh] = set_at.emplace(key, start_line); !fresh)
        fail(filename, start_line,
             key + " is set again (first at line " + std::to_string(first->second) +
                 "); keep one of the two lines");
    } else {
      fail(filename, start_line, "malformed line '" + l + "': expected 'subsection', 'set' or 'end'");
    }
  }
  if (!line.empty()) fail(filename, start_line, "the file ends inside a continued line");
  if (!stack.empty())
    fail(filename, line_no,
         "subsection '" + stack.back() + "' is not closed by 'end' before the end of the file");
  if (set_at.empty())
    throw Error(filename +
                ": sets no parameter (the file is empty, or holds only comments and subsections); run "
                "upgrain without a file for the built-in default scene, or start from "
                "'upgrain --print-parameters'");
}

}  // namespace upgrain::coupling
