// DSDL parsing for signatures (see dsdl_parser.hpp). Mirrors pydronecan's dsdl/parser.py:
// comments and constants dropped, cast modes made explicit, [<N] written [<=N-1], nested
// types by full name, void fields without a name.
#include "bridge/dronecan/dsdl_parser.hpp"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "bridge/dronecan/crc.hpp"

namespace a3::bridge {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

// Python's str.replace: every non-overlapping occurrence, left to right.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t found = text.find(from, pos);
    if (found == std::string::npos) break;
    out += text.substr(pos, found - pos) + to;
    pos = found + from.size();
  }
  return out + text.substr(pos);
}

std::string strip(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r\n");
  return s.substr(begin, end - begin + 1);
}

unsigned bit_length_of(uint64_t value) {
  unsigned bits = 0;
  while (value != 0) {
    ++bits;
    value >>= 1;
  }
  return bits;
}

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

uint64_t dsdl_signature(const std::string& normalized_definition,
                        const std::vector<uint64_t>& nested_signatures) {
  Crc64We crc;
  crc.add(normalized_definition);
  for (const uint64_t nested : nested_signatures) {
    const uint64_t current = crc.value();
    crc.add_u64_le(nested);
    crc.add_u64_le(current);
  }
  return crc.value();
}

DsdlLibrary::DsdlLibrary(const std::vector<std::filesystem::path>& roots) {
  for (const auto& root : roots) {
    if (!std::filesystem::is_directory(root)) {
      throw std::runtime_error("DSDL root " + root.string() + " is not a folder");
    }
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".uavcan") continue;
      const auto relative = std::filesystem::relative(entry.path().parent_path(), root);
      std::string name_space;
      for (const auto& part : relative) {
        if (part == ".") continue;
        if (!name_space.empty()) name_space += '.';
        name_space += part.string();
      }
      std::string stem = entry.path().stem().string();
      const auto dot = stem.find('.');
      const std::string short_name = dot == std::string::npos ? stem : stem.substr(dot + 1);
      const std::string full_name = name_space.empty() ? short_name : name_space + "." + short_name;
      const auto [it, inserted] = files_.emplace(full_name, entry.path());
      if (!inserted) {
        throw std::runtime_error("DSDL type " + full_name + " is defined twice: " +
                                 it->second.string() + " and " + entry.path().string());
      }
    }
  }
}

std::vector<std::string> DsdlLibrary::type_names() const {
  std::vector<std::string> names;
  for (const auto& [name, path] : files_) names.push_back(name);
  return names;
}

const DsdlDefinition& DsdlLibrary::get(const std::string& full_name) {
  std::vector<std::string> stack;
  return parse(full_name, stack);
}

const DsdlDefinition& DsdlLibrary::parse(const std::string& full_name,
                                         std::vector<std::string>& stack) {
  if (const auto it = parsed_.find(full_name); it != parsed_.end()) return *it->second;
  const auto file_it = files_.find(full_name);
  if (file_it == files_.end()) throw std::runtime_error("no DSDL file defines " + full_name);
  if (std::find(stack.begin(), stack.end(), full_name) != stack.end()) {
    throw std::runtime_error("DSDL type " + full_name + " contains itself");
  }
  stack.push_back(full_name);
  const std::filesystem::path& file = file_it->second;

  auto def = std::make_unique<DsdlDefinition>();
  def->full_name = full_name;
  def->file = file;
  const std::string stem = file.stem().string();
  if (const auto dot = stem.find('.'); dot != std::string::npos) {
    const std::string id_text = stem.substr(0, dot);
    if (id_text.empty() || !std::all_of(id_text.begin(), id_text.end(), ::isdigit) ||
        id_text.size() > 5 || std::stoul(id_text) > 65535) {
      fail(file, 0, "file name must be [<data type ID>.]<Name>.uavcan, got " + file.filename().string());
    }
    def->default_dtid = static_cast<uint16_t>(std::stoul(id_text));
  }
  const std::string name_space = full_name.substr(0, full_name.rfind('.'));

  static const std::regex kConstant(
      R"(^(?:(?:saturated|truncated)\s+)?[A-Za-z][A-Za-z0-9_.]*\s+[A-Za-z_][A-Za-z0-9_]*\s*=\s*\S.*$)");
  static const std::regex kVoid(R"(^void([0-9]+)$)");
  static const std::regex kField(
      R"(^(?:(saturated|truncated)\s+)?([A-Za-z][A-Za-z0-9_.]*)(?:\[(<=|<)?([0-9]+)\])?\s+([A-Za-z_][A-Za-z0-9_]*)$)");
  static const std::regex kPrimitive(R"(^(bool|uint([0-9]+)|int([0-9]+)|float([0-9]+))$)");

  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot be read");
  bool in_response = false;
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    std::string line = trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    if (line == "---") {
      if (in_response) fail(file, line_number, "a second '---'");
      in_response = true;
      def->service = true;
      continue;
    }
    if (line[0] == '@') {
      if (line != "@union") fail(file, line_number, "unknown directive " + line);
      (in_response ? def->response_union : def->request_union) = true;
      continue;
    }
    if (std::regex_match(line, kConstant)) continue;
    std::smatch m;
    DsdlField field;
    if (std::regex_match(line, m, kVoid)) {
      const unsigned bits = static_cast<unsigned>(std::stoul(m[1]));
      if (bits < 1 || bits > 64) fail(file, line_number, "void width must be 1..64");
      field.normalized = line;
      field.max_bit_length = bits;
    } else if (std::regex_match(line, m, kField)) {
      const std::string cast = m[1].matched ? m[1].str() : "";
      const std::string type = m[2];
      std::string element;
      unsigned element_bits = 0;
      std::smatch p;
      if (std::regex_match(type, p, kPrimitive)) {
        unsigned bits = 1;
        if (p[2].matched) bits = static_cast<unsigned>(std::stoul(p[2]));
        if (p[3].matched) bits = static_cast<unsigned>(std::stoul(p[3]));
        if (p[4].matched) bits = static_cast<unsigned>(std::stoul(p[4]));
        if (p[4].matched && bits != 16 && bits != 32 && bits != 64) {
          fail(file, line_number, "float width must be 16, 32 or 64, not " + std::to_string(bits));
        }
        if (p[3].matched && (bits < 2 || bits > 64)) fail(file, line_number, "int width must be 2..64");
        if (p[2].matched && (bits < 1 || bits > 64)) fail(file, line_number, "uint width must be 1..64");
        if (cast == "truncated" && (type == "bool" || p[3].matched)) {
          fail(file, line_number, "truncated is allowed only for uint and float");
        }
        element = (cast.empty() ? "saturated" : cast) + " " + type;
        element_bits = bits;
      } else {
        if (!cast.empty()) fail(file, line_number, "a cast mode on a compound type");
        const std::string nested = type.find('.') == std::string::npos ? name_space + "." + type : type;
        if (!contains(nested)) {
          fail(file, line_number, "unknown type " + type + " (looked for " + nested + ")");
        }
        const DsdlDefinition& nested_def = parse(nested, stack);
        if (nested_def.service) fail(file, line_number, "a service type used as a field: " + nested);
        element = nested;
        element_bits = nested_def.max_bit_length;
        field.nested_type = nested;
      }
      field.name = m[5];
      field.normalized = element;
      field.max_bit_length = element_bits;
      if (m[4].matched) {
        unsigned long size = std::stoul(m[4]);
        const std::string op = m[3].matched ? m[3].str() : "";
        if (op == "<") {
          if (size == 0) fail(file, line_number, "array bound [<0]");
          --size;
        }
        if (size == 0) fail(file, line_number, "array of size 0");
        if (op.empty()) {
          field.normalized += "[" + std::to_string(size) + "]";
          field.max_bit_length = static_cast<unsigned>(size) * element_bits;
        } else {
          field.normalized += "[<=" + std::to_string(size) + "]";
          field.max_bit_length = bit_length_of(size) + static_cast<unsigned>(size) * element_bits;
        }
      }
      field.normalized += " " + field.name;
    } else {
      fail(file, line_number, "cannot parse '" + line + "'");
    }
    (in_response ? def->response : def->request).push_back(std::move(field));
  }

  auto join = [](const std::vector<DsdlField>& fields) {
    std::string text;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      text += (i == 0 ? "" : "\n") + fields[i].normalized;
    }
    return text + "\n";
  };
  std::string text = full_name + "\n";
  if (def->request_union) text += "\n@union\n";
  text += join(def->request);
  if (def->service) {
    text += "\n---\n";
    if (def->response_union) text += "\n@union\n";
    text += join(def->response);
  }
  def->normalized_definition = replace_all(replace_all(strip(text), "\n\n\n", "\n"), "\n\n", "\n");

  std::vector<uint64_t> nested;
  for (const auto* fields : {&def->request, &def->response}) {
    for (const auto& field : *fields) {
      if (!field.nested_type.empty()) nested.push_back(parse(field.nested_type, stack).signature);
    }
  }
  def->signature = dsdl_signature(def->normalized_definition, nested);

  auto max_bits = [](const std::vector<DsdlField>& fields, bool is_union) {
    unsigned total = 0;
    unsigned largest = 0;
    for (const auto& f : fields) {
      total += f.max_bit_length;
      largest = std::max(largest, f.max_bit_length);
    }
    if (!is_union) return total;
    return bit_length_of(fields.empty() ? 0 : fields.size() - 1) + largest;
  };
  def->max_bit_length = max_bits(def->request, def->request_union);
  def->response_max_bit_length = max_bits(def->response, def->response_union);

  stack.pop_back();
  const auto [it, inserted] = parsed_.emplace(full_name, std::move(def));
  return *it->second;
}

}  // namespace a3::bridge
