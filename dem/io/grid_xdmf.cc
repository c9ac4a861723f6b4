#include "dem/io/grid_xdmf.h"

#include <sstream>

#include "dem/files/atomic_file.h"

namespace upgrain::dem::io {

void write_grid_xdmf(const std::filesystem::path& path, const std::string& collection,
                     const std::vector<GridXdmfStep>& steps) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"" << collection << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const GridXdmfStep& e : steps) {
    const RegularGrid& g = e.grid;
    const Vec3 h = (g.hi - g.lo).cwiseQuotient(Vec3(g.n[0], g.n[1], g.n[2]));
    x << "   <Grid Name=\"step_" << e.step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << e.time << "\"/>\n"
      << "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << g.n[2] + 1 << " " << g.n[1] + 1 << " "
      << g.n[0] + 1 << "\"/>\n"
      << "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">" << g.lo.z()
      << " " << g.lo.y() << " " << g.lo.x() << "</DataItem>\n"
      << "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">" << h.z()
      << " " << h.y() << " " << h.x() << "</DataItem>\n"
      << "    </Geometry>\n";
    for (const CellAttribute& a : e.attributes) {
      x << "    <Attribute Name=\"" << a.name << "\" AttributeType=\"" << a.kind << "\" Center=\"Cell\">"
        << "<DataItem Dimensions=\"" << g.n[2] << " " << g.n[1] << " " << g.n[0];
      if (a.components > 1) x << " " << a.components;
      x << "\" NumberType=\"" << a.number_type << "\" Precision=\"" << a.precision << "\" Format=\"HDF\">"
        << e.file << ":" << a.path << "</DataItem></Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  write_text_atomically(path, x.str());
}

}  // namespace upgrain::dem::io
