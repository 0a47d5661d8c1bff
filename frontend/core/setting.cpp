#include "frontend/core/setting.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

// A number as a range shows it: whole numbers whole (4294967295), others as ostream writes them.
std::string plain_number(double value) {
  std::ostringstream out;
  if (std::floor(value) == value && std::fabs(value) < 1e15) out << std::fixed << std::setprecision(0);
  out << value;
  return out.str();
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

bool has_low(const setting_range& range) { return range.low > -std::numeric_limits<double>::infinity(); }
bool has_high(const setting_range& range) { return range.high < std::numeric_limits<double>::infinity(); }

std::string joined(const std::vector<std::string>& items, const std::string& last) {
  std::string all;
  for (std::size_t i = 0; i < items.size(); ++i) all += (i == 0 ? "" : i + 1 == items.size() ? " " + last + " " : ", ") + items[i];
  return all;
}

std::string with_unit(const std::string& text, const std::string& unit) { return unit.empty() ? text : text + " (" + unit + ")"; }

}  // namespace

std::string describe_range(const setting_range& range) {
  if (has_low(range) && has_high(range))
    return "in " + std::string(range.low_open ? "(" : "[") + plain_number(range.low) + ", " + plain_number(range.high) + (range.high_open ? ")" : "]");
  if (has_low(range)) return std::string(range.low_open ? "> " : ">= ") + plain_number(range.low);
  if (has_high(range)) return std::string(range.high_open ? "< " : "<= ") + plain_number(range.high);
  return "finite";
}

std::string format_real(double value) {
  char buffer[64];
  const auto [end, code] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return code == std::errc() ? std::string(buffer, end) : plain_number(value);
}

std::string format_real(float value) {
  char buffer[64];
  const auto [end, code] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return code == std::errc() ? std::string(buffer, end) : plain_number(value);
}

std::optional<double> parse_real(std::string_view text) {
  text = trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view text) {
  text = trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  long long value = 0;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

std::optional<std::pair<int, int>> parse_extent(std::string_view text) {
  const std::size_t x = text.find('x');
  const auto side = [](std::string_view digits) -> std::optional<int> {
    if (digits.empty() || digits.size() > 6) return std::nullopt;
    for (char c : digits)
      if (c < '0' || c > '9') return std::nullopt;
    return static_cast<int>(*parse_integer(digits));
  };
  const std::optional<int> width = side(text.substr(0, x));
  const std::optional<int> height = x == std::string_view::npos ? width : side(text.substr(x + 1));
  if (!width || !height) return std::nullopt;
  return std::pair<int, int>{*width, *height};
}

std::optional<std::vector<double>> parse_point(std::string_view text) {
  std::vector<double> values;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::optional<double> value = parse_real(text.substr(0, comma));
    if (!value) return std::nullopt;
    values.push_back(*value);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (values.size() != 3) return std::nullopt;
  return values;
}

std::string quote_for_message(std::string_view text) {
  constexpr std::size_t limit = 60;
  std::string out(1, '\'');
  out.append(text.substr(0, limit));
  if (text.size() > limit) out.append("...' (").append(std::to_string(text.size())).append(" characters)");
  else out.push_back('\'');
  return out;
}

std::string setting_info::values() const {
  switch (type) {
    case setting_type::integer:
      if (!allowed.empty()) {
        std::vector<std::string> names;
        for (int value : allowed) names.push_back(std::to_string(value));
        return joined(names, "or");
      }
      return with_unit(describe_range(range), unit);
    case setting_type::real: return with_unit(describe_range(range), unit);
    case setting_type::choice: return joined(choices, "or");
    case setting_type::size: return "N or WxH, each side " + describe_range(range);
    case setting_type::point: return "x,y,z, each " + describe_range(range);
    case setting_type::text: return with_unit("a name or a file", unit);
  }
  return {};
}

std::string setting_info::check(const std::string& text) const {
  const std::string got = ", got " + quote_for_message(text);
  switch (type) {
    case setting_type::integer: {
      const std::optional<long long> value = parse_integer(text);
      if (!allowed.empty()) {
        const bool listed = value && std::find(allowed.begin(), allowed.end(), *value) != allowed.end();
        return listed ? std::string() : "must be " + values() + got;
      }
      if (!value || !range.contains(static_cast<double>(*value))) return "must be a whole number " + with_unit(describe_range(range), unit) + got;
      return {};
    }
    case setting_type::real: {
      const std::optional<double> value = parse_real(text);
      if (!value || !range.contains(*value)) return "must be a number " + with_unit(describe_range(range), unit) + got;
      return {};
    }
    case setting_type::choice:
      if (std::find(choices.begin(), choices.end(), text) == choices.end()) return "must be " + values() + got;
      return {};
    case setting_type::size: {
      const std::optional<std::pair<int, int>> extent = parse_extent(text);
      if (!extent) return "expected N or WxH (for example 512 or 640x480)" + got;
      if (!range.contains(extent->first) || !range.contains(extent->second)) return "each side must be " + describe_range(range) + got;
      return {};
    }
    case setting_type::point: {
      const std::optional<std::vector<double>> point = parse_point(text);
      bool inside = point.has_value();
      if (point)
        for (double coordinate : *point) inside = inside && range.contains(coordinate);
      if (!inside) return "expected x,y,z, each a finite number " + describe_range(range) + " (for example 0,0.7,0)" + got;
      return {};
    }
    case setting_type::text:
      if (text.empty()) return "must not be empty";
      for (char c : text)
        if (static_cast<unsigned char>(c) < 0x20) return "must be printable text" + got;
      return {};
  }
  return {};
}

std::optional<double> setting_info::number(const std::string& text) const {
  if (type == setting_type::integer) {
    if (const std::optional<long long> value = parse_integer(text)) return static_cast<double>(*value);
  } else if (type == setting_type::real) {
    return parse_real(text);
  }
  return std::nullopt;
}

std::vector<std::pair<std::string, std::string>> settings_in_effect(const technique_settings& settings) {
  std::vector<std::pair<std::string, std::string>> values;
  for (const setting_info* entry : settings.settings())
    if (entry->in_effect && settings.reads(entry->name)) values.emplace_back(entry->name, settings.get(entry->name));
  return values;
}

namespace {

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const auto code = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (code < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", code);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

std::string settings_json(const technique_settings& settings, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string json = "{\n" + pad + "  \"technique\": " + json_string(settings.technique());
  for (const auto& [name, value] : settings_in_effect(settings)) {
    const setting_info* entry = settings.find(name);
    const std::optional<double> number = entry->number(value);
    json += ",\n" + pad + "  " + json_string(name) + ": " + (number ? value : json_string(value));
  }
  return json + "\n" + pad + "}";
}

namespace detail {

void throw_unknown_technique(const std::string& technique, const std::vector<std::string>& known) {
  std::string names;
  for (const std::string& name : known) names += (names.empty() ? "" : ", ") + name;
  throw error("unknown technique '" + technique + "' for these settings (known: " + names + ")");
}

}  // namespace detail

}  // namespace vplkit
