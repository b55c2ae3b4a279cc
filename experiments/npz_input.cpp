#include "experiments/npz_input.h"

#include <zip.h>

#include <cstdint>
#include <cstring>
#include <memory>

#include "experiments/json_input.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

std::uint64_t littleEndian(const unsigned char* bytes, int count) {
  std::uint64_t value = 0;
  for (int k = count - 1; k >= 0; --k) value = (value << 8) | bytes[k];
  return value;
}

// The value of `key` in the header dictionary, as its literal text.
std::string headerValue(const std::string& header, const std::string& key, const std::string& where) {
  const std::string quoted[] = {"'" + key + "'", "\"" + key + "\""};
  std::size_t at = std::string::npos;
  for (const auto& q : quoted) {
    at = header.find(q);
    if (at != std::string::npos) {
      at += q.size();
      break;
    }
  }
  if (at == std::string::npos) throw InputError(where + ": the .npy header has no '" + key + "'");
  at = header.find(':', at);
  if (at == std::string::npos) throw InputError(where + ": malformed .npy header");
  ++at;
  while (at < header.size() && header[at] == ' ') ++at;
  std::size_t end = at;
  if (at < header.size() && header[at] == '(') {
    end = header.find(')', at);
    if (end == std::string::npos) throw InputError(where + ": malformed .npy shape");
    return header.substr(at + 1, end - at - 1);
  }
  while (end < header.size() && header[end] != ',' && header[end] != '}') ++end;
  std::string value = header.substr(at, end - at);
  while (!value.empty() && value.back() == ' ') value.pop_back();
  if (value.size() >= 2 && (value.front() == '\'' || value.front() == '"')) {
    value = value.substr(1, value.size() - 2);
  }
  return value;
}

std::vector<std::size_t> parseShape(const std::string& text, const std::string& where) {
  std::vector<std::size_t> shape;
  std::size_t at = 0;
  while (at < text.size()) {
    while (at < text.size() && (text[at] == ' ' || text[at] == ',')) ++at;
    if (at == text.size()) break;
    std::size_t end = at;
    while (end < text.size() && text[end] >= '0' && text[end] <= '9') ++end;
    if (end == at || end - at > 12) throw InputError(where + ": malformed .npy shape (" + text + ")");
    shape.push_back(std::size_t(std::stoull(text.substr(at, end - at))));
    at = end;
    while (at < text.size() && text[at] == ' ') ++at;
    if (at < text.size() && text[at] != ',') {
      throw InputError(where + ": malformed .npy shape (" + text + ")");
    }
  }
  return shape;
}

}  // namespace

std::size_t NpyArray::size() const {
  std::size_t count = 1;
  for (std::size_t n : shape) count *= n;
  return count;
}

NpyArray parseNpy(const std::string& bytes, const std::string& where) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0) {
    throw InputError(where + ": not a .npy array (no \\x93NUMPY magic)");
  }
  const int major = data[6];
  if (major < 1 || major > 3) {
    throw InputError(where + ": .npy format version " + std::to_string(major) + " not supported");
  }
  const int lengthBytes = major == 1 ? 2 : 4;
  const std::size_t start = 8 + std::size_t(lengthBytes);
  if (bytes.size() < start) throw InputError(where + ": truncated .npy header");
  const std::uint64_t headerLength = littleEndian(data + 8, lengthBytes);
  if (headerLength > bytes.size() - start) throw InputError(where + ": truncated .npy header");
  const std::string header = bytes.substr(start, std::size_t(headerLength));
  const std::string descr = headerValue(header, "descr", where);
  const std::string fortran = headerValue(header, "fortran_order", where);
  NpyArray array;
  array.shape = parseShape(headerValue(header, "shape", where), where);
  std::size_t count = 1;
  for (std::size_t n : array.shape) {
    if (n != 0 && count > (std::size_t(1) << 40) / n) throw InputError(where + ": array too large");
    count *= n;
  }
  if (fortran != "False" && fortran != "True") {
    throw InputError(where + ": malformed fortran_order (" + fortran + ")");
  }
  if (descr.size() < 3) throw InputError(where + ": unsupported dtype '" + descr + "'");
  const char order = descr[0], kind = descr[1];
  if (order == '>') throw InputError(where + ": big-endian dtype '" + descr + "' not supported");
  if (order != '<' && order != '|' && order != '=') {
    throw InputError(where + ": unsupported dtype '" + descr + "'");
  }
  std::size_t itemSize = 0;
  try {
    itemSize = std::size_t(std::stoul(descr.substr(2)));
  } catch (const std::exception&) {
    throw InputError(where + ": unsupported dtype '" + descr + "'");
  }
  const bool supported =
      (kind == 'f' && (itemSize == 4 || itemSize == 8)) ||
      ((kind == 'i' || kind == 'u') && (itemSize == 1 || itemSize == 2 || itemSize == 4 || itemSize == 8)) ||
      (kind == 'b' && itemSize == 1) || ((kind == 'U' || kind == 'S') && itemSize >= 1 && itemSize <= 1 << 20);
  if (!supported) throw InputError(where + ": unsupported dtype '" + descr + "'");
  const std::size_t width = kind == 'U' ? 4 * itemSize : itemSize;
  const std::size_t body = start + std::size_t(headerLength);
  if (count > 0 && width > (bytes.size() - body) / count) {
    throw InputError(where + ": truncated .npy data (" + std::to_string(count) + " items of " +
                     std::to_string(width) + " bytes expected)");
  }
  // Element k of the file in row-major position: the file is C order, or Fortran order.
  std::vector<std::size_t> position(count);
  for (std::size_t k = 0; k < count; ++k) position[k] = k;
  if (fortran == "True" && array.shape.size() > 1) {
    // File index k = i0 + n0 (i1 + n1 (i2 ...)); row-major index of the same element.
    for (std::size_t k = 0; k < count; ++k) {
      std::size_t rest = k, rowMajor = 0;
      std::vector<std::size_t> index(array.shape.size());
      for (std::size_t axis = 0; axis < array.shape.size(); ++axis) {
        index[axis] = rest % array.shape[axis];
        rest /= array.shape[axis];
      }
      for (std::size_t axis = 0; axis < array.shape.size(); ++axis) {
        rowMajor = rowMajor * array.shape[axis] + index[axis];
      }
      position[k] = rowMajor;
    }
  }
  const unsigned char* item = data + body;
  if (kind == 'U' || kind == 'S') {
    array.isString = true;
    array.strings.resize(count);
    for (std::size_t k = 0; k < count; ++k, item += width) {
      std::string text;
      for (std::size_t c = 0; c < itemSize; ++c) {
        const std::uint64_t code = kind == 'U' ? littleEndian(item + 4 * c, 4) : item[c];
        if (code == 0) break;
        if (code > 127) throw InputError(where + ": only ASCII strings are read");
        text.push_back(char(code));
      }
      array.strings[position[k]] = std::move(text);
    }
    return array;
  }
  array.numbers.resize(count);
  for (std::size_t k = 0; k < count; ++k, item += width) {
    const std::uint64_t raw = littleEndian(item, int(width));
    double value = 0.0;
    if (kind == 'f' && width == 8) {
      std::memcpy(&value, &raw, 8);
    } else if (kind == 'f') {
      const auto bits = std::uint32_t(raw);
      float single;
      std::memcpy(&single, &bits, 4);
      value = single;
    } else if (kind == 'i') {
      const int shift = 64 - 8 * int(width);
      value = double(std::int64_t(raw << shift) >> shift);
    } else {
      value = double(raw);
    }
    array.numbers[position[k]] = value;
  }
  return array;
}

std::map<std::string, NpyArray> readNpz(const std::filesystem::path& path) {
  const std::string where = path.string();
  std::error_code code;
  const auto fileSize = std::filesystem::file_size(path, code);
  if (code) throw InputError(where + ": cannot read (" + code.message() + ")");
  if (fileSize > maxInputBytes()) {
    throw InputError(where + ": larger than the input limit of " + std::to_string(maxInputBytes()) +
                     " bytes (RADQUAD_MAX_INPUT_BYTES)");
  }
  int error = 0;
  std::unique_ptr<zip_t, decltype(&zip_discard)> archive(
      zip_open(where.c_str(), ZIP_RDONLY, &error), &zip_discard);
  if (!archive) {
    zip_error_t details;
    zip_error_init_with_code(&details, error);
    const std::string message = zip_error_strerror(&details);
    zip_error_fini(&details);
    throw InputError(where + ": not a readable .npz (zip) archive: " + message);
  }
  std::map<std::string, NpyArray> arrays;
  const zip_int64_t entries = zip_get_num_entries(archive.get(), 0);
  std::uint64_t total = 0;
  for (zip_int64_t k = 0; k < entries; ++k) {
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(archive.get(), zip_uint64_t(k), 0, &stat) != 0 ||
        !(stat.valid & ZIP_STAT_NAME) || !(stat.valid & ZIP_STAT_SIZE)) {
      throw InputError(where + ": unreadable archive member " + std::to_string(k));
    }
    std::string name = stat.name;
    const std::string member = where + ": " + name;
    if (name.size() < 5 || name.substr(name.size() - 4) != ".npy") {
      throw InputError(member + ": not a .npy member");
    }
    total += stat.size;
    if (total > maxInputBytes()) {
      throw InputError(member + ": the archive's arrays exceed the input limit of " +
                       std::to_string(maxInputBytes()) + " bytes (RADQUAD_MAX_INPUT_BYTES)");
    }
    std::unique_ptr<zip_file_t, decltype(&zip_fclose)> file(
        zip_fopen_index(archive.get(), zip_uint64_t(k), 0), &zip_fclose);
    if (!file) throw InputError(member + ": cannot open (" + zip_strerror(archive.get()) + ")");
    std::string bytes(std::size_t(stat.size), '\0');
    const zip_int64_t read = zip_fread(file.get(), bytes.data(), stat.size);
    if (read < 0 || zip_uint64_t(read) != stat.size) {
      throw InputError(member + ": cannot read (" + zip_file_strerror(file.get()) + ")");
    }
    name.resize(name.size() - 4);
    if (arrays.count(name) != 0) throw InputError(member + ": duplicate member");
    arrays.emplace(name, parseNpy(bytes, member));
  }
  return arrays;
}

}  // namespace radquad
