#include "problem/yaml_access.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/check.h"

namespace kerf {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string join_key(const std::string& parent, const std::string& child) {
  return parent.empty() ? child : parent + "." + child;
}

}  // namespace

YamlField::YamlField(YAML::Node node, std::string key, const YamlContext* context, YAML::Mark parent)
    : node_(std::move(node)), parent_(parent), key_(std::move(key)), context_(context) {}

SourceLocation YamlField::location() const {
  SourceLocation where;
  where.file = context_->file;
  where.key = key_;
  for (const auto& prefix : context_->overridden)
    if (key_ == prefix || key_.rfind(prefix + ".", 0) == 0) where.command_line = true;
  YAML::Mark mark = node_ ? node_.Mark() : parent_;
  if (mark.line >= 0) {
    where.line = mark.line + 1;
    where.column = mark.column + 1;
  }
  return where;
}

YamlField YamlField::child(YAML::Node node, const std::string& name) const {
  YamlField field(std::move(node), join_key(key_, name), context_, present_mark());
  if (context_->record) {
    SourceLocation& where = (*context_->record)[field.key_] = field.location();
    // Scalars as written; lists and maps are described from their values.
    if (!field.node_ || field.node_.IsNull() || field.node_.IsScalar()) where.text = field.value_text();
  }
  return field;
}

bool YamlField::has(const std::string& child) const {
  if (!node_ || !node_.IsMap()) return false;
  YAML::Node value = node_[child];
  return value && !value.IsNull();
}

YamlField YamlField::operator[](const std::string& name) const {
  return child(node_ && node_.IsMap() ? node_[name] : YAML::Node(), name);
}

YamlField YamlField::operator[](std::size_t index) const { return child(node_[index], std::to_string(index)); }

YAML::Mark YamlField::present_mark() const { return node_ ? node_.Mark() : parent_; }

void YamlField::fail(const std::string& problem) const {
  throw Error(location().describe() + ": " + problem);
}

std::string YamlField::value_text() const {
  if (!node_) return "nothing (the key is missing)";
  if (node_.IsNull()) return "null";
  // A message quotes at most the first 160 bytes of a value (a scalar of
  // megabytes, a flow of thousands of items).
  auto shortened = [](const std::string& text) {
    if (text.size() <= 200) return text;
    return text.substr(0, 160) + "... (" + std::to_string(text.size()) + " bytes)";
  };
  if (node_.IsScalar()) return "'" + shortened(node_.Scalar()) + "'";
  YAML::Emitter out;
  out << YAML::Flow << node_;
  return shortened(out.c_str());
}

void YamlField::out_of_range(const std::string& expected) const {
  fail("value " + value_text() + " is out of range; expected " + expected);
}

void YamlField::allow_only(std::span<const char* const> allowed) const {
  if (!node_.IsMap()) fail("expected a map with keys, found " + value_text());
  std::vector<std::string> seen;
  for (const auto& entry : node_) {
    // A key must be text: `[1, 2]: x` or `{a: 1}: x` (a comma or brace out of place) is refused here.
    if (!entry.first.IsScalar())
      YamlField(entry.first, key_, context_)
          .fail("a map key that is not text (a list or map used as a key; a stray comma or bracket?)");
    std::string name = entry.first.Scalar();
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      YamlField(entry.first, join_key(key_, name), context_)
          .fail("key '" + name + "' appears twice in the same map; expected each key once");
    seen.push_back(name);
    bool known = std::any_of(allowed.begin(), allowed.end(),
                             [&](const char* a) { return name == a; });
    if (known) continue;
    std::string nearest;
    std::size_t best = 3;
    for (const char* a : allowed) {
      std::size_t d = edit_distance(name, a);
      if (d < best) best = d, nearest = a;
    }
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    YamlField unknown(entry.first, join_key(key_, name), context_, present_mark());
    unknown.fail("unknown key '" + name + "'" +
               (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
               "; expected one of: " + list);
  }
}

std::string YamlField::exactly_one_of(std::initializer_list<const char*> keys) const {
  std::string found, list;
  int count = 0;
  for (const char* k : keys) {
    list += (list.empty() ? "" : " | ") + std::string(k);
    if (has(k)) ++count, found = k;
  }
  if (count != 1)
    fail("expected exactly one of " + list + ", found " + std::to_string(count));
  return found;
}

double YamlField::number() const {
  if (!node_ || !node_.IsScalar()) fail("expected a number, found " + value_text());
  double value = 0.0;
  try {
    value = node_.as<double>();
  } catch (const YAML::Exception&) {
    fail("expected a number, found " + value_text());
  }
  if (!std::isfinite(value)) fail("expected a finite number, found " + value_text());
  return value;
}

int YamlField::integer() const {
  if (!node_ || !node_.IsScalar()) fail("expected an integer, found " + value_text());
  try {
    return node_.as<int>();
  } catch (const YAML::Exception&) {
    fail("expected an integer, found " + value_text());
  }
}

bool YamlField::boolean() const {
  if (!node_ || !node_.IsScalar()) fail("expected true or false, found " + value_text());
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    fail("expected true or false, found " + value_text());
  }
}

namespace {

/// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or code
/// points past U+10FFFF): names and paths go into summary.json, which must be.
bool valid_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    const int extra = c >= 0xC2 && c <= 0xDF ? 1 : c >= 0xE0 && c <= 0xEF ? 2 : c >= 0xF0 && c <= 0xF4 ? 3 : -1;
    if (extra < 0 || i + extra >= s.size()) return false;
    const auto next = static_cast<unsigned char>(s[i + 1]);
    const unsigned char low = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
    const unsigned char high = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
    if (next < low || next > high) return false;
    for (int k = 2; k <= extra; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return false;
    i += 1 + extra;
  }
  return true;
}

}  // namespace

std::string YamlField::text() const {
  if (!node_ || !node_.IsScalar()) fail("expected a string, found " + value_text());
  if (!valid_utf8(node_.Scalar())) fail("the text is not valid UTF-8; expected UTF-8 text");
  return node_.Scalar();
}

std::vector<double> YamlField::numbers() const {
  if (!node_ || !node_.IsSequence()) fail("expected a list of numbers, found " + value_text());
  std::vector<double> values;
  for (std::size_t i = 0; i < node_.size(); ++i) values.push_back((*this)[i].number());
  return values;
}

Vec3 YamlField::vector(int dimension) const {
  if (!node_ || !node_.IsSequence() || static_cast<int>(node_.size()) != dimension)
    fail("expected a list of " + std::to_string(dimension) + " numbers (dimension " +
         std::to_string(dimension) + "), found " + value_text());
  Vec3 v = Vec3::Zero();
  for (int i = 0; i < dimension; ++i) v[i] = (*this)[i].number();
  return v;
}

std::array<std::optional<double>, 3> YamlField::optional_vector(int dimension) const {
  if (!node_ || !node_.IsSequence() || static_cast<int>(node_.size()) != dimension)
    fail("expected a list of " + std::to_string(dimension) +
         " numbers or nulls (dimension " + std::to_string(dimension) + "), found " +
         value_text());
  std::array<std::optional<double>, 3> v;
  for (int i = 0; i < dimension; ++i)
    if (!(*this)[i].is_null() && (*this)[i].node().Scalar() != "~") v[i] = (*this)[i].number();
  return v;
}

int YamlField::choice(std::span<const char* const> choices) const {
  std::string value = text();
  int index = 0;
  std::string list;
  for (const char* c : choices) {
    if (value == c) return index;
    list += (list.empty() ? "" : " | ") + std::string(c);
    ++index;
  }
  fail("value " + value_text() + " is not allowed; expected one of " + list);
}

}  // namespace kerf
