#include <mr/core/errors.h>
#include <mr/io/file_bytes.h>
#include <mr/io/registry.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace mr::io {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string known_extensions(const std::vector<Format>& formats) {
  std::string list;
  for (const Format& format : formats)
    for (const std::string& ext : format.extensions) list += (list.empty() ? "" : " ") + ext;
  return list;
}

}  // namespace

void Registry::add(Format format) {
  if (by_name(format.name)) throw std::logic_error("format registered twice: " + format.name);
  for (const std::string& ext : format.extensions)
    if (by_extension("x" + ext)) throw std::logic_error("extension registered twice: " + ext);
  if (format.read_surface_bytes && !format.read_surface)
    format.read_surface = [read = format.read_surface_bytes](const std::filesystem::path& path,
                                                             const ReadOptions& options) {
      const std::vector<char> bytes = read_file_bytes(path);
      return read(std::string_view(bytes.data(), bytes.size()), path.string(), options);
    };
  if (format.read_volume_bytes && !format.read_volume)
    format.read_volume = [read = format.read_volume_bytes](const std::filesystem::path& path,
                                                           const ReadOptions& options) {
      const std::vector<char> bytes = read_file_bytes(path);
      return read(std::string_view(bytes.data(), bytes.size()), path.string(), options);
    };
  formats_.push_back(std::move(format));
}

const Format* Registry::by_name(const std::string& name) const {
  for (const Format& format : formats_)
    if (format.name == name) return &format;
  return nullptr;
}

const Format* Registry::by_extension(const std::filesystem::path& path) const {
  const std::string ext = lower_extension(path);
  for (const Format& format : formats_)
    if (std::find(format.extensions.begin(), format.extensions.end(), ext) != format.extensions.end())
      return &format;
  return nullptr;
}

const Format& Registry::resolve_for_read(const std::filesystem::path& path,
                                         const std::string& explicit_name) const {
  const Format* format = explicit_name.empty() ? by_extension(path) : by_name(explicit_name);
  if (!format) {
    if (!explicit_name.empty()) throw UsageError("unknown format '" + explicit_name + "'");
    throw InputError(path.string(), "unknown file extension '" + path.extension().string() +
                                        "' (known: " + known_extensions(formats_) + ")");
  }
  if (!format->can_read()) throw UsageError("format " + format->name + " cannot be read");
  return *format;
}

const Format& Registry::resolve_for_write(const std::filesystem::path& path,
                                          const std::string& explicit_name) const {
  const Format* format = explicit_name.empty() ? by_extension(path) : by_name(explicit_name);
  if (!format) {
    if (!explicit_name.empty()) throw UsageError("unknown format '" + explicit_name + "'");
    throw UsageError(path.string() + ": unknown output extension '" + path.extension().string() +
                     "' (known: " + known_extensions(formats_) + ")");
  }
  if (!format->can_write()) throw UsageError("format " + format->name + " cannot be written");
  return *format;
}

}  // namespace mr::io
