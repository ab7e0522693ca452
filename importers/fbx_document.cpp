#include "importers/fbx_document.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include <zlib.h>

#include "engine/core/text_lines.h"

namespace importers::fbx {

const Node* Node::child(std::string_view childName) const {
  for (const Node& c : children)
    if (c.name == childName) return &c;
  return nullptr;
}

std::optional<double> Node::number(size_t i) const {
  if (i >= values.size()) return std::nullopt;
  if (const auto* d = std::get_if<double>(&values[i])) return *d;
  if (const auto* n = std::get_if<int64_t>(&values[i])) return double(*n);
  return std::nullopt;
}

std::optional<int64_t> Node::integer(size_t i) const {
  if (i >= values.size()) return std::nullopt;
  if (const auto* n = std::get_if<int64_t>(&values[i])) return *n;
  // 2^63 is the first double past int64's range.
  if (const auto* d = std::get_if<double>(&values[i]); d && std::trunc(*d) == *d && std::abs(*d) < 9.2e18) return int64_t(*d);
  return std::nullopt;
}

std::string_view Node::text(size_t i) const {
  if (i >= values.size()) return {};
  if (const auto* s = std::get_if<std::string>(&values[i])) return *s;
  return {};
}

std::vector<double> Node::numbers(size_t i) const {
  if (i >= values.size()) return {};
  if (const auto* d = std::get_if<std::vector<double>>(&values[i])) return *d;
  if (const auto* n = std::get_if<std::vector<int64_t>>(&values[i])) return std::vector<double>(n->begin(), n->end());
  return {};
}

bool Node::integers(size_t i, std::vector<int64_t>& out) const {
  out.clear();
  if (i >= values.size()) return false;
  if (const auto* n = std::get_if<std::vector<int64_t>>(&values[i])) {
    out = *n;
    return true;
  }
  if (const auto* d = std::get_if<std::vector<double>>(&values[i])) {
    out.reserve(d->size());
    for (double x : *d) {
      if (!(std::trunc(x) == x && std::abs(x) < 9.2e18)) return false;
      out.push_back(int64_t(x));
    }
    return true;
  }
  return false;
}

namespace {

constexpr char kBinaryMagic[] = "Kaydara FBX Binary  ";  // then '\0', 0x1a, 0x00 and the version
constexpr size_t kBinaryHeaderBytes = 27;
// Real files nest about ten deep; the bound keeps recursion off the stack's end.
constexpr size_t kMaxDepth = 64;
// The first FBX whose connections number objects (FBX 2011).
constexpr uint32_t kOldestVersion = 7000;

eng::Error malformed(const std::string& name, const std::string& what) {
  return eng::makeError(eng::ErrorKind::Malformed, name + ": " + what);
}

uint64_t readLittle(const uint8_t* p, size_t n) {
  uint64_t v = 0;
  for (size_t k = 0; k < n; ++k) v |= uint64_t(p[k]) << (8 * k);
  return v;
}

class BinaryReader {
 public:
  BinaryReader(std::span<const uint8_t> bytes, const std::string& name, eng::LoadBudget& budget, uint32_t version)
      : bytes_(bytes), name_(name), budget_(budget), wide_(version >= 7500) {}

  // The records from `at` up to `end`, or to a null record, into `parent`.
  eng::Result<size_t> readList(Node& parent, size_t at, size_t end, size_t depth) {
    if (depth > kMaxDepth) return malformed(name_, "nodes nested deeper than " + std::to_string(kMaxDepth) + " at byte " + std::to_string(at));
    const size_t header = wide_ ? 25 : 13;
    while (at < end) {
      if (end - at < header)
        return malformed(name_, "a node record at byte " + std::to_string(at) + " is cut short (" + std::to_string(end - at) +
                                    " bytes left, its header takes " + std::to_string(header) + ")");
      const size_t field = wide_ ? 8 : 4;
      const uint64_t endOffset = readLittle(&bytes_[at], field);
      const uint64_t count = readLittle(&bytes_[at + field], field);
      const uint64_t listBytes = readLittle(&bytes_[at + 2 * field], field);
      const size_t nameBytes = bytes_[at + 3 * field];
      if (endOffset == 0 && count == 0 && listBytes == 0 && nameBytes == 0) return at + header;  // the null record ends a list
      const std::string where = "the node at byte " + std::to_string(at);
      if (endOffset <= at || endOffset > end)
        return malformed(name_, where + " ends at byte " + std::to_string(endOffset) + ", outside " + std::to_string(at) + ".." +
                                    std::to_string(end));
      const size_t nodeEnd = size_t(endOffset);
      const size_t valuesAt = at + header + nameBytes;
      if (valuesAt > nodeEnd || nodeEnd - valuesAt < listBytes)
        return malformed(name_, where + ": its name and " + std::to_string(listBytes) + " bytes of values run past its end (byte " +
                                    std::to_string(nodeEnd) + ")");
      // Each value takes two bytes at least: a count past that cannot be true.
      if (count > listBytes / 2)
        return malformed(name_, where + " claims " + std::to_string(count) + " values in " + std::to_string(listBytes) + " bytes");
      ENG_TRY(charge(sizeof(Node) + count * sizeof(Value), "FBX node"));
      Node& node = parent.children.emplace_back();
      node.name.assign(reinterpret_cast<const char*>(&bytes_[at + header]), nameBytes);
      const size_t valuesEnd = valuesAt + size_t(listBytes);
      size_t v = valuesAt;
      node.values.reserve(size_t(count));
      for (uint64_t k = 0; k < count; ++k) {
        auto next = readValue(node, v, valuesEnd);
        if (!next) return next.error();
        v = *next;
      }
      if (v != valuesEnd)
        return malformed(name_, "node '" + eng::shownText(node.name) + "' at byte " + std::to_string(at) + ": its values take " +
                                    std::to_string(v - valuesAt) + " bytes, its header says " + std::to_string(listBytes));
      if (valuesEnd < nodeEnd) ENG_TRY(readList(node, valuesEnd, nodeEnd, depth + 1));
      at = nodeEnd;
    }
    return at;
  }

 private:
  eng::Result<size_t> readValue(Node& node, size_t at, size_t end) {
    const std::string where = "node '" + eng::shownText(node.name) + "': the value at byte " + std::to_string(at);
    if (at >= end) return malformed(name_, where + " is past its node's values");
    const char type = char(bytes_[at++]);
    const size_t left = end - at;
    auto scalar = [&](size_t n) -> eng::Result<const uint8_t*> {
      if (left < n) return malformed(name_, where + " is cut short");
      return &bytes_[at];
    };
    switch (type) {
      case 'C': case 'Y': case 'I': case 'L': {
        const size_t n = type == 'C' ? 1 : type == 'Y' ? 2 : type == 'I' ? 4 : 8;
        const uint8_t* p = ENG_TRY_VALUE(scalar(n));
        const uint64_t raw = readLittle(p, n);
        // Sign-extended from its width.
        const int64_t value = n == 8 ? int64_t(raw) : n == 1 ? int64_t(raw != 0) : int64_t(raw << (64 - 8 * n)) >> (64 - 8 * n);
        node.values.emplace_back(value);
        return at + n;
      }
      case 'F': case 'D': {
        const size_t n = type == 'F' ? 4 : 8;
        const uint8_t* p = ENG_TRY_VALUE(scalar(n));
        const uint64_t raw = readLittle(p, n);
        double value = 0.0;
        if (n == 4) {
          float f = 0.0f;
          const auto bits = uint32_t(raw);
          std::memcpy(&f, &bits, 4);
          value = f;
        } else {
          std::memcpy(&value, &raw, 8);
        }
        node.values.emplace_back(value);
        return at + n;
      }
      case 'S': case 'R': {
        const uint8_t* p = ENG_TRY_VALUE(scalar(4));
        const uint64_t length = readLittle(p, 4);
        if (left - 4 < length)
          return malformed(name_, where + ": a string of " + std::to_string(length) + " bytes with " + std::to_string(left - 4) + " left");
        ENG_TRY(charge(size_t(length), "FBX string"));
        node.values.emplace_back(std::string(reinterpret_cast<const char*>(p + 4), size_t(length)));
        return at + 4 + size_t(length);
      }
      case 'f': case 'd': case 'l': case 'i': case 'b': return readArray(node, type, at, left, where);
      default:
        return malformed(name_, where + " has the unknown type '" + eng::shownText(std::string_view(&type, 1)) + "'");
    }
  }

  eng::Result<size_t> readArray(Node& node, char type, size_t at, size_t left, const std::string& where) {
    if (left < 12) return malformed(name_, where + ": an array header cut short");
    const uint64_t length = readLittle(&bytes_[at], 4);
    const uint64_t encoding = readLittle(&bytes_[at + 4], 4);
    const uint64_t stored = readLittle(&bytes_[at + 8], 4);
    const size_t each = type == 'd' || type == 'l' ? 8 : type == 'b' ? 1 : 4;
    const uint64_t raw = length * each;  // below 2^35: no overflow
    if (left - 12 < stored)
      return malformed(name_, where + ": an array of " + std::to_string(stored) + " stored bytes with " + std::to_string(left - 12) + " left");
    if (encoding == 0 && stored != raw)
      return malformed(name_, where + ": " + std::to_string(length) + " elements of " + std::to_string(each) + " bytes stored in " +
                                  std::to_string(stored));
    if (encoding > 1) return malformed(name_, where + ": array encoding " + std::to_string(encoding) + " (0 plain, 1 zlib)");
    // What it inflates to and what it is kept as, before either is made.
    ENG_TRY(charge(size_t(length), each + 8, "FBX array"));
    const uint8_t* data = &bytes_[at + 12];
    std::vector<uint8_t> inflated;
    if (encoding == 1) {
      inflated.resize(size_t(raw));
      uLongf made = uLongf(raw);
      const int z = uncompress(inflated.data(), &made, data, uLong(stored));
      if (z != Z_OK || made != raw)
        return malformed(name_, where + ": a zlib array of " + std::to_string(length) + " elements does not inflate to " +
                                    std::to_string(raw) + " bytes (" + (z == Z_OK ? std::to_string(made) + " made" : std::string(zError(z))) + ")");
      data = inflated.data();
    }
    if (type == 'f' || type == 'd') {
      std::vector<double> out(static_cast<size_t>(length));
      for (size_t k = 0; k < out.size(); ++k) {
        const uint64_t bits = readLittle(data + k * each, each);
        if (each == 4) {
          float f = 0.0f;
          const auto b = uint32_t(bits);
          std::memcpy(&f, &b, 4);
          out[k] = f;
        } else {
          std::memcpy(&out[k], &bits, 8);
        }
      }
      node.values.emplace_back(std::move(out));
    } else {
      std::vector<int64_t> out(static_cast<size_t>(length));
      for (size_t k = 0; k < out.size(); ++k) {
        const uint64_t bits = readLittle(data + k * each, each);
        out[k] = each == 8 ? int64_t(bits) : each == 4 ? int64_t(int32_t(uint32_t(bits))) : int64_t(bits != 0);
      }
      node.values.emplace_back(std::move(out));
    }
    return at + 12 + size_t(stored);
  }

  // Charged to the load budget; over it, the file is named in front.
  eng::Result<void> charge(size_t count, size_t each, std::string_view what) {
    if (auto charged = budget_.charge(count, each, what); !charged) return charged.error().prefixed(name_ + ": ");
    return {};
  }
  eng::Result<void> charge(size_t bytes, std::string_view what) { return charge(1, bytes, what); }

  std::span<const uint8_t> bytes_;
  const std::string& name_;
  eng::LoadBudget& budget_;
  bool wide_;
};

// ASCII FBX 7: `Name: value, value {` children `}`, arrays as `*N { a: ... }`,
// `;` comments.
class AsciiReader {
 public:
  AsciiReader(std::string_view text, const std::string& name, eng::LoadBudget& budget) : text_(text), name_(name), budget_(budget) {}

  eng::Result<void> readAll(Node& root) {
    while (true) {
      skipSpace();
      if (at_ >= text_.size()) return {};
      ENG_TRY(readNode(root, 0));
    }
  }

 private:
  enum class Kind { End, Name, String, Word, Comma, Open, Close };
  struct Token {
    Kind kind = Kind::End;
    std::string_view text;
  };

  void skipSpace() {
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == ';') {
        while (at_ < text_.size() && text_[at_] != '\n') ++at_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        if (c == '\n') ++line_;
        ++at_;
      } else {
        return;
      }
    }
  }

  eng::Result<Token> peek() {
    const size_t saved = at_, savedLine = line_;
    auto token = next();
    at_ = saved;
    line_ = savedLine;
    return token;
  }

  eng::Result<Token> next() {
    skipSpace();
    if (at_ >= text_.size()) return Token{};
    const char c = text_[at_];
    if (c == ',' || c == '{' || c == '}') {
      ++at_;
      return Token{c == ',' ? Kind::Comma : c == '{' ? Kind::Open : Kind::Close, text_.substr(at_ - 1, 1)};
    }
    if (c == '"') {
      const size_t close = text_.find('"', at_ + 1);
      if (close == std::string_view::npos) return error("a string that is never closed");
      const std::string_view s = text_.substr(at_ + 1, close - at_ - 1);
      for (char k : s) line_ += k == '\n';
      at_ = close + 1;
      return Token{Kind::String, s};
    }
    const size_t start = at_;
    while (at_ < text_.size() && std::strchr(" \t\r\n,{}\";:", text_[at_]) == nullptr) ++at_;
    if (at_ == start) return error("unexpected '" + eng::shownText(text_.substr(at_, 1)) + "'");
    if (at_ < text_.size() && text_[at_] == ':') {
      ++at_;
      return Token{Kind::Name, text_.substr(start, at_ - 1 - start)};
    }
    return Token{Kind::Word, text_.substr(start, at_ - start)};
  }

  eng::Error error(const std::string& what) const { return malformed(name_, "line " + std::to_string(line_) + ": " + what); }

  eng::Result<void> readNode(Node& parent, size_t depth) {
    if (depth > kMaxDepth) return error("nodes nested deeper than " + std::to_string(kMaxDepth));
    const Token name = ENG_TRY_VALUE(next());
    if (name.kind != Kind::Name) return error("a node name ('Name:') expected, found '" + eng::shownText(name.text) + "'");
    ENG_TRY(charge(sizeof(Node), "FBX node"));
    Node& node = parent.children.emplace_back();
    node.name = std::string(name.text);
    // Values, comma-separated, over as many lines as they take.
    bool wantValue = true;
    while (true) {
      const Token t = ENG_TRY_VALUE(peek());
      if (t.kind == Kind::Comma) {
        ENG_TRY(next());
        wantValue = true;
        continue;
      }
      if (!wantValue || (t.kind != Kind::String && t.kind != Kind::Word)) break;
      ENG_TRY(next());
      ENG_TRY(charge(sizeof(Value) + t.text.size(), "FBX value"));
      node.values.push_back(valueOf(t));
      wantValue = false;
    }
    if (ENG_TRY_VALUE(peek()).kind == Kind::Open) {
      ENG_TRY(next());
      while (true) {
        const Token t = ENG_TRY_VALUE(peek());
        if (t.kind == Kind::Close) {
          ENG_TRY(next());
          break;
        }
        if (t.kind == Kind::End) return error("node '" + eng::shownText(node.name) + "' is never closed ('}')");
        ENG_TRY(readNode(node, depth + 1));
      }
    }
    return foldArray(node);
  }

  static Value valueOf(const Token& t) {
    if (t.kind == Kind::String) return std::string(t.text);
    const char* b = t.text.data();
    const char* e = b + t.text.size();
    int64_t whole = 0;
    if (auto [end, ec] = std::from_chars(b, e, whole); ec == std::errc() && end == e) return whole;
    double number = 0.0;
    if (auto [end, ec] = std::from_chars(b, e, number); ec == std::errc() && end == e) return number;
    return std::string(t.text);  // a bare word: T, Y, W, ...
  }

  // `Vertices: *N { a: ... }` becomes `Vertices` with one array value.
  eng::Result<void> foldArray(Node& node) {
    if (node.values.size() != 1 || node.children.size() != 1 || node.children[0].name != "a") return {};
    const std::string_view marker = node.text(0);
    if (!marker.starts_with("*")) return {};
    uint64_t count = 0;
    const auto [end, ec] = std::from_chars(marker.data() + 1, marker.data() + marker.size(), count);
    if (ec != std::errc() || end != marker.data() + marker.size()) return error("'" + eng::shownText(marker) + "' is not an array size");
    const Node& a = node.children[0];
    if (a.values.size() != count)
      return error("array '" + eng::shownText(node.name) + "' says " + std::to_string(count) + " elements and has " + std::to_string(a.values.size()));
    bool whole = true;
    for (const Value& v : a.values) {
      if (std::holds_alternative<std::string>(v)) return error("array '" + eng::shownText(node.name) + "' holds a word, not a number");
      whole &= std::holds_alternative<int64_t>(v);
    }
    Value folded;
    if (whole) {
      std::vector<int64_t> out;
      out.reserve(a.values.size());
      for (const Value& v : a.values) out.push_back(std::get<int64_t>(v));
      folded = std::move(out);
    } else {
      std::vector<double> out;
      out.reserve(a.values.size());
      for (size_t k = 0; k < a.values.size(); ++k) out.push_back(*a.number(k));
      folded = std::move(out);
    }
    node.values = {std::move(folded)};
    node.children.clear();
    return {};
  }

  eng::Result<void> charge(size_t bytes, std::string_view what) {
    if (auto charged = budget_.charge(bytes, what); !charged) return charged.error().prefixed(name_ + ": ");
    return {};
  }

  std::string_view text_;
  const std::string& name_;
  eng::LoadBudget& budget_;
  size_t at_ = 0;
  size_t line_ = 1;
};

// "; FBX 7.4.0 project file": 7400.
uint32_t asciiVersion(std::string_view text) {
  const size_t at = text.find("FBX ");
  if (at == std::string_view::npos || at > 8) return 0;
  unsigned major = 0, minor = 0, patch = 0;
  const char* p = text.data() + at + 4;
  const char* e = text.data() + std::min(text.size(), at + 24);
  auto r = std::from_chars(p, e, major);
  if (r.ec != std::errc() || r.ptr == e || *r.ptr != '.') return major * 1000;
  r = std::from_chars(r.ptr + 1, e, minor);
  if (r.ec == std::errc() && r.ptr != e && *r.ptr == '.') std::from_chars(r.ptr + 1, e, patch);
  return major * 1000 + minor * 100 + patch;
}

}  // namespace

bool looksLikeFbx(std::span<const uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 64));
  return text.starts_with(kBinaryMagic) || text.starts_with("; FBX");
}

eng::Result<Document> readFbxDocument(std::span<const uint8_t> bytes, const std::string& name, eng::LoadBudget& budget) {
  Document doc;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text.starts_with(kBinaryMagic)) {
    if (bytes.size() < kBinaryHeaderBytes) return malformed(name, "an FBX header cut short (" + std::to_string(bytes.size()) + " bytes)");
    doc.version = uint32_t(readLittle(&bytes[23], 4));
    if (doc.version < kOldestVersion)
      return eng::makeError(eng::ErrorKind::Unsupported, name + ": FBX version " + std::to_string(doc.version) +
                            " (FBX 6 or older) is not read; export FBX 7 (2011 or later)");
    BinaryReader reader(bytes, name, budget, doc.version);
    ENG_TRY(reader.readList(doc.root, kBinaryHeaderBytes, bytes.size(), 0));
    return doc;
  }
  if (!text.starts_with("; FBX")) return malformed(name, "not an FBX file (neither the binary magic nor '; FBX' at its start)");
  doc.version = asciiVersion(text.substr(0, 64));
  if (doc.version < kOldestVersion)
    return eng::makeError(eng::ErrorKind::Unsupported, name + ": ASCII FBX version " + std::to_string(doc.version) +
                          " (FBX 6 or older) is not read; export FBX 7 (2011 or later)");
  AsciiReader reader(text, name, budget);
  ENG_TRY(reader.readAll(doc.root));
  return doc;
}

}  // namespace importers::fbx
