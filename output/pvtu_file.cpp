#include "output/pvtu_file.h"

#include <bit>
#include <sstream>

#include "output/atomic_file.h"

namespace kerf {
namespace {

// The pieces are written by vtkXMLUnstructuredGridWriter with doubles only.
void declare_fields(std::ostream& out, const char* section, const std::vector<OutputField>& fields) {
  out << "    <" << section;
  for (const OutputField& f : fields)
    if (f.name == "displacement") out << " Vectors=\"displacement\"";
  out << ">\n";
  for (const OutputField& f : fields)
    out << "      <PDataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.components
        << "\"/>\n";
  out << "    </" << section << ">\n";
}

}  // namespace

void write_pvtu(const BodySnapshot& layout, const std::vector<std::string>& pieces, const std::string& path) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\""
      << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian") << "\">\n"
      << "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  declare_fields(out, "PPointData", layout.point_fields);
  declare_fields(out, "PCellData", layout.cell_fields);
  out << "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& piece : pieces) out << "    <Piece Source=\"" << piece << "\"/>\n";
  out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomically(path, out.str());
}

}  // namespace kerf
