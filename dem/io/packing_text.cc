// Text packings: a table (CSV or whitespace) with optional header, and LAMMPS/LIGGGHTS data
// files (docs/input.md, "Starting from a packing"). Every error names the file, the line and,
// for a value, its column (the 1-based character position where the field starts).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "dem/core/error.h"
#include "dem/io/packing_file.h"

namespace upgrain::dem::io {

namespace {

struct Field {
  std::string text;
  int column = 1;  // 1-based character position of the field's first character
};

struct Line {
  long number = 0;
  std::vector<Field> fields;
  std::string raw;  // the line as written, without its line end
};

// The fields of a line: comma-separated when it holds a comma, else whitespace-separated.
// Surrounding whitespace is not part of a field; '#' starts a comment.
std::vector<Field> split(const std::string& raw) {
  std::string s = raw.substr(0, raw.find('#'));
  std::vector<Field> out;
  const bool csv = s.find(',') != std::string::npos;
  std::size_t i = 0;
  while (i <= s.size()) {
    if (csv) {
      std::size_t end = s.find(',', i);
      if (end == std::string::npos) end = s.size();
      std::size_t b = i, e = end;
      while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
      while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
      out.push_back({s.substr(b, e - b), static_cast<int>(b) + 1});
      i = end + 1;
    } else {
      while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
      if (i >= s.size()) break;
      std::size_t e = i;
      while (e < s.size() && !std::isspace(static_cast<unsigned char>(s[e]))) ++e;
      out.push_back({s.substr(i, e - i), static_cast<int>(i) + 1});
      i = e;
    }
  }
  // A line of only spaces (or a comment) in a CSV file is one empty field: no fields.
  if (out.size() == 1 && out[0].text.empty()) out.clear();
  return out;
}

std::vector<Line> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("packing " + path.string() + ": cannot open the file");
  std::vector<Line> lines;
  std::string s;
  long number = 0;
  while (std::getline(in, s)) {
    ++number;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    if (number == 1 && s.rfind("\xEF\xBB\xBF", 0) == 0) s.erase(0, 3);  // a UTF-8 byte-order mark
    lines.push_back({number, split(s), s});
  }
  // A read that fails (an I/O error) is not the file's end: its grains would be missing.
  if (in.bad())
    throw Error("packing " + path.string() + ": cannot read the file after line " + std::to_string(number));
  return lines;
}

std::string at(const std::filesystem::path& path, long line, int column = 0) {
  return "packing " + path.string() + ":" + std::to_string(line) +
         (column > 0 ? ":" + std::to_string(column) : "") + ": ";
}

std::optional<double> number(const std::string& t) {
  double v = 0.0;
  const char* end = t.data() + t.size();
  const char* begin = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
  const auto r = std::from_chars(begin, end, v);
  if (t.empty() || r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return v;
}

double number_at(const std::filesystem::path& path, long line, const Field& f, const std::string& column) {
  const std::optional<double> v = number(f.text);
  if (!v)
    throw Error(at(path, line, f.column) + "'" + f.text + "' in column '" + column + "' is not a number");
  if (!std::isfinite(*v))
    throw Error(at(path, line, f.column) + "'" + f.text + "' in column '" + column + "' is not finite");
  return *v;
}

long whole_at(const std::filesystem::path& path, long line, const Field& f, const std::string& column) {
  const double v = number_at(path, line, f, column);
  if (v != std::floor(v) || std::abs(v) > 9007199254740992.0)
    throw Error(at(path, line, f.column) + "'" + f.text + "' in column '" + column +
                "' is not a whole number");
  return static_cast<long>(v);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The columns a table may have, with the names they may go by.
const std::vector<std::pair<std::string, std::vector<std::string>>>& known_columns() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> k = {
      {"id", {"id"}},           {"x", {"x"}},   {"y", {"y"}},   {"z", {"z"}},   {"r", {"r", "radius"}},
      {"d", {"d", "diameter"}}, {"a", {"a"}},   {"b", {"b"}},   {"c", {"c"}},   {"qw", {"qw"}},
      {"qx", {"qx"}},           {"qy", {"qy"}}, {"qz", {"qz"}}, {"vx", {"vx"}}, {"vy", {"vy"}},
      {"vz", {"vz"}},           {"wx", {"wx"}}, {"wy", {"wy"}}, {"wz", {"wz"}},
  };
  return k;
}

std::string known_list() {
  std::string s;
  for (const auto& [name, aliases] : known_columns())
    for (const std::string& a : aliases) s += (s.empty() ? "" : ", ") + a;
  return s;
}

}  // namespace

std::vector<PackedGrain> read_text_table(const std::filesystem::path& path) {
  const std::vector<Line> lines = read_lines(path);
  std::size_t first = 0;
  while (first < lines.size() && lines[first].fields.empty()) ++first;
  if (first == lines.size()) throw Error("packing " + path.string() + ": holds no grains (no line of data)");
  // The columns: from a header line (its first field is not a number), or by their count.
  std::vector<std::string> columns;
  const Line& head = lines[first];
  std::size_t data_from = first;
  if (!number(head.fields[0].text)) {
    data_from = first + 1;
    for (const Field& f : head.fields) {
      const std::string name = lower(f.text);
      std::string canonical;
      for (const auto& [c, aliases] : known_columns())
        if (std::find(aliases.begin(), aliases.end(), name) != aliases.end()) canonical = c;
      if (canonical.empty())
        throw Error(at(path, head.number, f.column) + "unknown column '" + f.text +
                    "' (known: " + known_list() + ")");
      if (std::find(columns.begin(), columns.end(), canonical) != columns.end())
        throw Error(at(path, head.number, f.column) + "column '" + f.text + "' is given twice");
      columns.push_back(canonical);
    }
  } else {
    const std::size_t n = head.fields.size();
    if (n == 5)
      columns = {"id", "x", "y", "z", "r"};
    else if (n == 7)
      columns = {"id", "x", "y", "z", "a", "b", "c"};
    else if (n == 11)
      columns = {"id", "x", "y", "z", "a", "b", "c", "qw", "qx", "qy", "qz"};
    else
      throw Error(
          at(path, head.number) + std::to_string(n) +
          " columns and no header line: without a header a table has 5 (id x y z r), 7 (id x y z a b c) "
          "or 11 (id x y z a b c qw qx qy qz); otherwise name the columns in a first line (known: " +
          known_list() + ")");
  }
  auto has = [&](const char* c) { return std::find(columns.begin(), columns.end(), c) != columns.end(); };
  auto group = [&](std::initializer_list<const char*> names, const std::string& what) {
    int given = 0;
    for (const char* c : names) given += has(c);
    if (given != 0 && given != static_cast<int>(names.size()))
      throw Error(at(path, head.number) + "the columns " + what + " go together: give all or none");
    return given != 0;
  };
  for (const char* c : {"x", "y", "z"})
    if (!has(c))
      throw Error(at(path, head.number) + "no column '" + c + "' (the header names " +
                  std::to_string(columns.size()) + " columns)");
  const bool axes = group({"a", "b", "c"}, "a, b, c");
  const bool quat = group({"qw", "qx", "qy", "qz"}, "qw, qx, qy, qz");
  group({"vx", "vy", "vz"}, "vx, vy, vz");
  group({"wx", "wy", "wz"}, "wx, wy, wz");
  if (int(has("r")) + int(has("d")) + int(axes) != 1)
    throw Error(at(path, head.number) +
                "give the size once: a radius column (r), a diameter column (d) or the semi-axes (a, b, c)");
  if (quat && !axes)
    throw Error(at(path, head.number) + "an orientation (qw, qx, qy, qz) needs the semi-axes a, b, c");

  std::vector<PackedGrain> grains;
  long next_id = 0;
  for (std::size_t k = data_from; k < lines.size(); ++k) {
    const Line& l = lines[k];
    if (l.fields.empty()) continue;
    if (l.fields.size() != columns.size())
      throw Error(at(path, l.number) + std::to_string(l.fields.size()) + " fields, but the table has " +
                  std::to_string(columns.size()) + " columns");
    PackedGrain g;
    g.line = l.number;
    g.file_id = next_id++;
    double r = 0.0;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string& name = columns[c];
      const Field& f = l.fields[c];
      if (name == "id") {
        g.file_id = whole_at(path, l.number, f, name);
        continue;
      }
      const double v = number_at(path, l.number, f, name);
      static const std::map<std::string, std::pair<int, int>> slots = {
          {"x", {0, 0}},  {"y", {0, 1}},  {"z", {0, 2}},  {"vx", {1, 0}}, {"vy", {1, 1}}, {"vz", {1, 2}},
          {"wx", {2, 0}}, {"wy", {2, 1}}, {"wz", {2, 2}}, {"a", {3, 0}},  {"b", {3, 1}},  {"c", {3, 2}}};
      if (const auto s = slots.find(name); s != slots.end()) {
        Vec3* target[] = {&g.x, &g.v, &g.omega, &g.semi_axes};
        (*target[s->second.first])[s->second.second] = v;
      } else if (name == "r") {
        r = v;
      } else if (name == "d") {
        r = 0.5 * v;
      } else if (name == "qw") {
        g.orientation.w() = v;
      } else if (name == "qx") {
        g.orientation.x() = v;
      } else if (name == "qy") {
        g.orientation.y() = v;
      } else if (name == "qz") {
        g.orientation.z() = v;
      }
    }
    if (!axes) g.semi_axes = Vec3::Constant(r);
    grains.push_back(g);
  }
  return grains;
}

bool looks_like_lammps_data(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string s;
  long count = 0;
  // The header follows the title line; a data file says its atom count there.
  while (std::getline(in, s) && ++count < 100) {
    if (count == 1) continue;
    const std::vector<Field> f = split(s);
    if (f.size() == 2 && f[1].text == "atoms" && number(f[0].text).has_value()) return true;
  }
  return false;
}

std::vector<PackedGrain> read_lammps_data(const std::filesystem::path& path, double density,
                                          std::vector<std::string>& notes, std::string& style,
                                          std::optional<Box>* box, std::array<long, 3>* box_line) {
  Box bounds;
  std::array<long, 3> bound_line{0, 0, 0};
  const std::vector<Line> lines = read_lines(path);
  long atoms = -1;
  std::size_t k = 1;  // the first line is the title
  // The header: "N atoms" and the box and counts, which the scene's container replaces.
  for (; k < lines.size(); ++k) {
    const std::vector<Field>& f = lines[k].fields;
    if (f.empty()) continue;
    if (!number(f[0].text)) break;  // the first section
    if (f.size() == 2 && f[1].text == "atoms") atoms = whole_at(path, lines[k].number, f[0], "atoms");
    // "xlo xhi" and its kin: the box, which a periodic cell must match (docs/periodic.md).
    for (int d = 0; d < 3; ++d)
      if (f.size() == 4 && f[2].text == std::string(1, "xyz"[d]) + "lo" &&
          f[3].text == std::string(1, "xyz"[d]) + "hi") {
        bounds.lo[d] = number_at(path, lines[k].number, f[0], std::string(1, "xyz"[d]) + "lo");
        bounds.hi[d] = number_at(path, lines[k].number, f[1], std::string(1, "xyz"[d]) + "hi");
        bound_line[d] = lines[k].number;
      }
  }
  if (box != nullptr && bound_line[0] > 0 && bound_line[1] > 0 && bound_line[2] > 0) *box = bounds;
  if (box_line != nullptr) *box_line = bound_line;
  if (atoms < 1)
    throw Error("packing " + path.string() + ": a LAMMPS data file without a positive 'N atoms' line");
  std::vector<PackedGrain> grains;
  std::map<long, std::size_t> by_id;
  bool density_noted = false;
  // Sections: a keyword line, a blank line, then rows until the next keyword.
  while (k < lines.size()) {
    const Line& keyword = lines[k];
    if (keyword.fields.empty()) {
      ++k;
      continue;
    }
    const std::string section = keyword.fields[0].text;
    // The raw line's comment names the atom style ("Atoms # sphere").
    std::size_t end = k + 1;
    while (end < lines.size() && (lines[end].fields.empty() || number(lines[end].fields[0].text))) ++end;
    if (section == "Atoms") {
      const std::string& raw = keyword.raw;
      const std::size_t hash = raw.find('#');
      const std::vector<Field> comment =
          hash == std::string::npos ? std::vector<Field>{} : split(raw.substr(hash + 1));
      style = comment.empty() ? "sphere" : comment[0].text;
      if (style != "sphere" && style != "granular")
        throw Error(at(path, keyword.number) + "the Atoms section is atom_style '" + style +
                    "'; Upgrain reads atom_style sphere or granular (id type diameter density x y z)");
      for (std::size_t j = k + 1; j < end; ++j) {
        const Line& l = lines[j];
        if (l.fields.empty()) continue;
        if (l.fields.size() != 7 && l.fields.size() != 10)
          throw Error(at(path, l.number) + std::to_string(l.fields.size()) +
                      " fields: an atom_style sphere line has 7 (id type diameter density x y z) or 10 (with "
                      "image flags)");
        PackedGrain g;
        g.line = l.number;
        g.file_id = whole_at(path, l.number, l.fields[0], "atom-ID");
        (void)whole_at(path, l.number, l.fields[1], "atom-type");
        g.semi_axes = Vec3::Constant(0.5 * number_at(path, l.number, l.fields[2], "diameter"));
        const double rho = number_at(path, l.number, l.fields[3], "density");
        if (!density_noted && std::abs(rho - density) > 1e-9 * density) {
          std::ostringstream m;
          m << "packing " << path.string() << ":" << l.number << ": density " << rho
            << " kg/m^3 differs from Particles/density = " << density
            << " kg/m^3; every grain takes the scene's density";
          notes.push_back(m.str());
          density_noted = true;
        }
        for (int d = 0; d < 3; ++d)
          g.x[d] = number_at(path, l.number, l.fields[4 + d], std::string(1, "xyz"[d]));
        // Image flags: kept, so that a periodic cell continues the grain's unwrapped path;
        // check_packing() refuses them along a walled axis.
        if (l.fields.size() == 10)
          for (int d = 0; d < 3; ++d) {
            const long n = whole_at(path, l.number, l.fields[7 + d], std::string("image flag ") + "xyz"[d]);
            if (n < -1000000000L || n > 1000000000L)
              throw Error(at(path, l.number, l.fields[7 + d].column) + "image flag " + "xyz"[d] + " = " +
                          std::to_string(n) + " is beyond a billion cells");
            g.image[d] = static_cast<std::int32_t>(n);
          }
        if (!by_id.emplace(g.file_id, grains.size()).second)
          throw Error(at(path, l.number) + "atom " + std::to_string(g.file_id) + " is given twice");
        grains.push_back(g);
      }
    } else if (section == "Velocities") {
      if (grains.empty())
        throw Error(at(path, keyword.number) + "the Velocities section comes before the Atoms section");
      for (std::size_t j = k + 1; j < end; ++j) {
        const Line& l = lines[j];
        if (l.fields.empty()) continue;
        if (l.fields.size() != 7)
          throw Error(at(path, l.number) + std::to_string(l.fields.size()) +
                      " fields: an atom_style sphere velocity line has 7 (id vx vy vz wx wy wz)");
        const long id = whole_at(path, l.number, l.fields[0], "atom-ID");
        const auto it = by_id.find(id);
        if (it == by_id.end())
          throw Error(at(path, l.number) + "velocity of atom " + std::to_string(id) +
                      ", which the Atoms section does not have");
        PackedGrain& g = grains[it->second];
        for (int d = 0; d < 3; ++d) {
          g.v[d] = number_at(path, l.number, l.fields[1 + d], std::string("v") + "xyz"[d]);
          g.omega[d] = number_at(path, l.number, l.fields[4 + d], std::string("w") + "xyz"[d]);
        }
      }
    }
    // Other sections (Masses, coefficients) say nothing the scene does not.
    k = end;
  }
  if (static_cast<long>(grains.size()) != atoms)
    throw Error("packing " + path.string() + ": the header says " + std::to_string(atoms) +
                " atoms, the Atoms section has " + std::to_string(grains.size()));
  return grains;
}

}  // namespace upgrain::dem::io
