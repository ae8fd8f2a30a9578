#include "meshing/inputs/detail/mesh_readers.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "common/errors.h"
#include "common/run_limits.h"

namespace delmesh::detail {
namespace {

//! Whole number of a word: optional sign, then decimal digits only.
bool parse_whole(std::string_view word, long long& value) {
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  if (word.empty() || word[0] == '+') return false;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

//! A real number of a word (decimal, exponent, inf, nan; an optional leading '+').
bool parse_real(std::string_view word, double& value) {
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  if (word.empty() || word[0] == '+') return false;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (end != word.data() + word.size()) return false;
  // Out of double's range: strtod's answer (inf on overflow, 0 or a subnormal on underflow); the
  // word is known to be a number, so the C locale's decimal point is the only one met here.
  if (error == std::errc::result_out_of_range) value = std::strtod(std::string(word).c_str(), nullptr);
  return error == std::errc() || error == std::errc::result_out_of_range;
}

//! Refuses a count the file cannot hold: every element takes at least one byte in any encoding.
void check_count_fits(const std::string& path, std::uintmax_t count, std::size_t bytes) {
  if (count > bytes)
    mesh_file_error(path, "the header declares " + std::to_string(count) + " elements but the file has only " +
                              std::to_string(bytes) + " bytes (truncated, or a corrupt count)");
}

//! "truncated: the file ends in WHAT I of the N declared".
[[noreturn]] void truncated_in(const std::string& path, const std::string& what, std::uintmax_t i,
                               std::uintmax_t n) {
  mesh_file_error(path, "truncated: the file ends in " + what + " " + std::to_string(i) + " of the " +
                            std::to_string(n) + " declared");
}

//! A count of a text header: a whole number of at most 19 digits, no sign.
std::uintmax_t header_count(const std::string& path, std::string_view word, const std::string& what) {
  const std::string text(word);
  if (!text.empty() && text[0] == '-')
    mesh_file_error(path, "the header declares a negative " + what + " (" + printable(text) + ")");
  const bool digits = !text.empty() && text.size() <= 19 &&
                      std::all_of(text.begin(), text.end(), [](unsigned char c) { return c >= '0' && c <= '9'; });
  if (!digits) mesh_file_error(path, "the header's " + what + " '" + printable(text) + "' is not a whole number below 10^19");
  return std::stoull(text);
}

// ------------------------------------------------------------------------------------------------
// Text: words separated by blanks, '#' comments to the end of a line (OFF only).
// ------------------------------------------------------------------------------------------------

class TextCursor {
 public:
  TextCursor(const std::string& text, std::size_t start, bool comments)
      : text_(text), at_(start), comments_(comments) {}
  void seek(std::size_t at) { at_ = at; }

  //! The next word on the current line, or an empty view at the end of the line.
  std::string_view word_in_line() {
    skip_blanks();
    if (at_ >= text_.size() || text_[at_] == '\n') return {};
    return take_word();
  }
  //! The next word, on this line or a later one, or an empty view at the end of the text.
  std::string_view word() {
    for (;;) {
      skip_blanks();
      if (at_ >= text_.size()) return {};
      if (text_[at_] != '\n') return take_word();
      ++at_;
    }
  }
  //! Moves to the start of the next line unless at the start of a line already.
  void finish_line() {
    if (at_ == 0 || at_ > text_.size() || text_[at_ - 1] == '\n') return;
    const std::size_t end = text_.find('\n', at_);
    at_ = end == std::string::npos ? text_.size() : end + 1;
  }
  //! Moves to the next line that has a word (after finish_line); false at the end of the text.
  bool next_line_with_words() {
    finish_line();
    for (;;) {
      skip_blanks();
      if (at_ >= text_.size()) return false;
      if (text_[at_] != '\n') return true;
      ++at_;
    }
  }
  std::size_t position() const { return at_; }

 private:
  static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_blanks() {
    while (at_ < text_.size()) {
      if (blank(text_[at_])) {
        ++at_;
      } else if (comments_ && text_[at_] == '#') {
        const std::size_t end = text_.find('\n', at_);
        at_ = end == std::string::npos ? text_.size() : end;
      } else {
        return;
      }
    }
  }
  std::string_view take_word() {
    const std::size_t begin = at_;
    while (at_ < text_.size() && text_[at_] != '\n' && !blank(text_[at_]) && !(comments_ && text_[at_] == '#')) ++at_;
    return std::string_view(text_).substr(begin, at_ - begin);
  }

  const std::string& text_;
  std::size_t at_;
  bool comments_;
};

// ------------------------------------------------------------------------------------------------
// Binary: fixed-size numbers of either byte order.
// ------------------------------------------------------------------------------------------------

class ByteCursor {
 public:
  ByteCursor(const std::string& bytes, std::size_t start, bool big_endian)
      : bytes_(bytes), at_(start), swap_(big_endian != host_is_big_endian()) {}

  bool has(std::uintmax_t n) const { return at_ <= bytes_.size() && n <= bytes_.size() - at_; }
  //! Reads a T (false if the bytes run out).
  template <class T>
  bool read(T& value) {
    if (!has(sizeof(T))) return false;
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + at_, sizeof(T));
    if (swap_) std::reverse(raw, raw + sizeof(T));
    std::memcpy(&value, raw, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool skip(std::uintmax_t n) {
    if (!has(n)) return false;
    at_ += static_cast<std::size_t>(n);
    return true;
  }

 private:
  static bool host_is_big_endian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 0;
  }

  const std::string& bytes_;
  std::size_t at_;
  bool swap_;
};

// ------------------------------------------------------------------------------------------------
// OFF
// ------------------------------------------------------------------------------------------------

//! What the OFF keyword's prefixes declare.
struct OffLayout {
  bool texture = false, colour = false, normal = false, homogeneous = false, dimension = false, binary = false;
};

//! Parses "[ST][C][N][4][n]OFF"; false if word is not such a keyword.
bool parse_off_keyword(std::string_view word, OffLayout& layout) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  std::string_view prefix = word.substr(0, word.size() - 3);
  const auto take = [&](std::string_view p) {
    if (prefix.substr(0, p.size()) != p) return false;
    prefix.remove_prefix(p.size());
    return true;
  };
  layout.texture = take("ST");
  layout.colour = take("C");
  layout.normal = take("N");
  layout.homogeneous = take("4");
  layout.dimension = take("n");
  return prefix.empty();
}

//! Stores a vertex read in homogeneous or plain coordinates.
void add_vertex(const std::string& path, PolygonSoup& soup, const double* c, bool homogeneous) {
  if (homogeneous) {
    if (c[3] == 0) mesh_file_error(path, "vertex " + std::to_string(soup.points.size()) + " has the homogeneous coordinate 0");
    soup.points.emplace_back(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
  } else {
    soup.points.emplace_back(c[0], c[1], c[2]);
  }
}

void reserve(const std::string& contents, PolygonSoup& soup, std::uintmax_t vertices, std::uintmax_t faces) {
  // Counts were checked against the file size; a vertex or face takes at least 3 bytes.
  soup.points.reserve(static_cast<std::size_t>(std::min<std::uintmax_t>(vertices, contents.size() / 3)));
  const auto face_count = static_cast<std::size_t>(std::min<std::uintmax_t>(faces, contents.size() / 3));
  soup.offsets.reserve(face_count + 1);
  soup.corners.reserve(3 * face_count);
}

//! Refuses a face of fewer than three vertices before its indices are read.
void check_face_size(const std::string& path, std::uintmax_t face, long long size) {
  if (size < 3) too_few_corners(path, static_cast<std::size_t>(face), std::to_string(size));
}

PolygonSoup read_binary_off(const std::string& path, const std::string& contents, std::size_t start,
                             const OffLayout& layout) {
  ByteCursor in(contents, start, /*big_endian=*/true);
  std::int32_t dimension = 3, nv = 0, nf = 0, ne = 0;
  if (layout.dimension && !in.read(dimension)) mesh_file_error(path, "truncated: the binary header ends before its dimension");
  if (dimension != 3)
    mesh_file_error(path, "the header declares dimension " + std::to_string(dimension) +
                              "; only three-dimensional OFF files are supported");
  if (!in.read(nv) || !in.read(nf) || !in.read(ne)) mesh_file_error(path, "truncated: the binary header ends before its counts");
  if (nv < 0) mesh_file_error(path, "the header declares a negative vertex count (" + std::to_string(nv) + ")");
  if (nf < 0) mesh_file_error(path, "the header declares a negative face count (" + std::to_string(nf) + ")");
  check_count_fits(path, static_cast<std::uintmax_t>(nv), contents.size());
  check_count_fits(path, static_cast<std::uintmax_t>(nf), contents.size());
  PolygonSoup soup;
  reserve(contents, soup, static_cast<std::uintmax_t>(nv), static_cast<std::uintmax_t>(nf));
  const int coordinates = layout.homogeneous ? 4 : 3;
  // Geomview's binary vertex: coordinates, normal (3), colour (4), texture (2), all float32.
  const int extra = (layout.normal ? 3 : 0) + (layout.colour ? 4 : 0) + (layout.texture ? 2 : 0);
  for (std::int32_t v = 0; v < nv; ++v) {
    double c[4] = {0, 0, 0, 1};
    for (int k = 0; k < coordinates; ++k) {
      float value = 0;
      if (!in.read(value)) truncated_in(path, "vertex", static_cast<std::uintmax_t>(v), static_cast<std::uintmax_t>(nv));
      c[k] = value;
    }
    if (!in.skip(4u * static_cast<unsigned>(extra))) truncated_in(path, "vertex", static_cast<std::uintmax_t>(v), static_cast<std::uintmax_t>(nv));
    add_vertex(path, soup, c, layout.homogeneous);
  }
  for (std::int32_t f = 0; f < nf; ++f) {
    const auto face = static_cast<std::size_t>(f);
    std::int32_t size = 0;
    if (!in.read(size)) truncated_in(path, "face", face, static_cast<std::uintmax_t>(nf));
    check_face_size(path, face, size);
    // Each index is read before it is stored: a false size ends at the end of the file.
    for (std::int32_t k = 0; k < size; ++k) {
      std::int32_t i = 0;
      if (!in.read(i)) truncated_in(path, "face", face, static_cast<std::uintmax_t>(nf));
      soup.corners.push_back(static_cast<std::size_t>(static_cast<long long>(i)));
    }
    std::int32_t colours = 0;
    if (!in.read(colours)) truncated_in(path, "face", face, static_cast<std::uintmax_t>(nf));
    if (colours < 0 || colours > 4) mesh_file_error(path, "face " + std::to_string(face) + " has " + std::to_string(colours) + " colour components (at most 4)");
    if (!in.skip(4u * static_cast<unsigned>(colours))) truncated_in(path, "face", face, static_cast<std::uintmax_t>(nf));
    soup.offsets.push_back(soup.corners.size());
  }
  return soup;
}

// ------------------------------------------------------------------------------------------------
// PLY
// ------------------------------------------------------------------------------------------------

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool parse_ply_type(std::string_view word, PlyType& type) {
  static const std::pair<std::string_view, PlyType> names[] = {
      {"char", PlyType::int8},     {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},   {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16}, {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},   {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32}, {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [name, t] : names)
    if (word == name) {
      type = t;
      return true;
    }
  return false;
}

bool is_integral(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

//! The range of an integral type.
void integral_range(PlyType type, long long& lo, long long& hi) {
  switch (type) {
    case PlyType::int8: lo = -128, hi = 127; break;
    case PlyType::uint8: lo = 0, hi = 255; break;
    case PlyType::int16: lo = -32768, hi = 32767; break;
    case PlyType::uint16: lo = 0, hi = 65535; break;
    case PlyType::int32: lo = std::numeric_limits<std::int32_t>::min(), hi = std::numeric_limits<std::int32_t>::max(); break;
    case PlyType::uint32: lo = 0, hi = std::numeric_limits<std::uint32_t>::max(); break;
    default: lo = hi = 0; break;
  }
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::uint8;  // for a list
  PlyType type = PlyType::float32;      // of the value, or of a list's items
};

struct PlyElement {
  std::string name;
  std::uintmax_t count = 0;
  std::vector<PlyProperty> properties;
};

//! A number of the body: integral types as long long, the others as double.
struct PlyValue {
  long long whole = 0;
  double real = 0;
};

//! Reads the values of the body, ASCII or binary.
class PlyBody {
 public:
  PlyBody(const std::string& contents, std::size_t start, int format)
      : text_(contents, start, /*comments=*/false), bytes_(contents, start, format == 2), ascii_(format == 0) {}

  //! Reads one value of type; false if the file ends.  Throws on a word that is not a value of type.
  bool read(const std::string& path, PlyType type, const std::string& where, PlyValue& value) {
    if (ascii_) {
      const std::string_view word = text_.word();
      if (word.empty()) return false;
      if (is_integral(type)) {
        long long lo = 0, hi = 0;
        integral_range(type, lo, hi);
        if (!parse_whole(word, value.whole) || value.whole < lo || value.whole > hi)
          mesh_file_error(path, where + ": '" + printable(std::string(word)) + "' is not an integer of the declared type");
        value.real = static_cast<double>(value.whole);
      } else {
        if (!parse_real(word, value.real)) mesh_file_error(path, where + ": '" + printable(std::string(word)) + "' is not a number");
      }
      return true;
    }
    switch (type) {
      case PlyType::int8: return binary<std::int8_t>(value);
      case PlyType::uint8: return binary<std::uint8_t>(value);
      case PlyType::int16: return binary<std::int16_t>(value);
      case PlyType::uint16: return binary<std::uint16_t>(value);
      case PlyType::int32: return binary<std::int32_t>(value);
      case PlyType::uint32: return binary<std::uint32_t>(value);
      case PlyType::float32: return binary<float>(value);
      case PlyType::float64: return binary<double>(value);
    }
    return false;
  }
  //! Skips n values of type; false if the file ends first.
  bool skip(const std::string& path, PlyType type, std::uintmax_t n, const std::string& where) {
    if (!ascii_) {
      const std::uintmax_t size = type == PlyType::int8 || type == PlyType::uint8     ? 1
                                  : type == PlyType::int16 || type == PlyType::uint16 ? 2
                                  : type == PlyType::float64                          ? 8
                                                                                      : 4;
      return n <= std::numeric_limits<std::uintmax_t>::max() / size && bytes_.skip(n * size);
    }
    PlyValue ignored;
    for (std::uintmax_t i = 0; i < n; ++i)
      if (!read(path, type, where, ignored)) return false;
    return true;
  }

 private:
  template <class T>
  bool binary(PlyValue& value) {
    T raw{};
    if (!bytes_.read(raw)) return false;
    if constexpr (std::is_integral_v<T>) {
      value.whole = static_cast<long long>(raw);
      value.real = static_cast<double>(raw);
    } else {
      value.real = static_cast<double>(raw);
    }
    return true;
  }

  TextCursor text_;
  ByteCursor bytes_;
  bool ascii_;
};

// ------------------------------------------------------------------------------------------------
// STL
// ------------------------------------------------------------------------------------------------

//! Merges the corners of an STL file into shared points: exactly equal coordinates (after -0 is
//! made +0) are one point, numbered in the order of first appearance.
class CornerMerger {
 public:
  explicit CornerMerger(PolygonSoup& soup) : soup_(soup) {}

  //! Adds the triangle of corners c[0..8]; throws for a non-finite coordinate.
  void add_triangle(const std::string& path, std::uintmax_t triangle, const double* c) {
    for (int k = 0; k < 9; ++k)
      if (!std::isfinite(c[k]))
        mesh_file_error(path, "triangle " + std::to_string(triangle) + " has a non-finite coordinate");
    for (int corner = 0; corner < 3; ++corner) {
      // Adding 0 turns -0 into +0, so that the two are one key as they are one number.
      const Key key{c[3 * corner] + 0.0, c[3 * corner + 1] + 0.0, c[3 * corner + 2] + 0.0};
      const auto [it, added] = index_.try_emplace(key, soup_.points.size());
      if (added) soup_.points.emplace_back(key[0], key[1], key[2]);
      soup_.corners.push_back(it->second);
    }
    soup_.offsets.push_back(soup_.corners.size());
  }

 private:
  using Key = std::array<double, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& key) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ull;
      for (double x : key) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &x, sizeof bits);
        h ^= bits + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      }
      return static_cast<std::size_t>(h);
    }
  };
  PolygonSoup& soup_;
  std::unordered_map<Key, std::size_t, KeyHash> index_;
};

constexpr std::size_t stl_header_bytes = 84, stl_record_bytes = 50;

//! The file's size if it were binary STL with the count at byte 80 (size ≥ 84).
std::uintmax_t binary_stl_size(const std::string& contents, std::uint32_t& count) {
  ByteCursor in(contents, 80, /*big_endian=*/false);
  (void)in.read(count);
  return stl_header_bytes + std::uintmax_t{stl_record_bytes} * count;
}

PolygonSoup read_binary_stl(const std::string& path, const std::string& contents, std::uint32_t count) {
  PolygonSoup soup;
  soup.offsets.reserve(std::size_t{count} + 1);  // the size was checked: 50 bytes per triangle
  soup.corners.reserve(3 * std::size_t{count});
  CornerMerger merger(soup);
  ByteCursor in(contents, stl_header_bytes, /*big_endian=*/false);
  const RunLimits& limits = RunLimits::current();
  for (std::uint32_t t = 0; t < count; ++t) {
    limits.check("reading the mesh file");
    double c[9];
    in.skip(12);  // the normal
    for (double& x : c) {
      float value = 0;
      if (!in.read(value)) truncated_in(path, "triangle", t, count);  // not reached: the size was checked
      x = value;
    }
    in.skip(2);  // the attribute byte count
    merger.add_triangle(path, t, c);
  }
  return soup;
}

//! A keyword of ASCII STL in any case.
bool is_keyword(std::string_view word, std::string_view keyword) {
  return word.size() == keyword.size() &&
         std::equal(word.begin(), word.end(), keyword.begin(),
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

//! Reads ASCII STL; `not_binary` is appended to every error (why the file is not binary STL
//! either, or "").
PolygonSoup read_ascii_stl(const std::string& path, const std::string& contents, const std::string& not_binary) {
  const auto fail = [&](const std::string& why) { mesh_file_error(path, why + not_binary); };
  TextCursor in(contents, 0, /*comments=*/false);
  PolygonSoup soup;
  CornerMerger merger(soup);
  const RunLimits& limits = RunLimits::current();
  std::uintmax_t facet = 0;
  std::string where;
  const auto expect = [&](std::string_view keyword) {
    const std::string_view word = in.word();
    if (word.empty()) fail("truncated: the file ends in " + where + " (expected '" + std::string(keyword) + "')");
    if (!is_keyword(word, keyword))
      fail(where + ": expected '" + std::string(keyword) + "', got '" + printable(std::string(word)) + "'");
  };
  where = "its first line";
  expect("solid");
  for (;;) {
    in.finish_line();  // the solid's name
    for (;;) {
      where = "facet " + std::to_string(facet);
      const std::string_view word = in.word();
      if (word.empty()) fail("truncated: the file ends before 'endsolid' (after " + std::to_string(facet) + " facets)");
      if (is_keyword(word, "endsolid")) break;
      if (!is_keyword(word, "facet"))
        fail(where + ": expected 'facet' or 'endsolid', got '" + printable(std::string(word)) + "'");
      limits.check("reading the mesh file");
      expect("normal");
      for (int k = 0; k < 3; ++k)
        if (in.word().empty()) fail("truncated: the file ends in " + where + "'s normal");
      expect("outer");
      expect("loop");
      double c[9];
      for (int corner = 0; corner < 3; ++corner) {
        expect("vertex");
        for (int k = 0; k < 3; ++k) {
          const std::string_view number = in.word();
          if (number.empty()) fail("truncated: the file ends in " + where + "'s vertex " + std::to_string(corner));
          if (!parse_real(number, c[3 * corner + k]))
            fail(where + ": '" + printable(std::string(number)) + "' is not a number");
        }
      }
      expect("endloop");
      expect("endfacet");
      merger.add_triangle(path, facet, c);
      ++facet;
    }
    in.finish_line();  // the solid's name again
    const std::string_view next = in.word();
    if (next.empty()) return soup;
    if (!is_keyword(next, "solid"))
      fail("after 'endsolid': expected 'solid' or the end of the file, got '" + printable(std::string(next)) + "'");
  }
}

}  // namespace

void mesh_file_error(const std::string& path, const std::string& why) {
  throw InvalidInput("mesh file '" + path + "': " + why);
}

void not_a_triangle(const std::string& path, std::size_t face, const std::string& size) {
  mesh_file_error(path, "face " + std::to_string(face) + " has " + size + " vertices; only triangle meshes are supported");
}

void too_few_corners(const std::string& path, std::size_t face, const std::string& size) {
  mesh_file_error(path, "face " + std::to_string(face) + " has " + size + " vertices (a face needs at least three)");
}

std::string printable(const std::string& word) {
  std::string out;
  for (std::size_t i = 0; i < word.size() && i < 32; ++i) {
    const unsigned char c = static_cast<unsigned char>(word[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (word.size() > 32) out += "...";
  return out;
}

std::string vertex_range(std::uintmax_t n, std::uintmax_t first) {
  if (n == 0) return "the file has no vertices";
  return "the file has " + std::to_string(n) + " vertices (numbered " + std::to_string(first) + " to " +
         std::to_string(first + n - 1) + ")";
}

PolygonSoup read_off(const std::string& path, const std::string& contents) {
  TextCursor in(contents, 0, /*comments=*/true);
  // 1. The keyword, if any, and its prefixes; BINARY switches to the binary layout after its line.
  OffLayout layout;
  std::string_view word = in.word();
  if (word.empty()) mesh_file_error(path, "has no OFF header (only blanks and comments)");
  bool counts_start = true;
  if (word.find("OFF") != std::string_view::npos) {
    if (!parse_off_keyword(word, layout))
      mesh_file_error(path, "unknown OFF keyword '" + printable(std::string(word)) + "' (expected [ST][C][N][4][n]OFF)");
    counts_start = false;
    const std::size_t after_keyword = in.position();
    if (in.word_in_line() == "BINARY") {
      in.finish_line();
      return read_binary_off(path, contents, in.position(), layout);
    }
    in.seek(after_keyword);
  }
  // 2. Dimension and counts; the rest of the counts' line (the edge count) is ignored.
  if (counts_start) in.seek(0);
  if (layout.dimension) {
    const std::string_view d = in.word();
    if (d != "3")
      mesh_file_error(path, "the header declares dimension '" + printable(std::string(d)) +
                                "'; only three-dimensional OFF files are supported");
  }
  const std::string_view nv_word = in.word();
  if (nv_word.empty()) mesh_file_error(path, "the OFF header has no vertex and face counts");
  const std::uintmax_t nv = header_count(path, nv_word, "vertex count");
  const std::string_view nf_word = in.word();
  if (nf_word.empty()) mesh_file_error(path, "the OFF header has no face count");
  const std::uintmax_t nf = header_count(path, nf_word, "face count");
  check_count_fits(path, nv, contents.size());
  check_count_fits(path, nf, contents.size());
  in.finish_line();
  PolygonSoup soup;
  reserve(contents, soup, nv, nf);
  // 3. Vertices: the coordinates word by word; normal, colour and texture (whose number of fields
  // varies) are the rest of the vertex's line.
  const bool extra_fields = layout.normal || layout.colour || layout.texture;
  const int coordinates = layout.homogeneous ? 4 : 3;
  const RunLimits& limits = RunLimits::current();
  for (std::uintmax_t v = 0; v < nv; ++v) {
    limits.check("reading the mesh file");
    double c[4] = {0, 0, 0, 1};
    for (int k = 0; k < coordinates; ++k) {
      word = in.word();
      if (word.empty()) truncated_in(path, "vertex", v, nv);
      if (!parse_real(word, c[k]))
        mesh_file_error(path, "vertex " + std::to_string(v) + ": '" + printable(std::string(word)) + "' is not a number");
    }
    add_vertex(path, soup, c, layout.homogeneous);
    if (extra_fields) in.finish_line();
  }
  // 4. Faces, one per line: the size, the indices, then an optional colour (ignored).
  for (std::uintmax_t f = 0; f < nf; ++f) {
    limits.check("reading the mesh file");
    if (!in.next_line_with_words())
      mesh_file_error(path, "truncated: the file ends before face " + std::to_string(f) + " of the " +
                                std::to_string(nf) + " declared");
    const std::string where = "face " + std::to_string(f);
    word = in.word_in_line();
    long long size = 0;
    if (!parse_whole(word, size) || size < 1) mesh_file_error(path, where + ": '" + printable(std::string(word)) + "' is not a vertex count");
    check_face_size(path, f, size);
    for (long long k = 0; k < size; ++k) {
      word = in.word_in_line();
      if (word.empty())
        mesh_file_error(path, where + " lists fewer vertices than its count " + std::to_string(size) +
                                  (f + 1 == nf ? " (truncated?)" : ""));
      long long i = 0;
      if (!parse_whole(word, i)) mesh_file_error(path, where + ": '" + printable(std::string(word)) + "' is not a vertex index");
      soup.corners.push_back(static_cast<std::size_t>(i));
    }
    soup.offsets.push_back(soup.corners.size());
    in.finish_line();
  }
  return soup;
}

namespace {

// What a PLY header declares: its elements with their properties, the format (0 ascii, 1 binary
// little-endian, 2 binary big-endian) and where the body begins.
struct PlyHeader {
  std::vector<PlyElement> elements;
  int format = -1;
  std::size_t body = 0;
};

// The format named by a header's format line `words`.
int ply_format(const std::string& path, const std::vector<std::string_view>& words, const std::string& where) {
  if (words.size() < 2) mesh_file_error(path, where + ": the format line names no format");
  if (words[1] == "ascii") return 0;
  if (words[1] == "binary_little_endian") return 1;
  if (words[1] == "binary_big_endian") return 2;
  mesh_file_error(path, where + ": unknown format '" + printable(std::string(words[1])) + "'");
}

// The element declared by an element line `words`, not one of `elements` already declared.
PlyElement ply_element(const std::string& path, const std::vector<std::string_view>& words, const std::string& where,
                       const std::vector<PlyElement>& elements) {
  if (words.size() != 3) mesh_file_error(path, where + ": an element line is 'element NAME COUNT'");
  PlyElement e;
  e.name = std::string(words[1]);
  e.count = header_count(path, words[2], "number of " + printable(e.name) + " elements");
  for (const PlyElement& other : elements)
    if (other.name == e.name) mesh_file_error(path, where + ": element '" + printable(e.name) + "' is declared twice");
  return e;
}

// The property declared by a property line `words`.
PlyProperty ply_property(const std::string& path, const std::vector<std::string_view>& words, const std::string& where) {
  PlyProperty p;
  const bool list = words.size() >= 2 && words[1] == "list";
  if (list ? words.size() != 5 : words.size() != 3)
    mesh_file_error(path, where + ": a property line is 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
  p.list = list;
  if (list && (!parse_ply_type(words[2], p.count_type) || !is_integral(p.count_type)))
    mesh_file_error(path, where + ": '" + printable(std::string(words[2])) + "' is not an integer type for a list's size");
  if (!parse_ply_type(words[list ? 3 : 1], p.type))
    mesh_file_error(path, where + ": unknown type '" + printable(std::string(words[list ? 3 : 1])) + "'");
  p.name = std::string(words[list ? 4 : 2]);
  return p;
}

// The header, line by line, up to end_header; throws for anything it does not declare properly.
PlyHeader read_ply_header(const std::string& path, const std::string& contents) {
  PlyHeader h;
  std::size_t at = 0;
  bool ended = false;
  for (std::size_t line_number = 1; at < contents.size(); ++line_number) {
    const std::size_t end = std::min(contents.find('\n', at), contents.size());
    std::string line = contents.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string_view> words;
    TextCursor fields(line, 0, /*comments=*/false);
    for (std::string_view w = fields.word(); !w.empty(); w = fields.word()) words.push_back(w);
    const std::string where = "header line " + std::to_string(line_number);
    if (line_number == 1) {
      if (line != "ply") mesh_file_error(path, "is not a PLY file (its first line is not 'ply')");
      continue;
    }
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    if (keyword == "end_header") {
      ended = true;
      break;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      h.format = ply_format(path, words, where);
    } else if (keyword == "element") {
      h.elements.push_back(ply_element(path, words, where, h.elements));
    } else if (keyword == "property") {
      if (h.elements.empty()) mesh_file_error(path, where + ": a property line comes before any element line");
      h.elements.back().properties.push_back(ply_property(path, words, where));
    } else {
      mesh_file_error(path, where + ": unknown header keyword '" + printable(std::string(keyword)) + "'");
    }
  }
  if (!ended) mesh_file_error(path, "PLY header has no end_header");
  if (h.format < 0) mesh_file_error(path, "the PLY header has no format line");
  h.body = std::min(at, contents.size());
  for (const PlyElement& e : h.elements) check_count_fits(path, e.count, contents.size() - h.body);
  return h;
}

// Where the coordinates and the faces' indices are: their property numbers in the vertex and
// face elements.
struct PlyLayout {
  int x = -1, y = -1, z = -1, indices = -1;
};

// The layout of the elements; throws when the vertex or face element lacks its properties.
PlyLayout ply_layout(const std::string& path, const std::vector<PlyElement>& elements) {
  PlyLayout l;
  for (const PlyElement& e : elements) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z")) {
        if (p.list) mesh_file_error(path, "the vertex property '" + p.name + "' is a list, not a number");
        (p.name == "x" ? l.x : p.name == "y" ? l.y : l.z) = static_cast<int>(k);
      }
      if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        if (!p.list || !is_integral(p.type))
          mesh_file_error(path, "the face property '" + p.name + "' is not a list of integers");
        l.indices = static_cast<int>(k);
      }
    }
    if (e.name == "vertex" && (l.x < 0 || l.y < 0 || l.z < 0))
      mesh_file_error(path, "the vertex element lacks one of the properties x, y, z");
    if (e.name == "face" && l.indices < 0)
      mesh_file_error(path, "the face element has no list property vertex_indices");
  }
  return l;
}

// The instances of one element of the body: a vertex's coordinates and a face's indices into
// `soup`, the other properties and elements read past.
void read_ply_element(const std::string& path, const std::string& contents, const PlyElement& e,
                      const PlyLayout& layout, PlyBody& in, PolygonSoup& soup) {
  const bool vertex = e.name == "vertex", face = e.name == "face";
  if (vertex) reserve(contents, soup, e.count, 0);
  if (face) reserve(contents, soup, 0, e.count);
  const std::string what = vertex || face ? e.name : "element '" + printable(e.name) + "'";
  const RunLimits& limits = RunLimits::current();
  for (std::uintmax_t i = 0; i < e.count; ++i) {
    limits.check("reading the mesh file");
    const std::string where = what + " " + std::to_string(i);
    double c[3] = {0, 0, 0};
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      PlyValue value;
      if (!p.list) {
        if (!in.read(path, p.type, where, value)) truncated_in(path, what, i, e.count);
        if (vertex && static_cast<int>(k) == layout.x) c[0] = value.real;
        if (vertex && static_cast<int>(k) == layout.y) c[1] = value.real;
        if (vertex && static_cast<int>(k) == layout.z) c[2] = value.real;
        continue;
      }
      if (!in.read(path, p.count_type, where, value)) truncated_in(path, what, i, e.count);
      if (value.whole < 0) mesh_file_error(path, where + ": the list '" + printable(p.name) + "' has a negative size");
      const auto size = static_cast<std::uintmax_t>(value.whole);
      if (!(face && static_cast<int>(k) == layout.indices)) {
        if (!in.skip(path, p.type, size, where)) truncated_in(path, what, i, e.count);
        continue;
      }
      check_face_size(path, i, static_cast<long long>(std::min<std::uintmax_t>(size, 3)));
      for (std::uintmax_t j = 0; j < size; ++j) {
        if (!in.read(path, p.type, where, value)) truncated_in(path, what, i, e.count);
        soup.corners.push_back(static_cast<std::size_t>(value.whole));
      }
    }
    if (vertex) soup.points.emplace_back(c[0], c[1], c[2]);
    if (face) soup.offsets.push_back(soup.corners.size());
  }
}

}  // namespace

PolygonSoup read_ply(const std::string& path, const std::string& contents) {
  // 1. The header, line by line, up to end_header.
  const PlyHeader header = read_ply_header(path, contents);
  // 2. Where the coordinates and the faces' indices are.
  const PlyLayout layout = ply_layout(path, header.elements);
  // 3. The body, element after element.
  PolygonSoup soup;
  PlyBody in(contents, header.body, header.format);
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;  // takes no bytes
    read_ply_element(path, contents, e, layout, in, soup);
  }
  return soup;
}

PolygonSoup read_stl(const std::string& path, const std::string& contents) {
  std::size_t first = 0;
  while (first < contents.size() && std::isspace(static_cast<unsigned char>(contents[first]))) ++first;
  const bool solid = contents.size() - first >= 5 && is_keyword(std::string_view(contents).substr(first, 5), "solid");
  if (contents.size() >= stl_header_bytes) {
    std::uint32_t count = 0;
    const std::uintmax_t size = binary_stl_size(contents, count);
    if (size == contents.size()) return read_binary_stl(path, contents, count);
    const std::string mismatch = "its 84-byte header declares " + std::to_string(count) +
                                 " triangles, which take 84 + 50 x " + std::to_string(count) + " = " +
                                 std::to_string(size) + " bytes, but the file has " + std::to_string(contents.size()) +
                                 " bytes";
    if (solid) return read_ascii_stl(path, contents, " (nor is it binary STL: " + mismatch + ")");
    mesh_file_error(path, "binary STL: " + mismatch + " (truncated, or a corrupt count)");
  }
  if (solid) return read_ascii_stl(path, contents, "");
  mesh_file_error(path, "truncated: binary STL has an 84-byte header, the file has " + std::to_string(contents.size()) +
                            " bytes (and it is not ASCII STL, which begins with 'solid')");
}

}  // namespace delmesh::detail
