#include "src/io/xdmf_writer.hpp"

#include <fmt/format.h>

namespace mpsolid {

namespace {
std::string data_item(const std::string& h5_file, const std::string& group,
                      const std::string& dataset, std::size_t particles, const XdmfField& field) {
  const std::string dims = field.components == 1
                               ? fmt::format("{}", particles)
                               : fmt::format("{} {}", particles, field.components);
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}/{}"
      "</DataItem>",
      dims, field.number_type, field.precision, h5_file, group, dataset);
}
}  // namespace

std::string xdmf_document(const std::string& h5_file, std::size_t particles,
                          const std::vector<XdmfFrame>& frames,
                          const std::vector<XdmfField>& fields) {
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n"
      " <Domain>\n"
      "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const XdmfField position{"position", "Float", 8, 2};
  for (const XdmfFrame& frame : frames) {
    out += fmt::format("   <Grid Name=\"{}\" GridType=\"Uniform\">\n", frame.group);
    out += fmt::format("    <Time Value=\"{:.17g}\"/>\n", frame.time);
    out += fmt::format(
        "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
        "NodesPerElement=\"1\"/>\n",
        particles);
    out += fmt::format("    <Geometry GeometryType=\"XY\">\n     {}\n    </Geometry>\n",
                       data_item(h5_file, frame.group, "position", particles, position));
    for (const XdmfField& field : fields)
      out += fmt::format(
          "    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n     {}\n"
          "    </Attribute>\n",
          field.name, field.components == 1 ? "Scalar" : "Vector",
          data_item(h5_file, frame.group, field.name, particles, field));
    out += "   </Grid>\n";
  }
  out +=
      "  </Grid>\n"
      " </Domain>\n"
      "</Xdmf>\n";
  return out;
}

}  // namespace mpsolid
