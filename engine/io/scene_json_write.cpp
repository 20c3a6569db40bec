// sceneToJson: a Scene to the text of a *.strata.json file (format: engine/io/SCENE_FORMAT.md).
//
// Output is stable: keys in a fixed, readable order, 2-space indentation (arrays of numbers on
// one line), doubles in nlohmann's shortest round-trip form, colours (floats) in the shortest
// decimal that reads back to the same float. Transforms, colours, names and visibility are
// always written, defaults included.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "engine/io/scene_file.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"

namespace strata {
namespace {
// Whether node (a descendant of it, not itself) has the id.
bool holdsId(const Node& node, NodeId id) {
  for (const NodePtr& child : node.children)
    if (child && (child->id == id || holdsId(*child, id))) return true;
  return false;
}

// A shell's opening is written when it names a part inside the shell (hidden or not); a
// reference left behind by a deleted part is not (the inspector shows it as gone).
bool writesOpening(const Node& node) {
  return node.kind == NodeKind::Shell && node.opening != 0 && holdsId(node, node.opening);
}
}  // namespace

namespace {

using ojson = nlohmann::ordered_json;

// What is being written, for messages ("node 3 (\"hole\")").
std::string savedNodeLabel(const Node& node) {
  return "node " + std::to_string(node.id) + (node.name.empty() ? "" : " (\"" + node.name + "\")");
}

double finite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw Error("cannot save the scene: " + what + " is not finite");
  return value;
}

ojson vec3(const glm::dvec3& v, const std::string& what) {
  return ojson::array({finite(v.x, what), finite(v.y, what), finite(v.z, what)});
}

// The shortest decimal (as a double) that converts back to exactly `f`, so that 0.8f is
// written as 0.8 and not as 0.800000011920929.
double shortestFloat(float f, const std::string& what) {
  finite(f, what);
  char text[32];
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, static_cast<double>(f));
    double d = std::strtod(text, nullptr);
    if (static_cast<float>(d) == f) return d;
  }
  return static_cast<double>(f);  // unreachable: 9 significant digits always round-trip a float
}

std::string scalarText(const ojson& v) {
  return v.dump(-1, ' ', false, ojson::error_handler_t::strict);
}

// Pretty printing with 2-space indentation, except that arrays of plain values (vectors,
// colours) stay on one line: "[0.0, 0.0, 1.0]". Recursion is bounded by the tree depth check.
void writePretty(const ojson& v, int indent, std::string* out) {
  bool object = v.is_object();
  if (!object && !v.is_array()) {
    *out += scalarText(v);
    return;
  }
  if (v.empty()) {
    *out += object ? "{}" : "[]";
    return;
  }
  bool flat =
      !object && std::none_of(v.begin(), v.end(), [](const ojson& e) { return e.is_structured(); });
  if (flat) {
    *out += "[";
    for (size_t i = 0; i < v.size(); ++i) *out += (i ? ", " : "") + scalarText(v[i]);
    *out += "]";
    return;
  }
  *out += object ? "{\n" : "[\n";
  size_t i = 0;
  for (auto it = v.begin(); it != v.end(); ++it) {
    out->append(static_cast<size_t>(indent) + 2, ' ');
    if (object) *out += scalarText(ojson(it.key())) + ": ";
    writePretty(it.value(), indent + 2, out);
    *out += ++i < v.size() ? ",\n" : "\n";
  }
  out->append(static_cast<size_t>(indent), ' ');
  *out += object ? "}" : "]";
}

ojson nodeToJson(const Node& node, int depth) {
  std::string label = savedNodeLabel(node);
  if (depth > kMaxTreeDepth)
    throw Error("cannot save the scene: the tree is more than " + std::to_string(kMaxTreeDepth) +
                " levels deep");
  if (node.id == 0) throw Error("cannot save the scene: a node (\"" + node.name + "\") has id 0");
  ojson j;
  j["id"] = node.id;
  j["name"] = node.name;
  j["type"] = kindName(node.kind);

  if (const PrimitiveInfo* info = primitiveInfo(node.kind)) {
    for (const PrimitiveParam& param : info->params) {
      const std::string what = label + " " + param.label;
      if (param.scalar) j[param.key] = finite(node.params.*param.scalar, what);
      if (param.vector) j[param.key] = vec3(node.params.*param.vector, what);
    }
    j["segments"] = node.params.segments;
  } else if (node.kind == NodeKind::Mesh) {
    j["path"] = node.meshPath;
    if (!node.meshHash.empty()) j["hash"] = node.meshHash;
    if (node.meshOpen) j["open"] = true;
  } else if (node.kind == NodeKind::Instance) {
    j["of"] = node.instanceOf;
  } else if (const char* key = nodeKindInfo(node.kind).amountKey) {
    j[key] = finite(node.amount, label + " " + key);
    if (writesOpening(node)) j["opening"] = node.opening;
  } else if (const Pattern pattern = patternOf(node.kind); pattern != Pattern::None) {
    const PatternParams& p = node.pattern;
    checkPattern(pattern, p, "cannot save the scene: " + label);
    if (pattern == Pattern::Array) {
      j["counts"] = ojson::array({p.counts.x, p.counts.y, p.counts.z});
      j["step"] = vec3(p.step, label + " step");
    } else if (pattern == Pattern::Circular) {
      j["count"] = p.count;
      j["axis"] = axisName(p.axis);
      j["angle"] = finite(p.angle, label + " angle");
      j["center"] = vec3(p.center, label + " centre");
    } else {
      j["axis"] = axisName(p.axis);
      j["center"] = vec3(p.center, label + " centre");
      j["keep"] = p.keepOriginal;
    }
  }

  ojson transform;
  transform["translate"] = vec3(node.transform.translate, label + " translation");
  transform["rotate"] = vec3(node.transform.rotateDegrees, label + " rotation");
  transform["scale"] = vec3(node.transform.scale, label + " scale");
  j["transform"] = std::move(transform);
  j["color"] = ojson::array({shortestFloat(node.color.r, label + " colour"),
                             shortestFloat(node.color.g, label + " colour"),
                             shortestFloat(node.color.b, label + " colour")});
  j["visible"] = node.visible;

  if (isOperation(node.kind)) {
    ojson children = ojson::array();
    for (const NodePtr& child : node.children) {
      if (!child) throw Error("cannot save the scene: " + label + " has a null child");
      children.push_back(nodeToJson(*child, depth + 1));
    }
    j["children"] = std::move(children);
  }
  return j;
}

}  // namespace

namespace {
bool holdsModifier(const Node& node) {
  if (modifierOf(node.kind) != Modifier::None) return true;
  for (const NodePtr& child : node.children)
    if (child && holdsModifier(*child)) return true;
  return false;
}

bool holdsPattern(const Node& node) {
  if (patternOf(node.kind) != Pattern::None) return true;
  for (const NodePtr& child : node.children)
    if (child && holdsPattern(*child)) return true;
  return false;
}

bool holdsOpenMesh(const Node& node) {
  if (node.kind == NodeKind::Mesh && node.meshOpen) return true;
  for (const NodePtr& child : node.children)
    if (child && holdsOpenMesh(*child)) return true;
  return false;
}

bool holdsOpening(const Node& node) {
  if (writesOpening(node)) return true;
  for (const NodePtr& child : node.children)
    if (child && holdsOpening(*child)) return true;
  return false;
}
}  // namespace

std::string sceneToJson(const Scene& scene) {
  if (!scene.root) throw Error("cannot save the scene: it has no root node");
  if (scene.settings.unit.empty()) throw Error("cannot save the scene: its unit is empty");
  const SceneSettings& s = scene.settings;
  ojson doc;
  doc["format"] = "strata-scene";
  // The oldest version that holds the scene: files without modifiers stay readable by
  // builds that read version 1, files without a shell's opening by those that read 2, files
  // without patterns or measurements by those that read 3, files without an open mesh by those
  // that read 4.
  doc["version"] = holdsOpenMesh(*scene.root)                                 ? 5
                   : holdsPattern(*scene.root) || !scene.measurements.empty() ? 4
                   : holdsOpening(*scene.root)                                ? 3
                   : holdsModifier(*scene.root)                               ? 2
                                                                              : 1;
  doc["unit"] = s.unit;
  ojson settings;
  settings["resolution"] = s.resolution;
  settings["margin"] = finite(s.margin, "the grid margin");
  if (s.hasBounds) {
    ojson bounds;
    bounds["min"] = vec3(s.bounds.min, "the grid bounds");
    bounds["max"] = vec3(s.bounds.max, "the grid bounds");
    settings["bounds"] = std::move(bounds);
  }
  if (s.maxLeaves != kDefaultMaxLeaves) settings["maxLeaves"] = s.maxLeaves;
  doc["settings"] = std::move(settings);
  doc["root"] = nodeToJson(*scene.root, 1);
  if (!scene.measurements.empty()) {
    // Points in world coordinates where they are now, with the part they lie on.
    ojson measurements = ojson::array();
    for (const Measurement& m : scene.measurements) {
      ojson points = ojson::array();
      for (const MeasurePoint& p : m.points) {
        ojson point;
        if (p.node != 0) point["on"] = p.node;
        point["at"] = vec3(pointInWorld(scene.root, p), "a measured point");
        points.push_back(std::move(point));
      }
      ojson one;
      one["points"] = std::move(points);
      measurements.push_back(std::move(one));
    }
    doc["measurements"] = std::move(measurements);
  }
  try {
    std::string text;
    writePretty(doc, 0, &text);
    return text + "\n";
  } catch (const ojson::type_error& e) {
    throw Error(std::string("cannot save the scene: a name or path is not valid UTF-8 (") +
                e.what() + ")");
  }
}

}  // namespace strata
