#include "coupling/studies/femxdem/cell_choice.h"

#include <algorithm>
#include <cstdlib>
#include <string_view>

#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

bool whole_number(std::string_view s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos && s.size() < 10;
}

}  // namespace

// deal.II's cell id begins with its coarse cell's number ("20_0:").
long element_of(const std::string& cell) { return std::strtol(cell.c_str(), nullptr, 10); }

bool CellSnapshotChoice::chooses(const fem::PointPlace& place) const {
  if (all) return true;
  for (const auto& [element, point] : points)
    if (element == element_of(place.cell) && point == place.index) return true;
  return false;
}

CellSnapshotChoice parse_cell_snapshots(const std::string& entry) {
  CellSnapshotChoice c;
  std::string items;
  for (const char ch : entry)
    if (ch != ' ' && ch != '\t') items += ch;
  if (items.empty()) return c;
  if (items == "all") {
    c.all = true;
    return c;
  }
  std::size_t from = 0;
  while (from <= items.size()) {
    const std::size_t end = std::min(items.find(',', from), items.size());
    const std::string_view item = std::string_view(items).substr(from, end - from);
    const std::size_t colon = item.find(':');
    if (colon == std::string_view::npos || !whole_number(item.substr(0, colon)) ||
        !whole_number(item.substr(colon + 1)))
      throw Error("FEMxDEM/cell snapshots: '" + std::string(item) +
                  "' is not element:point (two whole numbers, as points.csv gives them), nor 'all'");
    c.points.emplace_back(std::stol(std::string(item.substr(0, colon))),
                          static_cast<unsigned>(std::stoul(std::string(item.substr(colon + 1)))));
    from = end + 1;
  }
  return c;
}

}  // namespace upgrain::coupling
