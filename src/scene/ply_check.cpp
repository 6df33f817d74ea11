#include "scene/ply_check.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "scene/model.h"

namespace penumbra {

namespace {

// Real PLY headers are a few hundred bytes; long comment blocks stay far below this.
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
constexpr std::string_view kHeaderEnd = "\nend_header";

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct ScalarType {
  int bytes = 0;
  bool isInteger = false;
  bool isSigned = false;
};

struct Property {
  ScalarType value;
  std::optional<ScalarType> listLength;  // set for `property list LENGTH VALUE NAME`
};

struct Element {
  std::string name;
  int line = 0;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<Element> elements;
};

std::optional<ScalarType> scalarType(std::string_view name) {
  static const std::unordered_map<std::string_view, ScalarType> kTypes{
      {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, true, false}},
      {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
      {"ushort", {2, true, false}}, {"uint16", {2, true, false}},  {"int", {4, true, true}},
      {"int32", {4, true, true}},   {"uint", {4, true, false}},    {"uint32", {4, true, false}},
      {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
      {"float64", {8, false, true}}};
  const auto found = kTypes.find(name);
  if (found == kTypes.end())
    return std::nullopt;
  return found->second;
}

// A count beyond 64 bits is as impossible as any other count the data cannot hold: it becomes
// the largest one.
std::optional<std::uint64_t> parseCount(std::string_view word) {
  std::uint64_t count = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), count);
  if (error == std::errc::result_out_of_range)
    return std::numeric_limits<std::uint64_t>::max();
  if (error != std::errc() || end != word.data() + word.size())
    return std::nullopt;
  return count;
}

// The element names assimp 5.2 knows. After any other name it reads the count from the start
// of the name itself ("element 300000000 3" declares 300 million elements to it, "element foo 3"
// none): the fuzzer's input declared "element 4294967295face 1".
const std::unordered_set<std::string> kAssimpElementNames{"vertex", "face",     "tristrips",
                                                          "edge",   "material", "TextureFile"};

std::string leadingDigits(const std::string& word) {
  std::size_t digits = 0;
  while (digits < word.size() && std::isdigit(static_cast<unsigned char>(word[digits])))
    ++digits;
  return digits == 0 ? "0" : word.substr(0, digits);
}

std::string cannotRead(const std::filesystem::path& file, const std::string& problem) {
  return "cannot read model " + file.string() + ": " + problem;
}

// A header line as messages quote it: up to 40 characters, other bytes than printable ASCII as
// '?'.
std::string quotedLine(std::string_view line) {
  std::string text;
  for (const char c : line.substr(0, 40))
    text += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return "'" + text + (line.size() > 40 ? "...'" : "'");
}

// The header's format and elements. Anything else than the lines of the PLY format (format,
// comment, obj_info, element, property) is rejected, naming the line: assimp 5.2 reads malformed
// headers in ways of its own, which the fuzzer keeps finding crashes in.
Header parseHeader(const std::filesystem::path& file, std::string_view text) {
  Header header;
  bool formatKnown = false;
  std::unordered_map<std::string, int> firstLineOf;
  std::istringstream lines{std::string(text)};
  std::string line;
  std::getline(lines, line);  // "ply"
  for (int number = 2; std::getline(lines, line); ++number) {
    const auto fail = [&](const std::string& problem) {
      throw ModelError(cannotRead(file, "line " + std::to_string(number) + " of the PLY header (" +
                                            quotedLine(line) + ") " + problem));
    };
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info")
      continue;
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format == "ascii")
        header.format = PlyFormat::Ascii;
      else if (format == "binary_little_endian")
        header.format = PlyFormat::BinaryLittleEndian;
      else if (format == "binary_big_endian")
        header.format = PlyFormat::BinaryBigEndian;
      else
        fail(
            "names no format this reader knows: ascii, binary_little_endian or "
            "binary_big_endian");
      formatKnown = true;
    } else if (keyword == "element") {
      std::string name;
      std::string count;
      words >> name;
      if (kAssimpElementNames.contains(name))
        words >> count;
      else
        count = leadingDigits(name);
      if (const auto [first, inserted] = firstLineOf.emplace(name, number); !inserted)
        throw ModelError(cannotRead(file, "the PLY header declares element '" + name +
                                              "' twice (lines " + std::to_string(first->second) +
                                              " and " + std::to_string(number) +
                                              "); each element is declared once"));
      const std::optional<std::uint64_t> parsed = parseCount(count);
      if (!parsed)
        fail("gives no count: an element line is 'element NAME COUNT'");
      header.elements.push_back({name, number, *parsed, {}});
    } else if (keyword == "property") {
      if (header.elements.empty())
        fail("declares a property before any element");
      std::string type;
      words >> type;
      Property property;
      if (type == "list") {
        std::string lengthType;
        words >> lengthType >> type;
        property.listLength = scalarType(lengthType);
        if (!property.listLength || !property.listLength->isInteger)
          fail("gives no integer type for the list's length");
      }
      const std::optional<ScalarType> value = scalarType(type);
      if (!value)
        fail(
            "names no PLY type: char, uchar, short, ushort, int, uint, float or double (or "
            "int8 to float64)");
      property.value = *value;
      header.elements.back().properties.push_back(property);
    } else {
      fail("is none of the PLY header's lines: format, comment, obj_info, element or property");
    }
  }
  if (!formatKnown)
    throw ModelError(cannotRead(file, "the PLY header has no format line"));
  // Instances of an element without properties take no data, but assimp allocates each of them
  // (the fuzzer's "element 44444444444444444444444ty" took 67 GB).
  for (const Element& element : header.elements) {
    if (element.properties.empty() && element.count > 0)
      throw ModelError(cannotRead(
          file, "the PLY header declares " + std::to_string(element.count) + " '" + element.name +
                    "' elements without properties (line " + std::to_string(element.line) +
                    "); an element with instances has properties"));
  }
  return header;
}

std::string endsWithin(const Element& element, std::uint64_t instance) {
  return "the PLY data ends within element " + std::to_string(instance) + " of the " +
         std::to_string(element.count) + " '" + element.name + "' elements declared on line " +
         std::to_string(element.line) +
         (!kAssimpElementNames.contains(element.name)
              ? " (assimp reads the count of an element whose name it does not "
                "know from the digits the name starts with)"
              : " (is the file truncated?)");
}

std::string listEndsWithin(const Element& element, std::uint64_t instance, std::int64_t length) {
  return "the PLY data ends within the " + std::to_string(length) + "-value list of '" +
         element.name + "' element " + std::to_string(instance) + " (declared on line " +
         std::to_string(element.line) + "; is the file truncated?)";
}

std::string negativeListLength(const Element& element, std::uint64_t instance,
                               std::int64_t length) {
  return "'" + element.name + "' element " + std::to_string(instance) + " (declared on line " +
         std::to_string(element.line) + ") has a list of length " + std::to_string(length) +
         "; a list's length is never negative";
}

// Walks binary data: a value is its type's bytes, a list its length then its values.
class BinaryData {
 public:
  BinaryData(std::string_view bytes, bool bigEndian) : bytes_(bytes), bigEndian_(bigEndian) {}

  std::uint64_t bytesLeft() const { return bytes_.size() - at_; }
  void skip(std::uint64_t count) { at_ += count; }

  std::int64_t readInteger(const ScalarType& type) {
    std::uint64_t bits = 0;
    for (int i = 0; i < type.bytes; ++i) {
      const int byte = bigEndian_ ? i : type.bytes - 1 - i;
      bits = (bits << 8) | static_cast<unsigned char>(bytes_[at_ + byte]);
    }
    at_ += type.bytes;
    const std::uint64_t signBit = std::uint64_t{1} << (8 * type.bytes - 1);
    if (type.isSigned && (bits & signBit))
      return static_cast<std::int64_t>(bits) - static_cast<std::int64_t>(signBit << 1);
    return static_cast<std::int64_t>(bits);
  }

 private:
  std::string_view bytes_;
  std::uint64_t at_ = 0;
  bool bigEndian_;
};

void checkBinaryData(const std::filesystem::path& file, const Header& header,
                     std::string_view bytes) {
  BinaryData data(bytes, header.format == PlyFormat::BinaryBigEndian);
  for (const Element& element : header.elements) {
    std::uint64_t fixedBytes = 0;
    bool hasLists = false;
    for (const Property& property : element.properties) {
      hasLists = hasLists || property.listLength;
      fixedBytes += property.listLength ? 0 : property.value.bytes;
    }
    if (!hasLists) {
      if (fixedBytes > 0 && element.count > data.bytesLeft() / fixedBytes)
        throw ModelError(cannotRead(file, endsWithin(element, data.bytesLeft() / fixedBytes)));
      data.skip(element.count * fixedBytes);
      continue;
    }
    // Each instance takes at least a byte, so this loop ends within the data's size.
    for (std::uint64_t instance = 0; instance < element.count; ++instance) {
      for (const Property& property : element.properties) {
        if (!property.listLength) {
          if (data.bytesLeft() < static_cast<std::uint64_t>(property.value.bytes))
            throw ModelError(cannotRead(file, endsWithin(element, instance)));
          data.skip(property.value.bytes);
          continue;
        }
        if (data.bytesLeft() < static_cast<std::uint64_t>(property.listLength->bytes))
          throw ModelError(cannotRead(file, endsWithin(element, instance)));
        const std::int64_t length = data.readInteger(*property.listLength);
        if (length < 0)
          throw ModelError(cannotRead(file, negativeListLength(element, instance, length)));
        const auto lengthBytes = static_cast<std::uint64_t>(length);
        if (lengthBytes > data.bytesLeft() / property.value.bytes)
          throw ModelError(cannotRead(file, listEndsWithin(element, instance, length)));
        data.skip(lengthBytes * property.value.bytes);
      }
    }
  }
}

// Walks ASCII data: a value is a whitespace-separated word, a list its length then its values.
class AsciiData {
 public:
  explicit AsciiData(std::string_view text) : text_(text) {}

  // The next word, empty at the end of the data.
  std::string_view next() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_])))
      ++at_;
    const std::size_t start = at_;
    while (at_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at_])))
      ++at_;
    return text_.substr(start, at_ - start);
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

void checkAsciiData(const std::filesystem::path& file, const Header& header,
                    std::string_view text) {
  AsciiData data(text);
  for (const Element& element : header.elements) {
    // Each instance takes at least a word (an element without properties has no instances:
    // parseHeader), so this loop ends within the data's size.
    for (std::uint64_t instance = 0; instance < element.count; ++instance) {
      for (const Property& property : element.properties) {
        const std::string_view word = data.next();
        if (word.empty())
          throw ModelError(cannotRead(file, endsWithin(element, instance)));
        if (!property.listLength)
          continue;
        std::int64_t length = 0;
        const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), length);
        if (error != std::errc() || end != word.data() + word.size())
          throw ModelError(cannotRead(file, "'" + element.name + "' element " +
                                                std::to_string(instance) + " (declared on line " +
                                                std::to_string(element.line) +
                                                ") has the list length " + quotedLine(word) +
                                                "; a list's length is a whole number"));
        if (length < 0)
          throw ModelError(cannotRead(file, negativeListLength(element, instance, length)));
        for (std::int64_t value = 0; value < length; ++value)
          if (data.next().empty())
            throw ModelError(cannotRead(file, listEndsWithin(element, instance, length)));
      }
    }
  }
}

}  // namespace

void checkPlyFile(const std::filesystem::path& file, std::uintmax_t fileBytes) {
  std::ifstream in(file, std::ios::binary);
  std::string head(kMaxHeaderBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const auto lower = [](char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  };
  if (head.size() < 3 || lower(head[0]) != 'p' || lower(head[1]) != 'l' || lower(head[2]) != 'y')
    return;
  std::size_t headerEnd = std::string::npos;
  std::size_t dataStart = 0;
  for (std::size_t at = head.find(kHeaderEnd); at != std::string::npos;
       at = head.find(kHeaderEnd, at + 1)) {
    const std::size_t next = at + kHeaderEnd.size();
    if (next < head.size() && (head[next] == '\n' || head[next] == '\r')) {
      headerEnd = at;
      dataStart =
          next + (head[next] == '\r' && next + 1 < head.size() && head[next + 1] == '\n' ? 2 : 1);
      break;
    }
  }
  if (headerEnd == std::string::npos)
    throw ModelError(cannotRead(file, "the PLY header has no end_header line in its first " +
                                          std::to_string(kMaxHeaderBytes / 1024) +
                                          " KiB (is the file truncated?)"));
  const Header header = parseHeader(file, std::string_view(head).substr(0, headerEnd));

  std::string data(fileBytes > dataStart ? fileBytes - dataStart : 0, '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(dataStart));
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  data.resize(static_cast<std::size_t>(in.gcount()));
  if (header.format == PlyFormat::Ascii)
    checkAsciiData(file, header, data);
  else
    checkBinaryData(file, header, data);
}

}  // namespace penumbra
