// Handlers of the model keywords that describe the mesh, materials, elements, boundary
// conditions, loads, output and references: each turns one parsed line into ProblemSpec items.
#include <fmt/format.h>

#include <filesystem>

#include "common/name_matching.hpp"
#include "deck/deck_state.hpp"
#include "deck/spec_choices.hpp"

namespace cc::deck {

namespace fs = std::filesystem;

namespace {

// A keyword allowed once per deck.
void requireFirst(const ParsedLine& line, std::optional<SourceLocation>& seenAt) {
  if (seenAt) {
    line.fail(line.where(),
              fmt::format("'{}' given twice (first at {})", line.keyword().name, seenAt->str()));
  }
  seenAt = line.where();
}

// Paths in a deck are relative to the file that contains them (the deck or an include).
fs::path resolveAgainstFile(const std::string& path, const std::string& containingFile) {
  const fs::path given(path);
  const fs::path joined =
      given.is_absolute() ? given : fs::path(containingFile).parent_path() / given;
  return fs::absolute(joined).lexically_normal();
}

// Function clauses named after components (ux uy uz / fx fy fz), in x, y, z order.
std::array<std::optional<FunctionSpec>, 3> componentFunctions(
    const ParsedLine& line, const std::vector<std::string>& components) {
  std::array<std::optional<FunctionSpec>, 3> functions;
  for (std::size_t i = 0; i < components.size(); ++i) {
    if (const Clause* clause = line.findClause(components[i])) functions[i] = clause->function;
  }
  if (!functions[0] && !functions[1] && !functions[2]) {
    line.fail(line.end(), fmt::format("give at least one component: {} followed by a function",
                                      joinAlternatives(components)));
  }
  return functions;
}

}  // namespace

void handleTitle(const ParsedLine& line, DeckState& state) {
  requireFirst(line, state.titleAt);
  state.spec.title = line.positional(0).text;
}

void handleMesh(const ParsedLine& line, DeckState& state) {
  requireFirst(line, state.meshAt);
  const Value& path = line.positional(0);
  const fs::path resolved = resolveAgainstFile(path.text, line.where().file);
  // What the path is, before its name is judged: a directory, device or FIFO was reported as
  // "not found" (or as having no extension).
  std::error_code error;
  const fs::file_status status = fs::status(resolved, error);
  if (fs::is_directory(status)) {
    line.fail(path.where, fmt::format("mesh file '{}' is a directory (looked for '{}'); expected a "
                                      "gmsh .msh or .geo file",
                                      path.text, resolved.string()));
  }
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    line.fail(path.where, fmt::format("mesh file '{}' is not a regular file but a device, FIFO "
                                      "or socket (looked for '{}'); expected a gmsh .msh or .geo "
                                      "file",
                                      path.text, resolved.string()));
  }
  const std::string extension = toLower(resolved.extension().string());
  if (extension != ".msh" && extension != ".geo") {
    line.fail(path.where,
              fmt::format("mesh file '{}' has {}; expected a gmsh .msh or .geo file", path.text,
                          extension.empty() ? std::string("no extension")
                                            : "an unknown extension '" + extension + "'"));
  }
  if (!fs::is_regular_file(resolved, error)) {
    line.fail(path.where, fmt::format("mesh file '{}' not found (looked for '{}')", path.text,
                                      resolved.string()));
  }
  if (extension == ".msh" && !line.extraNumbers().empty()) {
    const ExtraNumber& first = line.extraNumbers().front();
    line.fail(first.where, fmt::format("parameter '{}': NAME=VALUE parameters apply only to "
                                       ".geo meshes, '{}' is a .msh file",
                                       first.name, path.text));
  }
  MeshSpec& mesh = state.spec.mesh;
  mesh.path = resolved.string();
  for (const ExtraNumber& extra : line.extraNumbers()) mesh.parameters[extra.name] = extra.value;
  mesh.where = line.where();
}

void handleMaterial(const ParsedLine& line, DeckState& state) {
  const Value& name = line.positional(0);
  for (const MaterialSpec& earlier : state.spec.materials) {
    if (earlier.name == name.text) {
      line.fail(name.where, fmt::format("duplicate material '{}' (first defined at {})", name.text,
                                        earlier.where.str()));
    }
  }
  MaterialSpec material;
  material.name = name.text;
  material.model = choiceValue(materialModels(), line.positional(1).text);
  material.youngsModulus = line.number("E");
  material.poissonRatio = line.number("nu");
  material.where = line.where();
  state.spec.materials.push_back(material);
}

void handleElements(const ParsedLine& line, DeckState& state) {
  const Value& group = line.positional(0);
  for (const ElementBlockSpec& earlier : state.spec.elementBlocks) {
    if (earlier.group == group.text) {
      line.fail(group.where, fmt::format("group '{}' already has elements (at {})", group.text,
                                         earlier.where.str()));
    }
  }
  ElementBlockSpec block;
  block.group = group.text;
  block.type = choiceValue(elementTypes(), line.positional(1).text);
  if (block.type == ElementBlockSpec::Type::Hex8) {
    for (const char* shellOnly : {"thickness", "eas"}) {
      if (line.given(shellOnly)) {
        line.fail(
            line.value(shellOnly).where,
            fmt::format("{}= applies only to solid_shell8 and solid_shell18 elements", shellOnly));
      }
    }
  }
  block.material = line.text("material");
  block.thicknessAxis = choiceValue(thicknessAxes(), line.text("thickness"));
  block.easParameters = line.integer("eas");
  block.where = line.where();
  state.materialUses.push_back(
      {block.material, line.value("material").where, line.context(), "material", ""});
  state.spec.elementBlocks.push_back(block);
}

void handleFix(const ParsedLine& line, DeckState& state) {
  FixSpec fix;
  fix.set = line.positional(0).text;
  const bool all = line.findClause("all") != nullptr;
  for (std::size_t i = 0; i < kDisplacementComponents.size(); ++i) {
    fix.components[i] = all || line.findClause(kDisplacementComponents[i]) != nullptr;
  }
  if (line.clauses().empty()) {
    if (fix.set == kAllNodesSet) {
      // `fix all` reads as the built-in set with no component; the user meant either every
      // component of some set or some component of every node.
      line.fail(line.end(),
                "give the fixed components: 'fix all' names the built-in set of "
                "every node but no component; write 'fix all ux' (or uy, uz) to fix "
                "a component of every node, 'fix all all' to clamp every node, or "
                "'fix SET all' to clamp the nodes of one set");
    }
    line.fail(line.end(), "give the fixed components: ux, uy, uz or all");
  }
  fix.where = line.where();
  state.spec.fixes.push_back(fix);
}

void handlePrescribe(const ParsedLine& line, DeckState& state) {
  PrescribeSpec prescribe;
  prescribe.set = line.positional(0).text;
  prescribe.components = componentFunctions(line, kDisplacementComponents);
  prescribe.where = line.where();
  state.spec.prescribed.push_back(prescribe);
}

void handleLoad(const ParsedLine& line, DeckState& state) {
  LoadSpec load;
  load.set = line.positional(0).text;
  load.components = componentFunctions(line, kForceComponents);
  load.total = line.findClause("total") != nullptr;
  load.where = line.where();
  state.spec.loads.push_back(load);
}

void handleOutput(const ParsedLine& line, DeckState& state) {
  requireFirst(line, state.outputAt);
  OutputSpec& output = state.spec.output;
  if (line.given("file")) output.file = line.text("file");
  for (const auto& [name, field] : outputFields()) output.*field = false;
  for (const std::string& name : line.value("fields").list) {
    output.*choiceValue(outputFields(), name) = true;
  }
  output.csv = line.flag("csv");
  output.xdmf = line.flag("xdmf");
  output.where = line.where();
}

void handleReference(const ParsedLine& line, DeckState& state) {
  ReferenceSpec reference;
  reference.quantity = line.positional(0).text;
  const Clause* table = line.findClause("table");
  const Clause* analytic = line.findClause("analytic");
  const int given = int{line.given("value")} + int{table != nullptr} + int{analytic != nullptr};
  if (given == 0)
    line.fail(line.end(), "give one of value=NUMBER, table (t,v) ... or analytic NAME");
  if (given > 1) {
    line.fail(line.where(), "give only one of value=, table or analytic");
  }
  if (!analytic && !line.extraNumbers().empty()) {
    const ExtraNumber& first = line.extraNumbers().front();
    line.fail(first.where,
              fmt::format("unknown parameter '{}'{}; NAME=NUMBER parameters are "
                          "allowed only with 'analytic NAME'",
                          first.name, didYouMean(first.name, line.keyword().parameterNames())));
  }
  if (line.given("value")) reference.value = line.number("value");
  if (table) reference.table = table->points;
  if (analytic) reference.analytic = analytic->identifier;
  for (const ExtraNumber& extra : line.extraNumbers()) {
    reference.parameters[extra.name] = extra.value;
  }
  reference.where = line.where();
  state.spec.references.push_back(reference);
}

}  // namespace cc::deck
