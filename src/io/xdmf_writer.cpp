#include "src/io/xdmf_writer.hpp"

#include <fmt/format.h>

namespace mpsolid {

namespace {
std::string data_item(const std::string& h5_file, const std::string& group,
                      const std::string& dataset, const std::string& shape,
                      const XdmfField& field) {
  const std::string dims =
      field.components == 1 ? shape : fmt::format("{} {}", shape, field.components);
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}/{}"
      "</DataItem>",
      dims, field.number_type, field.precision, h5_file, group, dataset);
}
}  // namespace

std::string xdmf_document(const std::string& h5_file, std::size_t particles,
                          const std::vector<XdmfFrame>& frames,
                          const std::vector<XdmfField>& fields, const XdmfGasGrid& gas,
                          const std::vector<XdmfField>& gas_fields, int dimension) {
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n"
      " <Domain>\n"
      "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const XdmfField position{"position", "Float", 8, dimension};
  for (const XdmfFrame& frame : frames) {
    out += fmt::format("   <Grid Name=\"{}\" GridType=\"Uniform\">\n", frame.group);
    out += fmt::format("    <Time Value=\"{:.17g}\"/>\n", frame.time);
    out += fmt::format(
        "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
        "NodesPerElement=\"1\"/>\n",
        particles);
    out += fmt::format(
        "    <Geometry GeometryType=\"{}\">\n     {}\n    </Geometry>\n",
        dimension == 3 ? "XYZ" : "XY",
        data_item(h5_file, frame.group, "position", std::to_string(particles), position));
    for (const XdmfField& field : fields)
      out += fmt::format(
          "    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n     {}\n"
          "    </Attribute>\n",
          field.name, field.components == 1 ? "Scalar" : "Vector",
          data_item(h5_file, frame.group, field.name, std::to_string(particles), field));
    out += "   </Grid>\n";
  }
  out += "  </Grid>\n";
  if (gas.nx > 0) {
    // Cell fields (nx ny values, x fastest, as stored) on a 2D
    // co-rectilinear mesh of (ny + 1) x (nx + 1) nodes; XDMF lists the
    // slower axis (y) first.
    const std::string cells = std::to_string(static_cast<long long>(gas.nx) * gas.ny);
    out += "  <Grid Name=\"gas\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const XdmfFrame& frame : frames) {
      out += fmt::format("   <Grid Name=\"gas {}\" GridType=\"Uniform\">\n", frame.group);
      out += fmt::format("    <Time Value=\"{:.17g}\"/>\n", frame.time);
      out += fmt::format("    <Topology TopologyType=\"2DCoRectMesh\" Dimensions=\"{} {}\"/>\n",
                         gas.ny + 1, gas.nx + 1);
      out += fmt::format(
          "    <Geometry GeometryType=\"ORIGIN_DXDY\">\n"
          "     <DataItem Dimensions=\"2\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"XML\">{:.17g} {:.17g}</DataItem>\n"
          "     <DataItem Dimensions=\"2\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"XML\">{:.17g} {:.17g}</DataItem>\n"
          "    </Geometry>\n",
          gas.y0, gas.x0, gas.h, gas.h);
      for (const XdmfField& field : gas_fields)
        out += fmt::format(
            "    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Cell\">\n     {}\n"
            "    </Attribute>\n",
            field.name.substr(field.name.rfind("gas_") == 0 ? 4 : 0),
            field.components == 1 ? "Scalar" : "Vector",
            data_item(h5_file, frame.group, field.name, cells, field));
      out += "   </Grid>\n";
    }
    out += "  </Grid>\n";
  }
  out +=
      " </Domain>\n"
      "</Xdmf>\n";
  return out;
}

}  // namespace mpsolid
