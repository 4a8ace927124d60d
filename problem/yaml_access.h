#pragma once
// Typed, located access to a YAML tree: every failure names the file, line,
// dotted key, the value found and what was expected.
#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <optional>
#include <span>
#include <set>
#include <string>
#include <vector>

#include "problem/scene.h"

namespace kerf {

/// What every field of one scene file shares: the file's name, the keys set
/// on the command line, and where to record each key looked at (and its text).
struct YamlContext {
  std::string file;
  std::set<std::string> overridden;
  KeyLocations* record = nullptr;
};

/// One YAML node together with its dotted key; the context names the file.
/// A missing key is a field too: it points at its nearest present parent.
class YamlField {
 public:
  YamlField(YAML::Node node, std::string key, const YamlContext* context, YAML::Mark parent = YAML::Mark::null_mark());

  const YAML::Node& node() const { return node_; }
  const std::string& key() const { return key_; }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_null() const { return !node_ || node_.IsNull(); }
  std::size_t size() const { return node_.size(); }
  SourceLocation location() const;

  /// Child of a map; `has` tells whether the key is present and not null.
  bool has(const std::string& child) const;
  YamlField operator[](const std::string& child) const;
  YamlField operator[](std::size_t index) const;

  /// Refuses keys outside `allowed`, suggesting the nearest allowed one.
  void allow_only(std::span<const char* const> allowed) const;
  void allow_only(std::initializer_list<const char*> allowed) const {
    allow_only(std::span<const char* const>(allowed.begin(), allowed.size()));
  }
  /// Requires exactly one of the keys to be present.
  std::string exactly_one_of(std::initializer_list<const char*> keys) const;

  double number() const;
  int integer() const;
  bool boolean() const;
  std::string text() const;
  /// A vector of `dimension` numbers, padded with zero to 3 components.
  Vec3 vector(int dimension) const;
  /// A vector whose entries may be null (free component).
  std::array<std::optional<double>, 3> optional_vector(int dimension) const;
  std::vector<double> numbers() const;
  /// One of `choices`, returned as its position in the list.
  int choice(std::span<const char* const> choices) const;
  /// A value of an enum, spelled as EnumNames<E> says.
  template <class E>
  E enumeration() const {
    return static_cast<E>(choice(EnumNames<E>::names));
  }

  [[noreturn]] void fail(const std::string& problem) const;
  /// "value V is out of range; expected EXPECTED"
  [[noreturn]] void out_of_range(const std::string& expected) const;
  std::string value_text() const;
  /// The position of this node, or of its nearest present ancestor.
  YAML::Mark present_mark() const;

 private:
  YAML::Node node_;
  YAML::Mark parent_;  // where the nearest present ancestor starts
  std::string key_;
  const YamlContext* context_;

  /// The child, recorded in the context's KeyLocations.
  YamlField child(YAML::Node node, const std::string& name) const;
};

}  // namespace kerf
