// XDMF sidecar text generation and the in-place append that keeps the file complete after each
// step.
#include "output/xdmf_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "output/hdf5_io.hpp"
#include "output/results_layout.hpp"

namespace cc {

namespace {

constexpr const char* kHeader =
    "<?xml version=\"1.0\" ?>\n"
    "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
    "  <Domain>\n"
    "    <Grid Name=\"CovContact\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
constexpr const char* kFooter =
    "    </Grid>\n"
    "  </Domain>\n"
    "</Xdmf>\n";

constexpr int kDoublePrecision = 8;  // bytes, XDMF "Precision"
constexpr int kIntPrecision = 4;

std::string escapeXml(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string formatDouble(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string attributeOpen(const std::string& name, const char* type, const char* center) {
  return "          <Attribute Name=\"" + name + "\" AttributeType=\"" + type + "\" Center=\"" +
         center + "\">\n";
}

constexpr const char* kAttributeClose = "          </Attribute>\n";

}  // namespace

XdmfWriter::XdmfWriter(std::string xdmfPath, std::string h5FileName, long numNodes,
                       long numElements, std::vector<XdmfBlock> blocks, size_t atomicRewriteLimit)
    : path_(std::move(xdmfPath)),
      h5FileName_(std::move(h5FileName)),
      numNodes_(numNodes),
      numElements_(numElements),
      blocks_(std::move(blocks)),
      atomicRewriteLimit_(atomicRewriteLimit),
      footerOffset_(std::strlen(kHeader)) {
  replaceFile();
}

void XdmfWriter::appendStep(const XdmfStep& step) {
  std::string grid = "      <Grid Name=\"step " + layout::stepGroupName(step.step) +
                     "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n" +
                     "        <Time Value=\"" + formatDouble(step.time) + "\"/>\n";
  for (const XdmfBlock& block : blocks_)
    if (block.numElements > 0) grid += blockGrid(block, step);
  for (const auto& [pair, points] : step.contactPairs)
    if (points > 0) grid += contactGrid(pair, points, step);
  grid += "      </Grid>\n";
  if (footerOffset_ + grid.size() + std::strlen(kFooter) <= atomicRewriteLimit_) {
    steps_ += grid;
    replaceFile();
  } else {
    steps_.clear();  // no longer needed: the file itself holds the steps from now on
    appendInPlace(grid);
  }
  footerOffset_ += grid.size();
}

std::string XdmfWriter::dataItem(const std::string& dims, const char* numberType, int precision,
                                 const std::string& h5Path) const {
  return "            <DataItem Dimensions=\"" + dims + "\" NumberType=\"" + numberType +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" +
         escapeXml(h5FileName_ + ":" + h5Path) + "</DataItem>\n";
}

std::string XdmfWriter::blockGrid(const XdmfBlock& block, const XdmfStep& step) const {
  const std::string stepPath = layout::stepGroupPath(step.step) + "/";
  const std::string nodeDims = std::to_string(numNodes_) + " 3";
  const std::string elements = std::to_string(block.numElements);
  std::string grid = "        <Grid Name=\"" + escapeXml(block.name) + "\" GridType=\"Uniform\">\n";
  grid += "          <Topology TopologyType=\"" + block.topology + "\" NumberOfElements=\"" +
          elements + "\">\n";
  grid += dataItem(elements + " " + std::to_string(block.nodesPerCell), "Int", kIntPrecision,
                   block.connectivityPath);
  grid += "          </Topology>\n          <Geometry GeometryType=\"XYZ\">\n";
  grid += dataItem(nodeDims, "Float", kDoublePrecision, layout::kCoordinates);
  grid += "          </Geometry>\n";
  for (const auto& [present, field] : {std::pair{step.displacement, layout::kDisplacement},
                                       std::pair{step.reaction, layout::kReaction}}) {
    if (!present) continue;
    grid += attributeOpen(field, "Vector", "Node");
    grid += dataItem(nodeDims, "Float", kDoublePrecision, stepPath + field);
    grid += kAttributeClose;
  }
  if (step.stress) {
    // One stress table holds all blocks; Xdmf3's inline hyperslab "path|start:stride:count:dims"
    // picks this block's rows (the XML HyperSlab item is not read by ParaView's Xdmf3 reader).
    // Xdmf3 passes Tensor6 to VTK unchanged, whose symmetric tensor order XX YY ZZ XY YZ XZ is our
    // Voigt order.
    const std::string components = " " + std::to_string(layout::kStressComponents);
    std::string source = stepPath + layout::kStress;
    if (block.numElements != numElements_)
      source += "|" + std::to_string(block.firstElement) + " 0:1 1:" + elements + components + ":" +
                std::to_string(numElements_) + components;
    grid += attributeOpen(layout::kStress, "Tensor6", "Cell");
    grid += dataItem(elements + components, "Float", kDoublePrecision, source);
    grid += kAttributeClose;
  }
  return grid + "        </Grid>\n";
}

std::string XdmfWriter::contactGrid(const std::string& pair, long points,
                                    const XdmfStep& step) const {
  const std::string pairPath = layout::stepGroupPath(step.step) + "/" + layout::kContactGroup +
                               "/" + layout::linkName(pair) + "/";
  const std::string count = std::to_string(points);
  std::string grid = "        <Grid Name=\"contact " + escapeXml(pair) +
                     "\" GridType=\"Uniform\">\n" +
                     "          <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + count +
                     "\" NodesPerElement=\"1\">\n";
  // Without explicit vertex ids the Xdmf3 reader creates the points but no cells to draw.
  grid += dataItem(count, "Int", kIntPrecision, pairPath + layout::kVertexIds);
  grid += "          </Topology>\n          <Geometry GeometryType=\"XYZ\">\n";
  grid += dataItem(count + " 3", "Float", kDoublePrecision, pairPath + "position");
  grid += "          </Geometry>\n";
  struct PointField {
    const char* name;
    const char* type;
    bool integer;
    int components;
  };
  for (const PointField& field :
       {PointField{"gap", "Scalar", false, 1}, PointField{"normal_traction", "Scalar", false, 1},
        PointField{"tangential_traction", "Vector", false, 3},
        PointField{"state", "Scalar", true, 1}, PointField{"accumulated_slip", "Scalar", false, 1},
        PointField{"edge_share", "Scalar", false, 1}}) {
    const std::string dims = field.components == 1 ? count : count + " 3";
    grid += attributeOpen(field.name, field.type, "Node");
    grid += field.integer ? dataItem(dims, "Int", kIntPrecision, pairPath + field.name)
                          : dataItem(dims, "Float", kDoublePrecision, pairPath + field.name);
    grid += kAttributeClose;
  }
  return grid + "        </Grid>\n";
}

void XdmfWriter::appendInPlace(const std::string& grid) {
  const std::string text = grid + kFooter;
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw OutputError("cannot open XDMF file '" + path_ + "': " + std::strerror(errno));
  const ssize_t written = ::pwrite(fd, text.data(), text.size(), static_cast<off_t>(footerOffset_));
  const int writeError = errno;
  ::close(fd);
  if (written != static_cast<ssize_t>(text.size()))
    throw OutputError("cannot write XDMF file '" + path_ +
                      "': " + (written < 0 ? std::strerror(writeError) : "short write"));
}

void XdmfWriter::replaceFile() const {
  const std::string text = kHeader + steps_ + kFooter;
  const std::string temporary = path_ + ".tmp";
  const auto fail = [&](const std::string& operation, const std::string& file) {
    throw OutputError("cannot " + operation + " XDMF file '" + file + "': " + std::strerror(errno));
  };
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail("create", temporary);
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t count = ::write(fd, text.data() + written, text.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      ::close(fd);
      fail("write", temporary);
    }
    written += static_cast<size_t>(count);
  }
  if (::close(fd) != 0) fail("write", temporary);
  if (std::rename(temporary.c_str(), path_.c_str()) != 0) fail("replace", path_);
}

}  // namespace cc
