// 3MF (3D Manufacturing Format, core specification 1.x): a zip holding an OPC package whose
// model part is XML in the 3MF core namespace. The model part is the target of the 3D-model
// relationship in _rels/.rels, or 3D/3dmodel.model when the package has none (with a warning).
//
// What is read: the geometry the <build> places. Each <item> places an <object>; an object is
// either a <mesh> (<vertices><vertex x y z/>..., <triangles><triangle v1 v2 v3/>...) or
// <components> that place earlier objects. Item and component transforms ("m00 m01 m02 m10 m11
// m12 m20 m21 m22 m30 m31 m32", row-vector convention) are applied, composed through nested
// components; a mirroring transform reverses the winding so the surface keeps its orientation.
// Objects no item places are not read; items placing objects of type support, surface or other
// are skipped with a warning. Coordinates are kept in the model's unit: a unit other than
// millimeter is reported in a warning, never converted (MeshReadOptions::unitScale does that).
// Colours, materials and metadata are ignored.
//
// The XML goes through expat (xml_reader.h) with namespaces resolved: elements are matched by
// namespace URI and local name, so a file may bind the core namespace to any prefix or make it
// the default. <model> must be in the core namespace (a model in no namespace at all is read
// with a warning; in another namespace it is refused: it is not a 3MF model). Elements of any
// other namespace are skipped with their content, as the specification asks of consumers for
// extensions they do not require, even where their local names are core names. A model that
// *requires* an extension other than materials or production, or refers to another model part
// (the production extension's p:path), is refused.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "engine/io/mesh_readers.h"
#include "engine/io/xml_reader.h"
#include "engine/io/zip_archive.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

constexpr std::string_view kCoreNamespace =
    "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
constexpr std::string_view kMaterialNamespace =
    "http://schemas.microsoft.com/3dmanufacturing/material/2015/02";
constexpr std::string_view kProductionNamespace =
    "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
// Extensions a model may require: what they add (colours, materials, UUIDs) is not geometry.
constexpr std::string_view kHarmlessExtensions[] = {kMaterialNamespace, kProductionNamespace};
constexpr std::string_view kRelationshipsNamespace =
    "http://schemas.openxmlformats.org/package/2006/relationships";
constexpr std::string_view kModelRelationship =
    "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
const char* const kDefaultModelPart = "3D/3dmodel.model";
const char* const kRelationshipsPart = "_rels/.rels";

constexpr size_t kMaxRelationshipBytes = size_t(16) << 20;
// Placed vertices, and objects placed (each component reference is a placement): an object of
// vertices but no triangles, or of empty components, must not expand unboundedly either.
constexpr uint64_t kMaxPlacedVertices = 100'000'000;
constexpr uint64_t kMaxPlacements = 10'000'000;
constexpr int kMaxComponentDepth = 32;

// p -> linear * p + translation.
struct Affine {
  glm::dmat3 linear{1.0};
  glm::dvec3 translation{0.0};
  bool identity = true;
};

// outer(inner(p)).
Affine compose(const Affine& outer, const Affine& inner) {
  if (inner.identity) return outer;
  if (outer.identity) return inner;
  Affine result;
  result.linear = outer.linear * inner.linear;
  result.translation = outer.linear * inner.translation + outer.translation;
  result.identity = false;
  return result;
}

struct Component {
  uint64_t objectId = 0;
  Affine transform;
};

struct Object {
  uint64_t id = 0;
  size_t line = 0;
  std::string type = "model";
  bool hasMesh = false;
  bool hasComponents = false;
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<Component> components;
  uint64_t placedTriangles = 0;  // through components too, saturating above the limit
  uint64_t placedVertices = 0;   // the same for vertices
  uint64_t placements = 0;       // this object and every object its components place
  int depth = 0;                 // component nesting below this object
};

struct Item {
  uint64_t objectId = 0;
  Affine transform;
  size_t line = 0;
};

// A namespace URI for a message: whole (up to 200 characters), control characters as '?'.
std::string quotedUri(std::string_view uri) {
  std::string text(uri.substr(0, 200));
  for (char& ch : text) {
    if (static_cast<unsigned char>(ch) < 32) ch = '?';
  }
  return "'" + text + (uri.size() > 200 ? "...'" : "'");
}

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  // Saturating just above the largest limit any count here is held to (placed triangles,
  // vertices, placements), so that a sum never wraps.
  const uint64_t cap = std::max<uint64_t>(maxInputTriangles(), kMaxPlacedVertices);
  return a + b > cap ? cap + 1 : a + b;
}

// OPC part names are URIs: drop the leading '/', decode %XX escapes.
std::string partNameFromTarget(std::string_view target) {
  if (!target.empty() && target[0] == '/') target.remove_prefix(1);
  std::string part;
  for (size_t i = 0; i < target.size(); ++i) {
    auto hex = [](char c) {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      if (c >= 'A' && c <= 'F') return c - 'A' + 10;
      return -1;
    };
    if (target[i] == '%' && i + 2 < target.size() && hex(target[i + 1]) >= 0 &&
        hex(target[i + 2]) >= 0) {
      part += static_cast<char>(hex(target[i + 1]) * 16 + hex(target[i + 2]));
      i += 2;
    } else {
      part += target[i];
    }
  }
  return part;
}

// The part named by the first 3D-model relationship of _rels/.rels (Relationship elements in
// the OPC relationships namespace, or in none), checked to be in the archive.
class RelationshipScan : public XmlReader::Handler {
 public:
  RelationshipScan(const zipio::ZipReader& zip, const XmlReader& xml) : zip_(zip), xml_(xml) {}

  void startElement(const XmlElement& element) override {
    if (found_ || element.name.local != "Relationship") return;
    if (!element.name.uri.empty() && element.name.uri != kRelationshipsNamespace) return;
    const std::string_view* type = element.attribute("Type");
    if (!type || *type != kModelRelationship) return;
    const std::string_view* target = element.attribute("Target");
    if (!target || target->empty()) {
      xml_.fail(element.line, "the 3D model relationship has no Target");
    }
    part_ = partNameFromTarget(*target);
    if (!zip_.has(part_)) {
      xml_.fail(element.line, "the 3D model relationship names part " + quoted(*target) +
                                  ", which is not in the archive");
    }
    found_ = true;
  }
  void endElement(const XmlName&, size_t) override {}

  bool found() const { return found_; }
  const std::string& part() const { return part_; }

 private:
  const zipio::ZipReader& zip_;
  const XmlReader& xml_;
  bool found_ = false;
  std::string part_;
};

std::string findModelPart(const zipio::ZipReader& zip, const std::string& name,
                          MeshReadReport* report) {
  if (zip.has(kRelationshipsPart)) {
    const std::string text = zip.read(kRelationshipsPart, kMaxRelationshipBytes);
    XmlReader xml(name + ": " + kRelationshipsPart);
    RelationshipScan scan(zip, xml);
    xml.parse(text, scan);
    if (scan.found()) return scan.part();
    if (!zip.has(kDefaultModelPart)) {
      throw Error(name + ": missing 3D model part: " + kRelationshipsPart +
                  " has no 3D model relationship and there is no " + kDefaultModelPart);
    }
    addWarning(report, name,
               std::string(kRelationshipsPart) + " has no 3D model relationship; read " +
                   kDefaultModelPart);
    return kDefaultModelPart;
  }
  if (!zip.has(kDefaultModelPart)) {
    throw Error(name + ": missing 3D model part: the archive has neither " + kRelationshipsPart +
                " nor " + kDefaultModelPart + " (is this a 3MF file?)");
  }
  addWarning(
      report, name,
      std::string("the package has no ") + kRelationshipsPart + "; read " + kDefaultModelPart);
  return kDefaultModelPart;
}

// The model part, read as expat reports it: the elements open around each start tag are a
// stack of contexts; objects are kept as they close (components may only place objects defined
// before them), the build's items are placed once the whole part is read.
class ModelParser : public XmlReader::Handler {
 public:
  ModelParser(const std::string& fileName, const std::string& part, MeshReadReport* report)
      : fileName_(fileName), where_(fileName + ": " + part), xml_(where_), report_(report) {}

  TriangleMesh parse(std::string_view text) {
    xml_.parse(text, *this);  // throws when there is no root element
    if (!sawBuild_) xml_.fail(endLine_, "the model has no <build> element");
    if (items_.empty()) xml_.fail(buildLine_, "the <build> element places no <item>");

    TriangleMesh mesh;
    for (const Item& item : items_) place(objects_.at(item.objectId), item.transform, item, mesh);
    report_->fileVertices += mesh.positions.size();
    report_->fileFaces += mesh.triangles.size();
    return mesh;
  }

  void startElement(const XmlElement& element) override {
    if (stack_.empty()) {
      readModelElement(element);
      stack_.push_back(Context::Model);
      return;
    }
    stack_.push_back(childContext(stack_.back(), element));
  }

  void endElement(const XmlName&, size_t line) override {
    const Context context = stack_.back();
    stack_.pop_back();
    if (context == Context::Object) finishObject();
    endLine_ = line;
  }

 private:
  enum class Context {
    Model,
    Resources,
    Object,
    Mesh,
    Vertices,
    Triangles,
    Components,
    Build,
    Skipped,  // extension elements, metadata, vertex/triangle content: not read
  };

  // ---- <model> ----

  void readModelElement(const XmlElement& model) {
    if (model.name.local != "model") {
      xml_.fail(model.line,
                "the root element is <" + model.name.qualified() + ">, expected <model>");
    }
    checkModelNamespace(model);
    checkUnit(model);
    checkRequiredExtensions(model);
  }

  // Sets coreUri_: the core namespace, or none for a model that declares no namespace at all.
  void checkModelNamespace(const XmlElement& model) {
    if (model.name.uri == kCoreNamespace) {
      coreUri_ = std::string(kCoreNamespace);
      return;
    }
    if (!model.name.uri.empty()) {
      xml_.fail(model.line, "<" + model.name.qualified() +
                                "> is not in the 3MF core namespace (it is in " +
                                quotedUri(model.name.uri) + ")");
    }
    if (xml_.isBound(kCoreNamespace)) {
      xml_.fail(model.line, "<" + model.name.qualified() +
                                "> is not in the 3MF core namespace (which the file binds to a "
                                "prefix <model> does not use)");
    }
    addWarning(report_, fileName_,
               "<model> declares no 3MF core namespace; read its elements in no namespace as "
               "3MF");
    coreUri_.clear();
  }

  void checkUnit(const XmlElement& model) {
    const std::string_view* unit = model.attribute("unit");
    if (!unit) return;
    static const char* const kUnits[] = {"micron", "millimeter", "centimeter",
                                         "inch",   "foot",       "meter"};
    bool known = false;
    for (const char* u : kUnits) known |= *unit == u;
    if (!known) {
      xml_.fail(model.line, "unknown unit " + quoted(*unit) +
                                " (3MF allows micron, millimeter, centimeter, inch, foot, meter)");
    }
    if (*unit != "millimeter") {
      addWarning(report_, fileName_,
                 "the model's unit is " + std::string(*unit) +
                     "; coordinates are read as written, not converted to millimetres");
    }
  }

  // requiredextensions lists prefixes bound on <model>; each must name an extension whose
  // content can be skipped without changing the geometry.
  void checkRequiredExtensions(const XmlElement& model) {
    const std::string_view* required = model.attribute("requiredextensions");
    if (!required) return;
    std::vector<std::string_view> prefixes;
    splitTokens(*required, prefixes, false);
    for (std::string_view prefix : prefixes) {
      const std::string* uri = xml_.namespaceUri(prefix);
      if (!uri) {
        xml_.fail(model.line, "requiredextensions names prefix " + quoted(prefix) +
                                  ", which no xmlns declares");
      }
      bool harmless = *uri == kCoreNamespace;
      for (std::string_view ns : kHarmlessExtensions) harmless |= *uri == ns;
      if (!harmless) {
        xml_.fail(model.line, "the model requires the 3MF extension " + quotedUri(*uri) +
                                  ", which Strata cannot read");
      }
    }
  }

  // ---- Elements inside <model> ----

  Context unexpected(const XmlElement& element, const char* parent) {
    xml_.fail(element.line,
              "unexpected element <" + element.name.qualified() + "> inside <" + parent + ">");
  }

  Context ignoreUnknown(const XmlElement& element) {
    const std::string name = element.name.qualified();
    if (warnedUnknown_.insert(name).second) {
      addWarning(report_, fileName_,
                 "ignored unknown 3MF element <" + name + "> (first at line " +
                     std::to_string(element.line) + ")");
    }
    return Context::Skipped;
  }

  Context childContext(Context parent, const XmlElement& element) {
    if (parent == Context::Skipped || element.name.uri != coreUri_) return Context::Skipped;
    switch (parent) {
      case Context::Model:
        return childOfModel(element);
      case Context::Resources:
        if (element.name.local == "object") {
          beginObject(element);
          return Context::Object;
        }
        if (element.name.local == "basematerials") return Context::Skipped;
        return ignoreUnknown(element);
      case Context::Object:
        return childOfObject(element);
      case Context::Mesh:
        if (element.name.local == "vertices") return Context::Vertices;
        if (element.name.local == "triangles") return Context::Triangles;
        return ignoreUnknown(element);
      case Context::Vertices:
        if (element.name.local != "vertex") return unexpected(element, "vertices");
        addVertex(element);
        return Context::Skipped;
      case Context::Triangles:
        if (element.name.local != "triangle") return unexpected(element, "triangles");
        addTriangle(element);
        return Context::Skipped;
      case Context::Components:
        if (element.name.local != "component") return unexpected(element, "components");
        addComponent(element);
        return Context::Skipped;
      case Context::Build:
        if (element.name.local != "item") return unexpected(element, "build");
        addItem(element);
        return Context::Skipped;
      case Context::Skipped:
        break;
    }
    return Context::Skipped;
  }

  Context childOfModel(const XmlElement& element) {
    const std::string_view local = element.name.local;
    if (local == "resources") {
      if (sawResources_) xml_.fail(element.line, "a second <resources> element");
      sawResources_ = true;
      return Context::Resources;
    }
    if (local == "build") {
      if (sawBuild_) xml_.fail(element.line, "a second <build> element");
      sawBuild_ = true;
      buildLine_ = element.line;
      return Context::Build;
    }
    if (local == "metadata") return Context::Skipped;
    return ignoreUnknown(element);
  }

  Context childOfObject(const XmlElement& element) {
    const std::string_view local = element.name.local;
    if (local == "mesh" || local == "components") {
      if (current_.hasMesh || current_.hasComponents) {
        xml_.fail(element.line, "object " + std::to_string(current_.id) +
                                    " has more than one <mesh> or <components>");
      }
      (local == "mesh" ? current_.hasMesh : current_.hasComponents) = true;
      return local == "mesh" ? Context::Mesh : Context::Components;
    }
    if (local == "metadatagroup") return Context::Skipped;
    return ignoreUnknown(element);
  }

  const std::string_view& required(const XmlElement& element, std::string_view attr) {
    const std::string_view* value = element.attribute(attr);
    if (!value) {
      xml_.fail(element.line,
                "<" + element.name.qualified() + "> has no " + std::string(attr) + " attribute");
    }
    return *value;
  }

  // A resource id: a positive integer.
  uint64_t parseId(const XmlElement& element, std::string_view attr) {
    const std::string_view& text = required(element, attr);
    long long id = 0;
    if (!parseInteger(text, id) || id <= 0 || id > 0x7fffffff) {
      xml_.fail(element.line, std::string(attr) + " is not a positive integer id: " + quoted(text));
    }
    return static_cast<uint64_t>(id);
  }

  // The production extension's p:path places an object of another model part.
  void refuseOtherParts(const XmlElement& element) {
    for (const XmlAttribute& attribute : element.attributes) {
      if (attribute.name.uri == kProductionNamespace && attribute.name.local == "path") {
        xml_.fail(element.line, "<" + element.name.qualified() +
                                    "> refers to another model part (" +
                                    attribute.name.qualified() + "=" + quoted(attribute.value) +
                                    "); multi-part 3MF files are not supported");
      }
    }
  }

  Affine parseTransform(const XmlElement& element) {
    Affine transform;
    const std::string_view* text = element.attribute("transform");
    if (!text) return transform;
    std::vector<std::string_view> tokens;
    splitTokens(*text, tokens, false);
    if (tokens.size() != 12) {
      xml_.fail(element.line,
                "transform must have 12 numbers, has " + std::to_string(tokens.size()));
    }
    double m[12];
    for (int i = 0; i < 12; ++i) m[i] = parseCoordinate(where_, element.line, tokens[i]);
    // Row-vector convention: x' = m00 x + m10 y + m20 z + m30, so column c of the matrix
    // acting on column vectors is (m0c, m1c, m2c); glm indexes [column][row].
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) transform.linear[c][r] = m[c * 3 + r];
    }
    transform.translation = glm::dvec3(m[9], m[10], m[11]);
    const double det = glm::determinant(transform.linear);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
      xml_.fail(element.line, "transform is singular (it flattens the object)");
    }
    transform.identity = false;
    return transform;
  }

  void beginObject(const XmlElement& element) {
    current_ = Object();
    current_.id = parseId(element, "id");
    current_.line = element.line;
    if (objects_.count(current_.id)) {
      xml_.fail(element.line, "object id " + std::to_string(current_.id) + " is used twice");
    }
    if (const std::string_view* type = element.attribute("type")) {
      if (*type != "model" && *type != "solidsupport" && *type != "support" && *type != "surface" &&
          *type != "other") {
        xml_.fail(element.line, "unknown object type " + quoted(*type));
      }
      current_.type = std::string(*type);
    }
  }

  void finishObject() {
    Object& object = current_;
    object.placedTriangles = object.triangles.size();
    object.placedVertices = object.vertices.size();
    object.placements = 1;
    for (const Component& component : object.components) {
      const Object& child = objects_.at(component.objectId);
      object.placedTriangles = saturatingAdd(object.placedTriangles, child.placedTriangles);
      object.placedVertices = saturatingAdd(object.placedVertices, child.placedVertices);
      object.placements = saturatingAdd(object.placements, child.placements);
      object.depth = std::max(object.depth, child.depth + 1);
    }
    if (object.depth > kMaxComponentDepth) {
      xml_.fail(object.line,
                "components nest more than " + std::to_string(kMaxComponentDepth) + " deep");
    }
    const uint64_t id = object.id;
    objects_.emplace(id, std::move(object));
    current_ = Object();
  }

  void addVertex(const XmlElement& element) {
    if (current_.vertices.size() >= 0xffffffffu) xml_.fail(element.line, "too many vertices");
    glm::dvec3 p;
    p.x = parseCoordinate(where_, element.line, required(element, "x"));
    p.y = parseCoordinate(where_, element.line, required(element, "y"));
    p.z = parseCoordinate(where_, element.line, required(element, "z"));
    current_.vertices.push_back(p);
  }

  void addTriangle(const XmlElement& element) {
    static const char* const kNames[3] = {"v1", "v2", "v3"};
    std::array<uint32_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const std::string_view& text = required(element, kNames[k]);
      long long index = 0;
      if (!parseInteger(text, index)) {
        xml_.fail(element.line, std::string(kNames[k]) + " is not an integer: " + quoted(text));
      }
      if (index < 0 || static_cast<unsigned long long>(index) >= current_.vertices.size()) {
        xml_.fail(element.line, "vertex index " + std::string(kNames[k]) + "=" +
                                    std::to_string(index) + " is out of range (object " +
                                    std::to_string(current_.id) + " has " +
                                    std::to_string(current_.vertices.size()) +
                                    " vertices so far; indices start at 0)");
      }
      triangle[k] = static_cast<uint32_t>(index);
    }
    current_.triangles.push_back(triangle);
  }

  const Object& referencedObject(const XmlElement& element) {
    const uint64_t id = parseId(element, "objectid");
    auto it = objects_.find(id);
    if (it == objects_.end()) {
      xml_.fail(element.line,
                "objectid " + std::to_string(id) + " names no object defined before this point");
    }
    return it->second;
  }

  void addComponent(const XmlElement& element) {
    refuseOtherParts(element);
    Component component;
    component.objectId = referencedObject(element).id;
    component.transform = parseTransform(element);
    current_.components.push_back(component);
  }

  void addItem(const XmlElement& element) {
    refuseOtherParts(element);
    const Object& object = referencedObject(element);
    Item item;
    item.objectId = object.id;
    item.transform = parseTransform(element);
    item.line = element.line;
    if (object.type != "model" && object.type != "solidsupport") {
      addWarning(report_, fileName_,
                 "line " + std::to_string(element.line) + ": skipped build item: object " +
                     std::to_string(object.id) + " has type " + object.type +
                     " (not a solid model)");
      return;
    }
    placedTriangles_ = saturatingAdd(placedTriangles_, object.placedTriangles);
    placedVertices_ = saturatingAdd(placedVertices_, object.placedVertices);
    placements_ = saturatingAdd(placements_, object.placements);
    if (placedTriangles_ > maxInputTriangles()) {
      xml_.fail(element.line, "the build places more than " + std::to_string(maxInputTriangles()) +
                                  " triangles (components included); raise the limit with "
                                  "--max-triangles");
    }
    if (placedVertices_ > kMaxPlacedVertices) {
      xml_.fail(element.line,
                "the build places more than " + std::to_string(kMaxPlacedVertices) + " vertices");
    }
    if (placements_ > kMaxPlacements) {
      xml_.fail(element.line, "the build places objects more than " +
                                  std::to_string(kMaxPlacements) +
                                  " times through its components (nested components multiply)");
    }
    items_.push_back(item);
  }

  void place(const Object& object, const Affine& transform, const Item& item, TriangleMesh& mesh) {
    if (!object.hasMesh && !object.hasComponents) {
      xml_.fail(object.line, "object " + std::to_string(object.id) +
                                 " (placed by the build item at line " + std::to_string(item.line) +
                                 ") has neither a mesh nor components");
    }
    if (object.hasMesh) {
      const size_t base = mesh.positions.size();
      for (const glm::dvec3& v : object.vertices) {
        const glm::dvec3 p = transform.identity ? v : transform.linear * v + transform.translation;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
          xml_.fail(item.line, "the transform moves a vertex of object " +
                                   std::to_string(object.id) + " to infinity");
        }
        mesh.positions.push_back(p);
      }
      const bool mirrored = !transform.identity && glm::determinant(transform.linear) < 0.0;
      for (const auto& t : object.triangles) {
        const uint32_t a = static_cast<uint32_t>(base + t[0]);
        const uint32_t b = static_cast<uint32_t>(base + t[1]);
        const uint32_t c = static_cast<uint32_t>(base + t[2]);
        mesh.triangles.push_back(mirrored ? std::array<uint32_t, 3>{a, c, b}
                                          : std::array<uint32_t, 3>{a, b, c});
      }
      if (mesh.positions.size() > 0xffffffffu) {
        xml_.fail(item.line, "the build places more than 2^32 vertices");
      }
    }
    for (const Component& component : object.components) {
      place(objects_.at(component.objectId), compose(transform, component.transform), item, mesh);
    }
  }

  const std::string& fileName_;
  const std::string where_;  // "<file>: <model part>", for messages
  XmlReader xml_;
  MeshReadReport* report_;

  std::string coreUri_;  // the namespace of core elements: the core one, or "" (none)
  std::vector<Context> stack_;
  bool sawResources_ = false;
  bool sawBuild_ = false;
  size_t buildLine_ = 0;
  size_t endLine_ = 0;  // of the last end tag
  std::set<std::string> warnedUnknown_;

  Object current_;
  std::map<uint64_t, Object> objects_;
  std::vector<Item> items_;
  uint64_t placedTriangles_ = 0;
  uint64_t placedVertices_ = 0;
  uint64_t placements_ = 0;
};

}  // namespace

TriangleMesh parse3mf(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  const zipio::ZipReader zip(name, bytes);
  const std::string part = findModelPart(zip, name, report);
  // Uncompressed: a small package may inflate to gigabytes; the input limit bounds it.
  const std::string xml =
      zip.read(part, size_t(maxInputFileBytes()), "raise the limit with --max-file-size");
  ModelParser parser(name, part, report);
  return parser.parse(xml);
}

}  // namespace meshio
}  // namespace strata
