#include <vplkit/gl/uniform_declarations.hpp>

#include <cctype>
#include <vector>

namespace vplkit {

namespace {

// The source as identifiers and single punctuation characters, comments and preprocessor lines
// left out (the expansion has resolved #include; #define'd array sizes are only skipped over).
std::vector<std::string> tokens_of(const std::string& source) {
  std::vector<std::string> tokens;
  std::size_t at = 0;
  const std::size_t size = source.size();
  bool line_start = true;
  while (at < size) {
    const char c = source[at];
    if (c == '\n') {
      line_start = true;
      ++at;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++at;
    } else if (line_start && c == '#') {
      while (at < size && source[at] != '\n') ++at;
    } else if (source.compare(at, 2, "//") == 0) {
      while (at < size && source[at] != '\n') ++at;
    } else if (source.compare(at, 2, "/*") == 0) {
      const std::size_t end = source.find("*/", at + 2);
      at = end == std::string::npos ? size : end + 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t begin = at;
      while (at < size && (std::isalnum(static_cast<unsigned char>(source[at])) || source[at] == '_')) ++at;
      tokens.push_back(source.substr(begin, at - begin));
      line_start = false;
    } else {
      tokens.emplace_back(1, c);
      ++at;
      line_start = false;
    }
  }
  return tokens;
}

}  // namespace

void uniform_declarations::scan(const std::string& source) {
  const std::vector<std::string> tokens = tokens_of(source);
  const auto token = [&](std::size_t i) -> const std::string& {
    static const std::string none;
    return i < tokens.size() ? tokens[i] : none;
  };
  // Fields: "type name [N]? (, name [N]?)* ;" from `at` until the closing brace, which it
  // returns the index of. A block member's own qualifiers (layout(...), a precision) are skipped.
  const auto read_fields = [&](std::size_t at, std::map<std::string, field>& fields) {
    while (at < tokens.size() && tokens[at] != "}") {
      if (tokens[at] == "layout") {
        while (at < tokens.size() && tokens[at] != ")") ++at;
        ++at;
        continue;
      }
      if (tokens[at] == "highp" || tokens[at] == "mediump" || tokens[at] == "lowp") {
        ++at;
        continue;
      }
      const std::string type = tokens[at++];
      std::string last;  // the field an array size follows
      while (at < tokens.size() && tokens[at] != ";" && tokens[at] != "}") {
        if (tokens[at] == "[") {
          while (at < tokens.size() && tokens[at] != "]") ++at;
          if (!last.empty()) fields[last].array = true;
        } else if (tokens[at] != ",") {
          last = tokens[at];
          fields[last] = {type, false};
        }
        ++at;
      }
      if (at < tokens.size() && tokens[at] == ";") ++at;
    }
    return at;
  };
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i] == "struct" && token(i + 2) == "{") {
      i = read_fields(i + 3, struct_fields_[token(i + 1)]);
    } else if (tokens[i] == "uniform" && token(i + 2) == "{") {
      // A uniform block, "uniform Block { members } [instance];": its members are not default-
      // block uniforms (no location; a buffer holds them), but their struct types are checked
      // all the same. With an instance name the block reads as a struct of that name.
      const std::string block = token(i + 1);
      std::map<std::string, field> members;
      i = read_fields(i + 3, members);
      blocks_.insert(block);
      const std::string& instance = token(i + 1);
      if (!instance.empty() && instance != ";") {
        struct_fields_[block] = members;
        block_member_types_[instance] = block;
      } else {
        for (const auto& [name, member] : members) block_member_types_[name] = member.type;
      }
    } else if (tokens[i] == "uniform") {
      // "uniform [precision] type name [N]? ;"
      std::size_t at = i + 1;
      if (token(at) == "highp" || token(at) == "mediump" || token(at) == "lowp") ++at;
      const std::string type = token(at);
      const std::string name = token(at + 1);
      if (!name.empty()) uniform_types_[name] = type;
    }
  }
}

bool uniform_declarations::declares(const std::string& path) const {
  // Split "a.b[3].c" into a, b, c (indices dropped).
  std::vector<std::string> parts(1);
  for (std::size_t at = 0; at < path.size(); ++at) {
    if (path[at] == '.') {
      parts.emplace_back();
    } else if (path[at] == '[') {
      const std::size_t close = path.find(']', at);
      if (close == std::string::npos) return false;
      at = close;
    } else {
      parts.back() += path[at];
    }
  }
  const auto uniform = uniform_types_.find(parts.front());
  if (uniform == uniform_types_.end()) return false;
  std::string type = uniform->second;
  for (std::size_t k = 1; k < parts.size(); ++k) {
    const auto fields = struct_fields_.find(type);
    if (fields == struct_fields_.end()) return false;
    const auto found = fields->second.find(parts[k]);
    if (found == fields->second.end()) return false;
    type = found->second.type;
  }
  return true;
}

const std::map<std::string, uniform_declarations::field>* uniform_declarations::struct_fields(const std::string& name) const {
  const auto found = struct_fields_.find(name);
  return found == struct_fields_.end() ? nullptr : &found->second;
}

std::string uniform_declarations::block_names() const {
  std::string all;
  for (const std::string& name : blocks_) all += (all.empty() ? "" : ", ") + name;
  return all;
}

std::string uniform_declarations::names() const {
  std::string all;
  for (const auto& [name, type] : uniform_types_) all += (all.empty() ? "" : ", ") + name;
  return all;
}

}  // namespace vplkit
