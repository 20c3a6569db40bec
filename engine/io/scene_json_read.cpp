// parseScene: scene JSON text to a validated Scene (the format is engine/io/SCENE_FORMAT.md).
//
// Reading happens in four passes, cheapest first, so that a broken file fails fast:
//   1. the raw text's bracket nesting is bounded (nlohmann's parser and our walk must not be
//      driven into a stack overflow), then the text is parsed, rejecting duplicate keys;
//   2. the document is walked: every field is checked for name, type and range, nodes are
//      built and recorded in a flat table with their JSON pointers;
//   3. ids, instance targets, instance cycles and the depth through instances are checked on
//      that table with an iterative depth-first search;
//   4. referenced meshes are read (each file once) and their content hashes compared.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/io/scene_file.h"
#include "engine/kinds/primitives.h"
#include "engine/ldi/grid.h"
#include "engine/util/error.h"

namespace strata {
namespace {

using json = nlohmann::json;

constexpr const char* kFormatName = "strata-scene";
// A tree of kMaxTreeDepth levels nests two JSON levels per tree level (node object, children
// array) plus a few for transforms and vectors; anything much deeper is not a scene.
constexpr int kMaxJsonNesting = 2 * kMaxTreeDepth + 16;
constexpr double kMaxMargin = 10.0;
constexpr size_t kMaxDescribedString = 40;

// "1:5"-style location of a 0-based byte offset: 1-based line and column (columns count bytes).
std::string lineColumn(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
  size_t lineStart = text.rfind('\n', offset == 0 ? std::string::npos : offset - 1);
  size_t column = lineStart == std::string::npos || offset == 0 ? offset + 1 : offset - lineStart;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// JSON pointer token escaping (RFC 6901): "~" -> "~0", "/" -> "~1".
std::string pointerToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// Rejects text whose brackets nest deeper than kMaxJsonNesting, before any recursive code sees
// it. Brackets inside strings do not count.
void checkNesting(const std::string& text, const std::string& source) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        throw Error(source + ": " + lineColumn(text, i) + ": JSON nested more than " +
                    std::to_string(kMaxJsonNesting) +
                    " levels deep (a scene tree may have at most " + std::to_string(kMaxTreeDepth) +
                    " levels)");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// Builds the document like json::parse (through nlohmann's DOM builder), following the events
// to know the JSON pointer of every key, and records the first key that repeats within one
// object (nlohmann would silently keep only one of them). A SAX handler rather than parse's
// callback: the callback builder rescans the parent container at every value's end, quadratic
// in the children of one node (100,000 leaves took seconds).
class DuplicateKeyFinder {
 public:
  using Dom = nlohmann::detail::json_sax_dom_parser<json>;
  explicit DuplicateKeyFinder(json& doc) : dom_(doc, true) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool v) { return value(dom_.boolean(v)); }
  bool number_integer(json::number_integer_t v) { return value(dom_.number_integer(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
  bool number_float(json::number_float_t v, const json::string_t& s) {
    return value(dom_.number_float(v, s));
  }
  bool string(json::string_t& v) { return value(dom_.string(v)); }
  bool binary(json::binary_t& v) { return value(dom_.binary(v)); }
  bool start_object(std::size_t n) {
    frames_.push_back(Frame{true, {}, {}, 0});
    return dom_.start_object(n);
  }
  bool key(json::string_t& k) {
    Frame& frame = frames_.back();
    frame.key = k;
    if (!frame.keys.insert(frame.key).second && duplicate_.empty()) duplicate_ = pointer();
    return dom_.key(k);
  }
  bool end_object() { return end(dom_.end_object()); }
  bool start_array(std::size_t n) {
    frames_.push_back(Frame{false, {}, {}, 0});
    return dom_.start_array(n);
  }
  bool end_array() { return end(dom_.end_array()); }
  template <class Exception>
  bool parse_error(std::size_t at, const std::string& token, const Exception& e) {
    return dom_.parse_error(at, token, e);  // throws e
  }

  // Pointer of the first repeated key; empty when there was none.
  const std::string& duplicate() const { return duplicate_; }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;  // objects: keys seen so far
    std::string key;             // objects: the current key
    size_t index;                // arrays: the current element
  };
  bool value(bool ok) {
    elementDone();
    return ok;
  }
  bool end(bool ok) {
    if (!frames_.empty()) frames_.pop_back();
    elementDone();
    return ok;
  }
  void elementDone() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_)
      p += "/" + (f.object ? pointerToken(f.key) : std::to_string(f.index));
    return p;
  }
  Dom dom_;
  std::vector<Frame> frames_;
  std::string duplicate_;
};

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix.
std::string parseErrorText(const json::parse_error& e) {
  std::string what = e.what();
  size_t start = what.find("parse error");
  if (start != std::string::npos) {
    size_t colon = what.find(": ", start);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

json parseJson(const std::string& text, const std::string& source) {
  checkNesting(text, source);
  json doc;
  DuplicateKeyFinder finder(doc);
  try {
    json::sax_parse(text, &finder);
  } catch (const json::parse_error& e) {
    size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    throw Error(source + ": " + lineColumn(text, offset) + ": invalid JSON: " + parseErrorText(e));
  } catch (const json::out_of_range& e) {
    // A number too large for a double ("number overflow parsing '1e999'"); nlohmann gives no
    // position, so point at the first occurrence of the quoted token.
    std::string what = e.what();
    size_t open = what.find('\'');
    size_t close = open == std::string::npos ? open : what.find('\'', open + 1);
    std::string where;
    if (close != std::string::npos) {
      size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) where = lineColumn(text, at) + ": ";
    }
    size_t bracket = what.find("] ");
    throw Error(source + ": " + where + "invalid JSON: " +
                (bracket == std::string::npos ? what : what.substr(bracket + 2)));
  }
  if (!finder.duplicate().empty())
    throw Error(source + ": " + finder.duplicate() + ": duplicate key (each key may appear once)");
  return doc;
}

// A double as people write it: 1 rather than 1.0, otherwise the shortest round-trip form.
std::string numberText(double d) {
  std::string text = json(d).dump();
  if (text.size() > 2 && text.compare(text.size() - 2, 2, ".0") == 0) text.resize(text.size() - 2);
  return text;
}

// A short description of a JSON value for messages: numbers and short strings as written,
// containers by kind and size.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::number_float: {
      double d = v.get<double>();
      if (std::isnan(d)) return "NaN";
      if (std::isinf(d)) return d > 0 ? "infinity" : "-infinity";
      return v.dump();
    }
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return v.dump();
    case json::value_t::string: {
      std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
      if (s.size() > kMaxDescribedString) s = s.substr(0, kMaxDescribedString) + "...\"";
      return s;
    }
    case json::value_t::array:
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
    case json::value_t::object:
      return "an object";
    default:
      return "a value of an unexpected kind";
  }
}

const char* const kCommonFields[] = {"id", "type", "name", "transform", "color", "visible"};

bool typeHasField(NodeKind kind, const std::string& key) {
  for (const std::string& f : nodeKindInfo(kind).fields)
    if (key == f) return true;
  return false;
}
bool anyTypeHasField(const std::string& key) {
  for (const NodeKindInfo& info : nodeKindTable())
    if (typeHasField(info.kind, key)) return true;
  return false;
}
std::string typeList() {
  std::string list;
  for (const NodeKindInfo& info : nodeKindTable())
    list += (list.empty() ? "" : ", ") + std::string(info.name);
  return list;
}

class SceneReader {
 public:
  SceneReader(const std::string& source, const std::string& baseDir, SceneLoadReport* report,
              const MeshReadOptions& meshOptions, MissingMeshes missing)
      : source_(source),
        baseDir_(baseDir),
        report_(report),
        meshOptions_(meshOptions),
        missing_(missing) {}

  Scene read(const json& doc) {
    if (!doc.is_object()) fail("", "expected a JSON object at the top level, got " + describe(doc));
    readFormatAndVersion(doc);
    Scene scene;
    for (auto it = doc.begin(); it != doc.end(); ++it) {
      const std::string& key = it.key();
      std::string at = "/" + pointerToken(key);
      if (key == "format" || key == "version") continue;
      if (key == "unit") {
        nonEmptyString(*it, at);
        scene.settings.unit = readableString(*it, at);
      } else if (key == "settings")
        readSettings(*it, at, &scene.settings);
      else if (key != "root" && key != "measurements")
        fail(at, "unknown field \"" + key + "\"");
    }
    auto root = doc.find("root");
    if (root == doc.end()) fail("/root", "missing required field (the scene's root node)");
    size_t rootEntry = readNode(*root, "/root", 1, kNoParent, 0);
    checkGraph(rootEntry);
    loadMeshes();
    scene.root = entries_[rootEntry].node;
    if (auto m = doc.find("measurements"); m != doc.end())
      readMeasurements(*m, "/measurements", scene.root, &scene.measurements);
    return scene;
  }

 private:
  // One node as read, with what the graph checks need.
  // Pointers are rebuilt from the parent links when a message needs one: storing each node's
  // full pointer would cost depth x nodes memory, which a hostile file can make huge.
  struct Entry {
    std::shared_ptr<Node> node;
    std::vector<size_t> children;  // entry indices
    size_t parent;                 // entry index; kNoParent for the root
    size_t indexInParent;          // position in the parent's children
  };
  static constexpr size_t kNoParent = static_cast<size_t>(-1);

  std::string pointerOf(size_t entry) const {
    std::vector<size_t> path;
    for (size_t e = entry; entries_[e].parent != kNoParent; e = entries_[e].parent)
      path.push_back(entries_[e].indexInParent);
    std::string p = "/root";
    for (auto it = path.rbegin(); it != path.rend(); ++it) p += "/children/" + std::to_string(*it);
    return p;
  }

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw Error(source_ + ": " + (pointer.empty() ? "" : pointer + ": ") + what);
  }
  void warn(const std::string& pointer, const std::string& what) const {
    if (report_) report_->warnings.push_back(source_ + ": " + pointer + ": " + what);
  }

  // ---- values ----------------------------------------------------------------------------

  const std::string& string(const json& v, const std::string& at) const {
    if (!v.is_string()) fail(at, "expected a string, got " + describe(v));
    return v.get_ref<const std::string&>();
  }
  // A name or unit shown to people (messages on a terminal, the editor): control characters
  // (an escape sequence in a name recoloured the terminal and retitled its window) replaced by
  // '?', with a warning.
  std::string readableString(const json& v, const std::string& at) const {
    const std::string& in = string(v, at);
    std::string s;
    s.reserve(in.size());
    size_t replaced = 0;
    for (size_t i = 0; i < in.size(); ++i) {
      const auto c = static_cast<unsigned char>(in[i]);
      // C0 controls and DEL, and C1 controls (U+0080 .. U+009F: 0xC2 0x80 .. 0xC2 0x9F, CSI
      // among them), each one '?'.
      const bool c1 = c == 0xC2 && i + 1 < in.size() &&
                      static_cast<unsigned char>(in[i + 1]) >= 0x80 &&
                      static_cast<unsigned char>(in[i + 1]) <= 0x9F;
      if (c < 0x20 || c == 0x7f || c1) {
        s += '?';
        ++replaced;
        if (c1) ++i;
      } else {
        s += in[i];
      }
    }
    if (replaced > 0)
      warn(at, std::to_string(replaced) + " control character" + (replaced == 1 ? "" : "s") +
                   " replaced by '?'");
    return s;
  }
  const std::string& nonEmptyString(const json& v, const std::string& at) const {
    const std::string& s = string(v, at);
    if (s.empty()) fail(at, "expected a non-empty string");
    return s;
  }
  bool boolean(const json& v, const std::string& at) const {
    if (!v.is_boolean()) fail(at, "expected true or false, got " + describe(v));
    return v.get<bool>();
  }
  // An integer in [lo, hi]; `expected` describes the range for the message.
  int64_t integer(const json& v, const std::string& at, int64_t lo, int64_t hi,
                  const std::string& expected) const {
    if (!v.is_number_integer()) fail(at, "expected " + expected + ", got " + describe(v));
    if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(hi))
      fail(at, "expected " + expected + ", got " + describe(v));
    int64_t x = v.get<int64_t>();
    if (x < lo || x > hi) fail(at, "expected " + expected + ", got " + describe(v));
    return x;
  }
  double number(const json& v, const std::string& at, const std::string& expected) const {
    if (!v.is_number()) fail(at, "expected " + expected + ", got " + describe(v));
    double d = v.get<double>();
    if (!std::isfinite(d)) fail(at, "expected a finite number, got " + describe(v));
    return d;
  }
  double positive(const json& v, const std::string& at) const {
    double d = number(v, at, "a positive number");
    if (!(d > 0)) fail(at, "expected a positive number, got " + describe(v));
    return d;
  }
  double inRange(const json& v, const std::string& at, double lo, double hi) const {
    std::string expected = "a number from " + numberText(lo) + " to " + numberText(hi);
    double d = number(v, at, expected);
    if (d < lo || d > hi) fail(at, "expected " + expected + ", got " + describe(v));
    return d;
  }
  // Exactly three numbers, each checked by `component(value, pointer)`.
  template <typename Check>
  glm::dvec3 vec3(const json& v, const std::string& at, Check component) const {
    if (!v.is_array() || v.size() != 3)
      fail(at, "expected an array of 3 numbers, got " + describe(v));
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) out[i] = component(v[i], at + "/" + std::to_string(i));
    return out;
  }
  glm::dvec3 anyVec3(const json& v, const std::string& at) const {
    return vec3(v, at,
                [this](const json& c, const std::string& p) { return number(c, p, "a number"); });
  }
  void requireObject(const json& v, const std::string& at) const {
    if (!v.is_object()) fail(at, "expected an object, got " + describe(v));
  }

  // ---- document level ----------------------------------------------------------------------

  void readFormatAndVersion(const json& doc) const {
    auto format = doc.find("format");
    if (format == doc.end())
      fail("/format", std::string("missing required field (expected \"") + kFormatName +
                          "\"; is this a Strata scene file?)");
    if (!format->is_string() || format->get<std::string>() != kFormatName)
      fail("/format", std::string("expected \"") + kFormatName + "\", got " + describe(*format) +
                          " (is this a Strata scene file?)");
    auto version = doc.find("version");
    if (version == doc.end()) fail("/version", "missing required field (the format version)");
    if (!version->is_number_integer())
      fail("/version", "expected an integer, got " + describe(*version));
    if (version->is_number_unsigned() &&
        version->get<uint64_t>() > static_cast<uint64_t>(kSceneFormatVersion))
      fail("/version",
           "version " + version->dump() + " is newer than this build of Strata reads (" +
               std::to_string(kSceneFormatVersion) + "); open the file with a newer Strata");
    if (version->get<int64_t>() < 1)
      fail("/version", "unsupported version " + version->dump() + " (versions start at 1)");
  }

  void readSettings(const json& v, const std::string& at, SceneSettings* settings) const {
    requireObject(v, at);
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string& key = it.key();
      std::string p = at + "/" + pointerToken(key);
      if (key == "resolution") {
        settings->resolution =
            static_cast<int>(integer(*it, p, kMinResolution, kMaxResolution,
                                     "an integer from " + std::to_string(kMinResolution) + " to " +
                                         std::to_string(kMaxResolution)));
      } else if (key == "margin") {
        settings->margin = inRange(*it, p, 0.0, kMaxMargin);
      } else if (key == "bounds") {
        readBounds(*it, p, &settings->bounds);
        settings->hasBounds = true;
      } else if (key == "maxLeaves") {
        // Files written before the ceiling (up to 2^40) still open, held to it, with a word.
        const int64_t asked = integer(*it, p, 1, int64_t(1) << 40,
                                      "an integer from 1 to " + std::to_string(kMaxLeavesSetting));
        settings->maxLeaves = static_cast<uint64_t>(std::min(asked, kMaxLeavesSetting));
        if (asked > kMaxLeavesSetting)
          warn(p, std::to_string(asked) + " leaves held to " + std::to_string(kMaxLeavesSetting) +
                      ", the most a scene file may allow; more with the command line's "
                      "--max-leaves");
      } else {
        fail(p, "unknown field \"" + key + "\"");
      }
    }
  }

  void readBounds(const json& v, const std::string& at, Bounds* bounds) const {
    requireObject(v, at);
    for (auto it = v.begin(); it != v.end(); ++it)
      if (it.key() != "min" && it.key() != "max")
        fail(at + "/" + pointerToken(it.key()), "unknown field \"" + it.key() + "\"");
    auto min = v.find("min");
    auto max = v.find("max");
    if (min == v.end()) fail(at + "/min", "missing required field (the box's low corner)");
    if (max == v.end()) fail(at + "/max", "missing required field (the box's high corner)");
    bounds->min = anyVec3(*min, at + "/min");
    bounds->max = anyVec3(*max, at + "/max");
    for (int i = 0; i < 3; ++i)
      if (!(bounds->max[i] > bounds->min[i]))
        fail(at + "/max/" + std::to_string(i), "expected a number greater than min (" +
                                                   numberText(bounds->min[i]) + "), got " +
                                                   describe((*max)[i]));
  }

  // ---- nodes -------------------------------------------------------------------------------

  // Reads the node at `at` (tree level `depth`, the root being 1) and its subtree; returns its
  // entry index.
  size_t readNode(const json& v, const std::string& at, int depth, size_t parent,
                  size_t indexInParent) {
    if (!v.is_object()) fail(at, "expected a node object, got " + describe(v));
    if (depth > kMaxTreeDepth)
      fail(at, "the tree is more than " + std::to_string(kMaxTreeDepth) + " levels deep");
    auto node = std::make_shared<Node>();

    auto type = v.find("type");
    if (type == v.end()) fail(at + "/type", "missing required field (the node type)");
    const std::string& typeName = string(*type, at + "/type");
    if (!kindFromName(typeName, &node->kind))
      fail(at + "/type",
           "unknown node type " + describe(*type) + " (expected one of " + typeList() + ")");

    auto id = v.find("id");
    if (id == v.end())
      fail(at + "/id", "missing required field (a positive integer, unique in the file)");
    node->id = static_cast<NodeId>(
        integer(*id, at + "/id", 1, UINT32_MAX, "a positive integer id below 2^32"));
    auto [existing, inserted] = byId_.emplace(node->id, entries_.size());
    if (!inserted)
      fail(at + "/id", "duplicate id " + std::to_string(node->id) + " (also used by the node at " +
                           pointerOf(existing->second) + ")");

    for (auto it = v.begin(); it != v.end(); ++it) checkFieldApplies(node->kind, it.key(), at);

    size_t self = entries_.size();
    entries_.push_back(Entry{node, {}, parent, indexInParent});

    if (auto f = v.find("name"); f != v.end()) node->name = readableString(*f, at + "/name");
    if (auto f = v.find("transform"); f != v.end())
      node->transform = readTransform(*f, at + "/transform");
    if (auto f = v.find("color"); f != v.end()) {
      glm::dvec3 c = vec3(*f, at + "/color", [this](const json& x, const std::string& p) {
        return inRange(x, p, 0.0, 1.0);
      });
      node->color = glm::vec3(c);
    }
    if (auto f = v.find("visible"); f != v.end()) node->visible = boolean(*f, at + "/visible");

    if (const char* key = nodeKindInfo(node->kind).amountKey) {
      // A modifier's amount (version 2): required, a distance (offset) or a positive length.
      auto f = v.find(key);
      const std::string p = at + "/" + key;
      if (f == v.end()) fail(p, std::string("missing required field (the ") + key + ")");
      node->amount =
          modifierOf(node->kind) == Modifier::Offset ? number(*f, p, "a number") : positive(*f, p);
    }
    if (isOperation(node->kind)) {
      if (auto f = v.find("children"); f != v.end()) {
        if (!f->is_array())
          fail(at + "/children", "expected an array of nodes, got " + describe(*f));
        for (size_t i = 0; i < f->size(); ++i) {
          size_t child =
              readNode((*f)[i], at + "/children/" + std::to_string(i), depth + 1, self, i);
          entries_[self].children.push_back(child);
          node->children.push_back(entries_[child].node);
        }
      }
      if (auto f = v.find("opening"); f != v.end()) {
        // A shell's opening (version 3): the id of a part inside the shell.
        node->opening = static_cast<NodeId>(
            integer(*f, at + "/opening", 1, UINT32_MAX, "a positive integer id"));
        if (node->opening == node->id || !findNode(node, node->opening))
          fail(at + "/opening", "names node " + std::to_string(node->opening) +
                                    ", which is not inside this shell (an opening must be a "
                                    "part the shell holds)");
      }
      if (patternOf(node->kind) != Pattern::None) readPattern(v, at, *node);
    } else if (isPrimitive(node->kind)) {
      readPrimitiveParams(v, at, node->kind, &node->params);
    } else if (node->kind == NodeKind::Mesh) {
      auto path = v.find("path");
      if (path == v.end()) fail(at + "/path", "missing required field (the mesh file)");
      node->meshPath = nonEmptyString(*path, at + "/path");
      if (node->meshPath.find('\0') != std::string::npos)
        fail(at + "/path", "the path contains a NUL character");
      if (auto hash = v.find("hash"); hash != v.end()) {
        node->meshHash = string(*hash, at + "/hash");
        if (!isContentHash(node->meshHash))
          fail(at + "/hash",
               "expected \"fnv1a64:\" followed by 16 lowercase hex digits, got " + describe(*hash));
      }
      if (auto open = v.find("open"); open != v.end())
        node->meshOpen = boolean(*open, at + "/open");
      meshEntries_.push_back(self);
    } else if (node->kind == NodeKind::Instance) {
      auto of = v.find("of");
      if (of == v.end()) fail(at + "/of", "missing required field (the id of the instanced node)");
      node->instanceOf =
          static_cast<NodeId>(integer(*of, at + "/of", 1, UINT32_MAX, "a positive integer id"));
    }
    return self;
  }

  void checkFieldApplies(NodeKind kind, const std::string& key, const std::string& at) const {
    for (const char* common : kCommonFields)
      if (key == common) return;
    if (typeHasField(kind, key)) return;
    std::string p = at + "/" + pointerToken(key);
    if (key == "children")
      fail(p, std::string("a ") + kindName(kind) +
                  " node cannot have children (only operations and modifiers can)");
    if (anyTypeHasField(key))
      fail(p, "field \"" + key + "\" does not apply to a " + kindName(kind) + " node");
    fail(p, "unknown field \"" + key + "\"");
  }

  Transform readTransform(const json& v, const std::string& at) const {
    requireObject(v, at);
    Transform t;
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string& key = it.key();
      std::string p = at + "/" + pointerToken(key);
      if (key == "translate") {
        t.translate = anyVec3(*it, p);
      } else if (key == "rotate") {
        t.rotateDegrees = anyVec3(*it, p);
      } else if (key == "scale") {
        t.scale = vec3(*it, p, [this](const json& c, const std::string& cp) {
          double d = number(c, cp, "a nonzero number");
          if (d == 0) fail(cp, "expected a nonzero number, got " + describe(c));
          return d;
        });
      } else {
        fail(p, "unknown field \"" + key + "\"");
      }
    }
    return t;
  }

  // Reads the fields the primitive's table entry lists, starting from its defaults.
  void readPrimitiveParams(const json& v, const std::string& at, NodeKind kind,
                           PrimitiveParams* params) const {
    const PrimitiveInfo& info = *primitiveInfo(kind);
    *params = info.defaults;
    for (const PrimitiveParam& param : info.params) {
      auto f = v.find(param.key);
      if (f == v.end()) continue;
      const std::string p = at + "/" + param.key;
      auto inRange = [&](const json& x, const std::string& xp) {
        if (param.minimum == ParamMinimum::Positive) return positive(x, xp);
        double d = number(x, xp, "a number >= 0");
        if (d < 0) fail(xp, "expected a number >= 0, got " + describe(x));
        return d;
      };
      if (param.scalar) params->*param.scalar = inRange(*f, p);
      if (param.vector) params->*param.vector = vec3(*f, p, inRange);
    }
    if (auto f = v.find("segments"); f != v.end()) {
      std::string expected =
          "0 (automatic) or an integer from 3 to " + std::to_string(kMaxSegments);
      int64_t s = integer(*f, at + "/segments", 0, kMaxSegments, expected);
      if (s == 1 || s == 2)
        fail(at + "/segments", "expected " + expected + ", got " + describe(*f));
      params->segments = static_cast<int>(s);
    }
    if (info.relations) {
      ParamProblem problem = info.relations(*params);
      if (!problem.message.empty()) {
        const char* where = problem.keys.back();
        for (const char* key : problem.keys)
          if (v.contains(key)) {
            where = key;
            break;
          }
        fail(at + "/" + where, problem.message);
      }
    }
  }

  // Measurements (version 4): [{"points": [{"on": id, "at": [x, y, z]}, ...]}], 2 or 3 points,
  // each in world coordinates, on the node `on` (a leaf of the tree) or fixed in the world.
  void readMeasurements(const json& v, const std::string& at, const NodePtr& root,
                        std::vector<Measurement>* out) const {
    if (!v.is_array()) fail(at, "expected an array of measurements, got " + describe(v));
    if (v.size() > kMaxMeasurements)
      fail(at, "more than " + std::to_string(kMaxMeasurements) + " measurements");
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string mp = at + "/" + std::to_string(i);
      requireObject(v[i], mp);
      for (auto it = v[i].begin(); it != v[i].end(); ++it)
        if (it.key() != "points") fail(mp + "/" + pointerToken(it.key()), "unknown field");
      auto points = v[i].find("points");
      if (points == v[i].end()) fail(mp + "/points", "missing required field (2 or 3 points)");
      if (!points->is_array() || points->size() < 2 || points->size() > 3)
        fail(mp + "/points", "expected an array of 2 or 3 points, got " + describe(*points));
      Measurement m;
      for (size_t k = 0; k < points->size(); ++k) {
        const json& p = (*points)[k];
        const std::string pp = mp + "/points/" + std::to_string(k);
        requireObject(p, pp);
        for (auto it = p.begin(); it != p.end(); ++it)
          if (it.key() != "on" && it.key() != "at")
            fail(pp + "/" + pointerToken(it.key()), "unknown field");
        auto where = p.find("at");
        if (where == p.end()) fail(pp + "/at", "missing required field (the point)");
        const glm::dvec3 world = anyVec3(*where, pp + "/at");
        NodeId on = 0;
        if (auto f = p.find("on"); f != p.end()) {
          on = static_cast<NodeId>(integer(*f, pp + "/on", 1, UINT32_MAX, "a positive integer id"));
          if (!findNode(root, on))
            fail(pp + "/on", "names node " + std::to_string(on) + ", which is not in the scene");
        }
        m.points.push_back(attachPoint(root, on, world));
      }
      out->push_back(std::move(m));
    }
  }

  // A pattern's parameters (version 4): array `counts` and `step` (required); circular array
  // `count` (required), `axis` ("z"), `angle` (360), `center` (origin); mirror `axis`
  // (required), `center` (origin), `keep` (true).
  void readPattern(const json& v, const std::string& at, Node& node) const {
    const Pattern pattern = patternOf(node.kind);
    PatternParams& p = node.pattern;
    const std::string countText = "an integer from 1 to " + std::to_string(kMaxPatternCount);
    auto required = [&](const char* key) {
      auto f = v.find(key);
      if (f == v.end())
        fail(at + "/" + key, std::string("missing required field (the ") + key + ")");
      return f;
    };
    auto readAxis = [&](const json& x) {
      const std::string& name = string(x, at + "/axis");
      if (!axisFromName(name, &p.axis))
        fail(at + "/axis", "expected \"x\", \"y\" or \"z\", got " + describe(x));
    };
    if (pattern == Pattern::Array) {
      p.counts = glm::ivec3(
          vec3(*required("counts"), at + "/counts", [&](const json& x, const std::string& xp) {
            return double(integer(x, xp, 1, kMaxPatternCount, countText));
          }));
      if (patternCopies(pattern, p) > kMaxPatternCopies)
        fail(at + "/counts", "the counts make " + std::to_string(patternCopies(pattern, p)) +
                                 " copies, more than " + std::to_string(kMaxPatternCopies));
      p.step = anyVec3(*required("step"), at + "/step");
    } else if (pattern == Pattern::Circular) {
      p.count = int(integer(*required("count"), at + "/count", 1, kMaxPatternCount, countText));
      if (auto f = v.find("axis"); f != v.end()) readAxis(*f);
      if (auto f = v.find("angle"); f != v.end()) {
        p.angle = inRange(*f, at + "/angle", -360.0, 360.0);
        if (p.angle == 0.0 && p.count > 1)
          fail(at + "/angle", "expected a non-zero angle for more than one copy, got 0");
      }
    } else {
      readAxis(*required("axis"));
      if (auto f = v.find("keep"); f != v.end()) p.keepOriginal = boolean(*f, at + "/keep");
    }
    if (pattern != Pattern::Array)
      if (auto f = v.find("center"); f != v.end()) p.center = anyVec3(*f, at + "/center");
  }

  static bool isContentHash(const std::string& s) {
    const std::string prefix = "fnv1a64:";
    if (s.size() != prefix.size() + 16 || s.compare(0, prefix.size(), prefix) != 0) return false;
    return std::all_of(s.begin() + prefix.size(), s.end(),
                       [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
  }

  // ---- graph checks ------------------------------------------------------------------------

  // Instance targets exist; no cycles through instances; depth through instances within
  // kMaxTreeDepth. Iterative, memoised depth-first search over tree and instance edges.
  void checkGraph(size_t rootEntry) const {
    for (size_t i = 0; i < entries_.size(); ++i)
      if (const Node& n = *entries_[i].node;
          n.kind == NodeKind::Instance && !byId_.count(n.instanceOf))
        fail(pointerOf(i) + "/of", "refers to node " + std::to_string(n.instanceOf) +
                                       ", which does not exist in this file");

    enum class State : uint8_t { Unvisited, Active, Done };
    std::vector<State> state(entries_.size(), State::Unvisited);
    std::vector<int> depth(entries_.size(), 0);
    struct Step {
      size_t entry;
      size_t nextEdge;
    };
    auto edgeCount = [this](size_t e) {
      return entries_[e].node->kind == NodeKind::Instance ? size_t{1} : entries_[e].children.size();
    };
    auto edge = [this](size_t e, size_t i) {
      const Node& n = *entries_[e].node;
      return n.kind == NodeKind::Instance ? byId_.at(n.instanceOf) : entries_[e].children[i];
    };
    std::vector<Step> stack{{rootEntry, 0}};
    state[rootEntry] = State::Active;
    while (!stack.empty()) {
      Step& top = stack.back();
      size_t count = edgeCount(top.entry);
      if (top.nextEdge < count) {
        size_t target = edge(top.entry, top.nextEdge++);
        if (state[target] == State::Active) reportCycle(stack, target);
        if (state[target] == State::Unvisited) {
          state[target] = State::Active;
          stack.push_back(Step{target, 0});
        }
        continue;
      }
      int d = entries_[top.entry].node->kind == NodeKind::Instance ? 0 : 1;
      int deepest = 0;
      for (size_t i = 0; i < count; ++i) deepest = std::max(deepest, depth[edge(top.entry, i)]);
      d += deepest;
      if (d > kMaxTreeDepth)
        fail(pointerOf(top.entry), "the tree below this node is " + std::to_string(d) +
                                       " levels deep counting through instances; the limit is " +
                                       std::to_string(kMaxTreeDepth));
      depth[top.entry] = d;
      state[top.entry] = State::Done;
      stack.pop_back();
    }
  }

  // The search stack from `target` to its top, plus the edge back to `target`, is a cycle; it
  // contains at least one instance edge (tree edges alone cannot close a cycle). Names it.
  template <typename Step>
  [[noreturn]] void reportCycle(const std::vector<Step>& stack, size_t target) const {
    size_t first = 0;
    while (stack[first].entry != target) ++first;
    std::vector<size_t> cycle;
    for (size_t i = first; i < stack.size(); ++i) cycle.push_back(stack[i].entry);
    size_t start = 0;
    while (entries_[cycle[start]].node->kind != NodeKind::Instance) ++start;
    std::rotate(cycle.begin(), cycle.begin() + static_cast<std::ptrdiff_t>(start), cycle.end());
    std::string path;
    for (size_t e : cycle) path += std::to_string(entries_[e].node->id) + " -> ";
    path += std::to_string(entries_[cycle.front()].node->id);
    fail(pointerOf(cycle.front()) + "/of",
         "instance cycle " + path +
             " (an instance may not refer to itself or to a node that contains it)");
  }

  // ---- meshes ------------------------------------------------------------------------------

  void loadMeshes() {
    struct Loaded {
      std::shared_ptr<const TriangleMesh> mesh;
      std::string hash;
      std::string error;  // why it could not be read (MissingMeshes::Keep)
      bool open = false;  // refused only for being open
    };
    // By resolved path and whether the node accepts it open: each file is read once either way.
    std::map<std::pair<std::string, bool>, Loaded> cache;
    for (size_t index : meshEntries_) {
      Node& node = *entries_[index].node;
      std::string at = pointerOf(index);
      std::filesystem::path path(node.meshPath);
      if (path.is_relative() && !baseDir_.empty()) path = std::filesystem::path(baseDir_) / path;
      std::string resolved = path.lexically_normal().string();
      MeshReadOptions options = meshOptions_;
      options.allowOpen = options.allowOpen || node.meshOpen;
      auto found = cache.find({resolved, node.meshOpen});
      if (found == cache.end()) {
        Loaded loaded;
        try {
          MeshReadReport meshReport;
          loaded.mesh =
              std::make_shared<const TriangleMesh>(readMeshFile(resolved, options, &meshReport));
          loaded.hash = hashFile(resolved);
          for (const std::string& w : meshReport.warnings) warn(at + "/path", w);
        } catch (const Error& error) {
          if (missing_ == MissingMeshes::Refuse) fail(at + "/path", error.what());
          // Kept without its mesh: an empty one (readers never give one) marks it missing.
          loaded.mesh = std::make_shared<const TriangleMesh>();
          loaded.hash.clear();
          loaded.error = error.what();
          loaded.open = dynamic_cast<const OpenMeshRefused*>(&error) != nullptr;
        }
        found = cache.emplace(std::make_pair(resolved, node.meshOpen), std::move(loaded)).first;
      }
      node.mesh = found->second.mesh;
      std::string label = "mesh node " + std::to_string(node.id) +
                          (node.name.empty() ? "" : " \"" + node.name + "\"");
      if (!found->second.error.empty()) {
        node.meshProblem = found->second.error;
        node.meshRefusedAsOpen = found->second.open;
        warn(at + "/path",
             label + " is kept without its mesh (" + found->second.error +
                 "): nothing of it is evaluated, and its path and hash are saved as "
                 "they were; " +
                 (found->second.open ? "take it as an open mesh (the editor's inspector, or "
                                       "\"open\": true here), repair the file, or delete the node"
                                     : "put the file back, or replace or delete the node"));
        continue;  // the recorded hash stays: it still names the content meant
      }
      if (node.meshHash.empty())
        warn(at, label + " records no hash for \"" + node.meshPath +
                     "\", so changes to the file cannot be detected (its hash is now " +
                     found->second.hash + ")");
      else if (node.meshHash != found->second.hash)
        warn(at, label + ": \"" + node.meshPath + "\" changed since the scene was saved (hash " +
                     found->second.hash + ", recorded " + node.meshHash + ")");
      node.meshHash = found->second.hash;  // the node now describes the content it holds
    }
  }

  std::string source_;
  std::string baseDir_;
  SceneLoadReport* report_;
  MeshReadOptions meshOptions_;
  MissingMeshes missing_;
  std::vector<Entry> entries_;  // in document order; the root first
  std::unordered_map<NodeId, size_t> byId_;
  std::vector<size_t> meshEntries_;
};

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName, const std::string& baseDir,
                 SceneLoadReport* report, const MeshReadOptions& meshOptions,
                 MissingMeshes missing) {
  json doc = parseJson(text, sourceName);
  return SceneReader(sourceName, baseDir, report, meshOptions, missing).read(doc);
}

}  // namespace strata
