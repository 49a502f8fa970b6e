// Internal: Java .properties text (ISO-8859-1, as JPK writes it) to a key -> value table.
#pragma once

#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace layerjkr::detail {

/// The parsed entries, sorted by key (as std::map<std::string, std::string> would order them).
/// One text buffer holds every key and value: plain ASCII lines are referenced where they stand,
/// escaped or Latin-1 ones are unescaped into an arena after the text. A map of strings cost a
/// node, a key and often a value allocation per entry, and each JPK curve has ~200 entries.
class Properties {
 public:
  using value_type = std::pair<std::string_view, std::string_view>;

  class const_iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = Properties::value_type;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = value_type;
    const_iterator(const Properties* owner, std::size_t i) : owner_(owner), i_(i) {}
    value_type operator*() const { return owner_->entry(i_); }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const const_iterator& other) const { return i_ == other.i_; }
    bool operator!=(const const_iterator& other) const { return i_ != other.i_; }

   private:
    const Properties* owner_;
    std::size_t i_;
  };

  /// [first, last): the entries whose keys start with a prefix, in key order.
  struct Range {
    const_iterator first, last;
    const_iterator begin() const { return first; }
    const_iterator end() const { return last; }
  };

  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, entries_.size()}; }

  /// The value of `key`, or none.
  std::optional<std::string_view> find(std::string_view key) const;
  bool contains(std::string_view key) const { return find(key).has_value(); }
  std::size_t count(std::string_view key) const { return contains(key) ? 1 : 0; }
  /// The value of `key`; throws std::out_of_range if it is absent (as std::map::at does).
  std::string_view at(std::string_view key) const;
  /// The first entry whose key is not less than `key`.
  const_iterator lower_bound(std::string_view key) const { return {this, lower(key)}; }
  Range with_prefix(std::string_view prefix) const;

 private:
  struct Entry {
    std::size_t key = 0, key_length = 0, value = 0, value_length = 0;
    std::size_t line = 0;  // order in the text, for the duplicate-key error
  };
  friend Properties parse_properties(std::string text, const std::string& where);
  std::string_view key_at(std::size_t i) const { return std::string_view(text_).substr(entries_[i].key, entries_[i].key_length); }
  value_type entry(std::size_t i) const {
    const Entry& e = entries_[i];
    const std::string_view t(text_);
    return {t.substr(e.key, e.key_length), t.substr(e.value, e.value_length)};
  }
  std::size_t lower(std::string_view key) const;

  std::string text_;
  std::vector<Entry> entries_;
};

/// Parses `text`: '#' and '!' comments, key/value separated by '=', ':' or whitespace,
/// backslash escapes (\t \n \r \f, \uXXXX as UTF-8, any other escaped character as itself)
/// and line continuations. Latin-1 bytes are converted to UTF-8. A key given twice throws
/// InputError "<where>: the key '<key>' is given twice (...)": Java's Properties.store never
/// writes one twice, so a repeat is damage, and which value holds would be a guess.
Properties parse_properties(std::string text, const std::string& where);

}  // namespace layerjkr::detail
