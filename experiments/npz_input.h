// NumPy's .npz archives (numpy.savez and numpy.savez_compressed: a zip of .npy files, read
// with libzip), for rules from data files (experiments/rule_file.h).
//
// Each member NAME.npy is an array in NumPy's format 1.0, 2.0 or 3.0: the magic "\x93NUMPY",
// a header dictionary {'descr': ..., 'fortran_order': ..., 'shape': (...)}, then the data.
// Read are little-endian (or byte-sized) floats ('<f8', '<f4'), integers ('<i8', '<i4',
// '<i2', '|i1', '<u8', '<u4', '<u2', '|u1'), booleans ('|b1'), and strings ('<U' UTF-32
// and '|S' bytes, kept when ASCII); anything else, a truncated member, an archive or member
// larger than maxInputBytes() (json_input.h), or an object array is an InputError naming
// the file and the member.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace radquad {

struct NpyArray {
  std::vector<std::size_t> shape;  // () for a scalar
  bool isString = false;
  std::vector<double> numbers;       // row-major (C order), numbers and booleans
  std::vector<std::string> strings;  // row-major, string arrays

  std::size_t size() const;
};

// Members by name without the ".npy" suffix.
std::map<std::string, NpyArray> readNpz(const std::filesystem::path& path);

// One .npy member's bytes; `where` names it in messages. Exposed for tests.
NpyArray parseNpy(const std::string& bytes, const std::string& where);

}  // namespace radquad
