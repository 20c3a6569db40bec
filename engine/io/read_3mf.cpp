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
// Colours, materials and metadata are ignored. Elements of other namespaces (extensions) are
// skipped with their content; a model that *requires* an extension other than materials or
// production, or refers to another model part (the production extension's p:path), is refused.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "engine/io/mesh_readers.h"
#include "engine/io/xml_scan.h"
#include "engine/io/zip_archive.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

constexpr std::string_view kCoreNamespace =
    "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
constexpr std::string_view kModelRelationship =
    "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
constexpr std::string_view kHarmlessExtensions[] = {
    "http://schemas.microsoft.com/3dmanufacturing/material/2015/02",
    "http://schemas.microsoft.com/3dmanufacturing/production/2015/06",
};
const char* const kDefaultModelPart = "3D/3dmodel.model";
const char* const kRelationshipsPart = "_rels/.rels";

constexpr size_t kMaxModelBytes = size_t(2) << 30;  // uncompressed model XML
constexpr size_t kMaxRelationshipBytes = size_t(16) << 20;
// Placed triangles in all (components can multiply a small file into a huge mesh).
constexpr uint64_t kMaxPlacedTriangles = 100'000'000;
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
  return a + b > kMaxPlacedTriangles ? kMaxPlacedTriangles + 1 : a + b;
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

std::string findModelPart(const zipio::ZipReader& zip, const std::string& name,
                          MeshReadReport* report) {
  if (zip.has(kRelationshipsPart)) {
    const std::string text = zip.read(kRelationshipsPart, kMaxRelationshipBytes);
    XmlScanner xml(text, name + ": " + kRelationshipsPart);
    XmlTag tag;
    while (xml.next(tag)) {
      if (tag.kind == XmlTag::Kind::End || XmlTag::localOf(tag.name) != "Relationship") continue;
      const std::string_view* type = tag.attribute("Type");
      if (!type || *type != kModelRelationship) continue;
      const std::string_view* target = tag.attribute("Target");
      if (!target || target->empty()) xml.fail(tag.line, "the 3D model relationship has no Target");
      const std::string part = partNameFromTarget(*target);
      if (!zip.has(part)) {
        xml.fail(tag.line, "the 3D model relationship names part " + quoted(*target) +
                               ", which is not in the archive");
      }
      return part;
    }
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

class ModelParser {
 public:
  ModelParser(const std::string& fileName, std::string_view xml, const std::string& part,
              MeshReadReport* report)
      : fileName_(fileName), where_(fileName + ": " + part), xml_(xml, where_), report_(report) {}

  TriangleMesh parse() {
    XmlTag tag;
    xml_.next(tag);  // throws when there is no root element
    readModelElement(tag);
    stack_.push_back(Context::Model);
    while (xml_.next(tag)) {
      if (tag.kind == XmlTag::Kind::End) {
        const Context context = stack_.back();
        stack_.pop_back();
        if (context == Context::Object) finishObject();
        continue;
      }
      const Context context = startElement(stack_.back(), tag);
      if (tag.kind == XmlTag::Kind::Start) {
        stack_.push_back(context);
      } else if (context == Context::Object) {
        finishObject();
      }
    }
    if (!sawBuild_) xml_.fail(xml_.line(), "the model has no <build> element");
    if (items_.empty()) xml_.fail(buildLine_, "the <build> element places no <item>");

    TriangleMesh mesh;
    for (const Item& item : items_) place(objects_.at(item.objectId), item.transform, item, mesh);
    report_->fileVertices += mesh.positions.size();
    report_->fileFaces += mesh.triangles.size();
    return mesh;
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

  void readModelElement(const XmlTag& tag) {
    if (XmlTag::localOf(tag.name) != "model") {
      xml_.fail(tag.line, "the root element is <" + std::string(tag.name) + ">, expected <model>");
    }
    const std::string_view* defaultNamespace = nullptr;
    for (const auto& [attr, value] : tag.attributes) {
      if (attr == "xmlns") {
        defaultNamespace = &value;
        namespaces_[""] = value;
      } else if (XmlTag::prefixOf(attr) == "xmlns") {
        namespaces_[XmlTag::localOf(attr)] = value;
      }
    }
    bool foundCore = false;
    for (const auto& [prefix, uri] : namespaces_) {
      if (uri == kCoreNamespace && (!foundCore || prefix.empty())) {
        corePrefix_ = prefix;
        foundCore = true;
      }
    }
    if (!foundCore) {
      if (defaultNamespace) {
        xml_.fail(tag.line, "<model> is not in the 3MF core namespace (xmlns=" +
                                quotedUri(*defaultNamespace) + ")");
      }
      addWarning(report_, fileName_,
                 "<model> declares no 3MF core namespace; read its unprefixed elements as 3MF");
    }
    if (XmlTag::prefixOf(tag.name) != corePrefix_) {
      xml_.fail(tag.line, "<" + std::string(tag.name) + "> is not in the 3MF core namespace");
    }

    if (const std::string_view* unit = tag.attribute("unit")) {
      static const char* const kUnits[] = {"micron", "millimeter", "centimeter",
                                           "inch",   "foot",       "meter"};
      bool known = false;
      for (const char* u : kUnits) known |= *unit == u;
      if (!known) {
        xml_.fail(tag.line, "unknown unit " + quoted(*unit) +
                                " (3MF allows micron, millimeter, centimeter, inch, foot, meter)");
      }
      if (*unit != "millimeter") {
        addWarning(report_, fileName_,
                   "the model's unit is " + std::string(*unit) +
                       "; coordinates are read as written, not converted to millimetres");
      }
    }

    if (const std::string_view* required = tag.attribute("requiredextensions")) {
      std::vector<std::string_view> prefixes;
      splitTokens(*required, prefixes, false);
      for (std::string_view prefix : prefixes) {
        auto it = namespaces_.find(prefix);
        if (it == namespaces_.end()) {
          xml_.fail(tag.line, "requiredextensions names prefix " + quoted(prefix) +
                                  ", which no xmlns declares");
        }
        bool harmless = it->second == kCoreNamespace;
        for (std::string_view ns : kHarmlessExtensions) harmless |= it->second == ns;
        if (!harmless) {
          xml_.fail(tag.line, "the model requires the 3MF extension " + quotedUri(it->second) +
                                  ", which Strata cannot read");
        }
      }
    }
    if (tag.kind != XmlTag::Kind::Start) xml_.fail(tag.line, "<model> is empty");
  }

  bool isCore(const XmlTag& tag) const { return XmlTag::prefixOf(tag.name) == corePrefix_; }

  Context unexpected(const XmlTag& tag, const char* parent) {
    xml_.fail(tag.line,
              "unexpected element <" + std::string(tag.name) + "> inside <" + parent + ">");
  }

  Context ignoreUnknown(const XmlTag& tag) {
    if (warnedUnknown_.insert(std::string(tag.name)).second) {
      addWarning(report_, fileName_,
                 "ignored unknown 3MF element <" + std::string(tag.name) + "> (first at line " +
                     std::to_string(tag.line) + ")");
    }
    return Context::Skipped;
  }

  Context startElement(Context parent, const XmlTag& tag) {
    if (parent == Context::Skipped || !isCore(tag)) return Context::Skipped;
    const std::string_view local = XmlTag::localOf(tag.name);
    switch (parent) {
      case Context::Model:
        if (local == "resources") {
          if (sawResources_) xml_.fail(tag.line, "a second <resources> element");
          sawResources_ = true;
          return Context::Resources;
        }
        if (local == "build") {
          if (sawBuild_) xml_.fail(tag.line, "a second <build> element");
          sawBuild_ = true;
          buildLine_ = tag.line;
          return Context::Build;
        }
        if (local == "metadata") return Context::Skipped;
        return ignoreUnknown(tag);
      case Context::Resources:
        if (local == "object") {
          beginObject(tag);
          return Context::Object;
        }
        if (local == "basematerials") return Context::Skipped;
        return ignoreUnknown(tag);
      case Context::Object:
        if (local == "mesh" || local == "components") {
          if (current_.hasMesh || current_.hasComponents) {
            xml_.fail(tag.line, "object " + std::to_string(current_.id) +
                                    " has more than one <mesh> or <components>");
          }
          (local == "mesh" ? current_.hasMesh : current_.hasComponents) = true;
          return local == "mesh" ? Context::Mesh : Context::Components;
        }
        if (local == "metadatagroup") return Context::Skipped;
        return ignoreUnknown(tag);
      case Context::Mesh:
        if (local == "vertices") return Context::Vertices;
        if (local == "triangles") return Context::Triangles;
        return ignoreUnknown(tag);
      case Context::Vertices:
        if (local != "vertex") return unexpected(tag, "vertices");
        addVertex(tag);
        return Context::Skipped;
      case Context::Triangles:
        if (local != "triangle") return unexpected(tag, "triangles");
        addTriangle(tag);
        return Context::Skipped;
      case Context::Components:
        if (local != "component") return unexpected(tag, "components");
        addComponent(tag);
        return Context::Skipped;
      case Context::Build:
        if (local != "item") return unexpected(tag, "build");
        addItem(tag);
        return Context::Skipped;
      case Context::Skipped:
        break;
    }
    return Context::Skipped;
  }

  const std::string_view& required(const XmlTag& tag, std::string_view attr) {
    const std::string_view* value = tag.attribute(attr);
    if (!value) {
      xml_.fail(tag.line,
                "<" + std::string(tag.name) + "> has no " + std::string(attr) + " attribute");
    }
    return *value;
  }

  // A resource id: a positive integer.
  uint64_t parseId(const XmlTag& tag, std::string_view attr) {
    const std::string_view& text = required(tag, attr);
    long long id = 0;
    if (!parseInteger(text, id) || id <= 0 || id > 0x7fffffff) {
      xml_.fail(tag.line, std::string(attr) + " is not a positive integer id: " + quoted(text));
    }
    return static_cast<uint64_t>(id);
  }

  void refuseOtherParts(const XmlTag& tag) {
    for (const auto& attribute : tag.attributes) {
      if (XmlTag::localOf(attribute.first) == "path" &&
          !XmlTag::prefixOf(attribute.first).empty()) {
        xml_.fail(tag.line, "<" + std::string(tag.name) + "> refers to another model part (" +
                                std::string(attribute.first) + "=" + quoted(attribute.second) +
                                "); multi-part 3MF files are not supported");
      }
    }
  }

  Affine parseTransform(const XmlTag& tag) {
    Affine transform;
    const std::string_view* text = tag.attribute("transform");
    if (!text) return transform;
    std::vector<std::string_view> tokens;
    splitTokens(*text, tokens, false);
    if (tokens.size() != 12) {
      xml_.fail(tag.line, "transform must have 12 numbers, has " + std::to_string(tokens.size()));
    }
    double m[12];
    for (int i = 0; i < 12; ++i) m[i] = parseCoordinate(where_, tag.line, tokens[i]);
    // Row-vector convention: x' = m00 x + m10 y + m20 z + m30, so column c of the matrix
    // acting on column vectors is (m0c, m1c, m2c); glm indexes [column][row].
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) transform.linear[c][r] = m[c * 3 + r];
    }
    transform.translation = glm::dvec3(m[9], m[10], m[11]);
    const double det = glm::determinant(transform.linear);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
      xml_.fail(tag.line, "transform is singular (it flattens the object)");
    }
    transform.identity = false;
    return transform;
  }

  void beginObject(const XmlTag& tag) {
    current_ = Object();
    current_.id = parseId(tag, "id");
    current_.line = tag.line;
    if (objects_.count(current_.id)) {
      xml_.fail(tag.line, "object id " + std::to_string(current_.id) + " is used twice");
    }
    if (const std::string_view* type = tag.attribute("type")) {
      if (*type != "model" && *type != "solidsupport" && *type != "support" && *type != "surface" &&
          *type != "other") {
        xml_.fail(tag.line, "unknown object type " + quoted(*type));
      }
      current_.type = std::string(*type);
    }
  }

  void finishObject() {
    Object& object = current_;
    object.placedTriangles = object.triangles.size();
    for (const Component& component : object.components) {
      const Object& child = objects_.at(component.objectId);
      object.placedTriangles = saturatingAdd(object.placedTriangles, child.placedTriangles);
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

  void addVertex(const XmlTag& tag) {
    if (current_.vertices.size() >= 0xffffffffu) xml_.fail(tag.line, "too many vertices");
    glm::dvec3 p;
    p.x = parseCoordinate(where_, tag.line, required(tag, "x"));
    p.y = parseCoordinate(where_, tag.line, required(tag, "y"));
    p.z = parseCoordinate(where_, tag.line, required(tag, "z"));
    current_.vertices.push_back(p);
  }

  void addTriangle(const XmlTag& tag) {
    static const char* const kNames[3] = {"v1", "v2", "v3"};
    std::array<uint32_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const std::string_view& text = required(tag, kNames[k]);
      long long index = 0;
      if (!parseInteger(text, index)) {
        xml_.fail(tag.line, std::string(kNames[k]) + " is not an integer: " + quoted(text));
      }
      if (index < 0 || static_cast<unsigned long long>(index) >= current_.vertices.size()) {
        xml_.fail(tag.line, "vertex index " + std::string(kNames[k]) + "=" + std::to_string(index) +
                                " is out of range (object " + std::to_string(current_.id) +
                                " has " + std::to_string(current_.vertices.size()) +
                                " vertices so far; indices start at 0)");
      }
      triangle[k] = static_cast<uint32_t>(index);
    }
    current_.triangles.push_back(triangle);
  }

  const Object& referencedObject(const XmlTag& tag) {
    const uint64_t id = parseId(tag, "objectid");
    auto it = objects_.find(id);
    if (it == objects_.end()) {
      xml_.fail(tag.line,
                "objectid " + std::to_string(id) + " names no object defined before this point");
    }
    return it->second;
  }

  void addComponent(const XmlTag& tag) {
    refuseOtherParts(tag);
    Component component;
    component.objectId = referencedObject(tag).id;
    component.transform = parseTransform(tag);
    current_.components.push_back(component);
  }

  void addItem(const XmlTag& tag) {
    refuseOtherParts(tag);
    const Object& object = referencedObject(tag);
    Item item;
    item.objectId = object.id;
    item.transform = parseTransform(tag);
    item.line = tag.line;
    if (object.type != "model" && object.type != "solidsupport") {
      addWarning(report_, fileName_,
                 "line " + std::to_string(tag.line) + ": skipped build item: object " +
                     std::to_string(object.id) + " has type " + object.type +
                     " (not a solid model)");
      return;
    }
    placedTriangles_ = saturatingAdd(placedTriangles_, object.placedTriangles);
    if (placedTriangles_ > kMaxPlacedTriangles) {
      xml_.fail(tag.line,
                "the build places more than " + std::to_string(kMaxPlacedTriangles) + " triangles");
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
  XmlScanner xml_;
  MeshReadReport* report_;

  std::map<std::string_view, std::string_view> namespaces_;
  std::string_view corePrefix_;
  std::vector<Context> stack_;
  bool sawResources_ = false;
  bool sawBuild_ = false;
  size_t buildLine_ = 0;
  std::set<std::string> warnedUnknown_;

  Object current_;
  std::map<uint64_t, Object> objects_;
  std::vector<Item> items_;
  uint64_t placedTriangles_ = 0;
};

}  // namespace

TriangleMesh parse3mf(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  const zipio::ZipReader zip(name, bytes);
  const std::string part = findModelPart(zip, name, report);
  const std::string xml = zip.read(part, kMaxModelBytes);
  ModelParser parser(name, xml, part, report);
  return parser.parse();
}

}  // namespace meshio
}  // namespace strata
