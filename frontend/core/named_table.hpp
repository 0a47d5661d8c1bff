// Lookup in a table of named entries (the techniques of each family): one way to find an entry
// by its CLI name and to say which names exist when it is not there.
#pragma once

#include <string>
#include <vector>

#include "frontend/core/error.hpp"

namespace vplkit {

/// The names of a table whose entries have a `const char* name`, in table order.
template <typename Entry>
std::vector<std::string> names_of(const std::vector<Entry>& table) {
  std::vector<std::string> names;
  for (const Entry& entry : table) names.emplace_back(entry.name);
  return names;
}

/// Whether the table has an entry called `name`.
template <typename Entry>
bool has_name(const std::vector<Entry>& table, const std::string& name) {
  for (const Entry& entry : table)
    if (name == entry.name) return true;
  return false;
}

/// The entry called `name`. Throws vplkit::error "unknown <what> '<name>' (known: ...)".
template <typename Entry>
const Entry& find_by_name(const std::vector<Entry>& table, const std::string& name, const std::string& what) {
  std::string known;
  for (const Entry& entry : table) {
    if (name == entry.name) return entry;
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  throw error("unknown " + what + " '" + name + "' (known: " + known + ")");
}

}  // namespace vplkit
