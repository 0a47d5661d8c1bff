#include "frontend/core/files.hpp"

#include <cstdio>
#include <fstream>
#include <random>
#include <system_error>

#include "frontend/core/error.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (std::uintmax_t{1} << 30) && bytes % (std::uintmax_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// The folder `path` goes into, created if needed.
fs::path parent_folder_of(const fs::path& path) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code code;
  fs::create_directories(parent, code);
  if (code || !fs::is_directory(parent))
    throw error("cannot write " + path.string() + ": cannot create folder " + parent.string() +
                (code ? " (" + code.message() + ")" : std::string(" (a file is in the way)")));
  return parent;
}

// Writes `bytes` to a new temporary file next to `path` and returns its name.
fs::path write_temporary(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  const fs::path parent = parent_folder_of(path);
  std::error_code code;
  if (fs::is_directory(path, code)) throw error("cannot write " + path.string() + ": a folder of that name is in the way");
  std::random_device entropy;
  // Built with += rather than "." + string: GCC 12 gives a false -Wrestrict on the latter (bug 105329).
  std::string temporary_name = ".";
  temporary_name += path.filename().string();
  temporary_name += ".partial-";
  temporary_name += std::to_string(entropy());
  const fs::path temporary = parent / temporary_name;
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) throw error("cannot write " + path.string() + ": cannot create a file in " + parent.string());
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    fs::remove(temporary, code);
    throw error("cannot write " + path.string() + ": the write failed (disk full?)");
  }
  return temporary;
}

void rename_over(const fs::path& temporary, const fs::path& path) {
  std::error_code code;
  fs::rename(temporary, path, code);
  if (code) {
    // The message first: removing the temporary resets `code`.
    const std::string reason = code.message();
    fs::remove(temporary, code);
    throw error("cannot write " + path.string() + ": " + reason);
  }
}

}  // namespace

std::string read_file(const fs::path& path, std::uintmax_t max_bytes, const std::string& what) {
  std::error_code code;
  const fs::file_status status = fs::status(path, code);
  if (code || !fs::exists(status)) throw error(path.string() + ": no such " + what);
  if (!fs::is_regular_file(status)) throw error(path.string() + ": not a regular file (expected an " + what + ")");
  const std::uintmax_t bytes = fs::file_size(path, code);
  if (code) throw error(path.string() + ": cannot read the " + what + " (" + code.message() + ")");
  if (bytes > max_bytes)
    throw error(path.string() + ": the " + what + " is " + size_text(bytes) + ", more than the " + size_text(max_bytes) + " vplkit reads");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw error(path.string() + ": cannot open the " + what);
  std::string contents(static_cast<std::size_t>(bytes), '\0');
  in.read(contents.data(), static_cast<std::streamsize>(bytes));
  if (static_cast<std::uintmax_t>(in.gcount()) != bytes) throw error(path.string() + ": the " + what + " could not be read whole");
  return contents;
}

void write_bytes_atomically(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  rename_over(write_temporary(path, bytes), path);
}

void write_all_or_nothing(const std::vector<output_file>& files) {
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (files[i].path.lexically_normal() == files[j].path.lexically_normal())
        throw error("two outputs would be written to " + files[i].path.string());
  std::vector<fs::path> temporaries;
  std::error_code ignored;
  const auto remove_temporaries_from = [&](std::size_t first) {
    for (std::size_t i = first; i < temporaries.size(); ++i) fs::remove(temporaries[i], ignored);
  };
  try {
    for (const output_file& file : files) temporaries.push_back(write_temporary(file.path, file.encode()));
  } catch (...) {
    remove_temporaries_from(0);
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      rename_over(temporaries[i], files[i].path);
    } catch (...) {
      for (std::size_t k = 0; k < i; ++k) fs::remove(files[k].path, ignored);
      remove_temporaries_from(i + 1);
      throw;
    }
  }
}

}  // namespace vplkit
