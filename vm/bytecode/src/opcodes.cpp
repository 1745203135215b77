// The opcode table of opcodes.def, and the decoding and naming helpers the bytecode files share.
#include <array>
#include <iterator>
#include <string_view>

#include "meldvm/bytecode_internal.hpp"
#include "meldvm/program.hpp"

namespace meldvm {

namespace {

constexpr OpcodeInfo kTable[] = {
#define OP(name, operands, meaning) {#name, operands, meaning},
#include "meldvm/opcodes.def"
#undef OP
};
static_assert(std::size(kTable) == kOpcodeCount);

// Every decoder (here, the verifier, the disassembler, the interpreter) relies on these, so a typo
// in opcodes.def must not compile.
constexpr bool wellFormed(std::string_view ops) {
  for (std::size_t i = 0; i < ops.size(); ++i) {
    if (std::string_view("rifbnlsSPTKGIDFXBUEJ*W").find(ops[i]) == std::string_view::npos) return false;
    if ((ops[i] == '*' || ops[i] == 'W') && i + 1 != ops.size()) return false;
  }
  return true;
}
constexpr bool allWellFormed() {
  for (const OpcodeInfo& info : kTable)
    if (!wellFormed(info.operands)) return false;
  return true;
}
static_assert(allWellFormed(), "opcodes.def: unknown operand letter, or '*' or 'W' not last");

// Returned for values outside the table, so that printing a bad opcode is not undefined.
constexpr OpcodeInfo kInvalid{"?", "", "not an opcode"};

}  // namespace

const OpcodeInfo& opcodeInfo(Opcode op) {
  const auto i = std::uint32_t(op);
  return i < kOpcodeCount ? kTable[i] : kInvalid;
}

namespace {

// The meaning of an instruction that computes a register says so first: "r = ...", "r0 = ...",
// "int r0 = ...", "list register = ...", "struct r0 of type T = ...". The register written is
// then the first register operand.
constexpr int writtenRegisterOf(const OpcodeInfo& info) {
  std::string_view m = info.meaning;
  for (std::string_view type : {"int ", "float ", "bool ", "list ", "struct ", "string ", "node "})
    if (m.starts_with(type)) {
      m.remove_prefix(type.size());
      break;
    }
  if (!(m.starts_with("r = ") || m.starts_with("r0 = ") || m.starts_with("register = ") ||
        m.starts_with("r0 of type")))
    return -1;
  const std::string_view ops = info.operands;
  for (std::size_t i = 0; i < ops.size(); ++i)
    if (std::string_view("rifbnls").find(ops[i]) != std::string_view::npos) return int(i);
  return -1;
}

}  // namespace

int writtenRegisterOperand(Opcode op) {
  static const std::array<int, kOpcodeCount> kWritten = [] {
    std::array<int, kOpcodeCount> w{};
    for (std::uint32_t i = 0; i < kOpcodeCount; ++i) w[i] = writtenRegisterOf(kTable[i]);
    return w;
  }();
  const auto i = std::uint32_t(op);
  return i < kOpcodeCount ? kWritten[i] : -1;
}

namespace detail {

std::size_t instructionLength(std::span<const std::uint32_t> code, std::size_t pos, std::string& why) {
  if (code[pos] >= kOpcodeCount) {
    why = "unknown opcode " + std::to_string(code[pos]);
    return 0;
  }
  // The operand strings measured once (a loader walks millions of instructions).
  static const std::array<std::string_view, kOpcodeCount> kOperands = [] {
    std::array<std::string_view, kOpcodeCount> v;
    for (std::uint32_t i = 0; i < kOpcodeCount; ++i) v[i] = kTable[i].operands;
    return v;
  }();
  const std::string_view ops = kOperands[code[pos]];
  std::size_t p = pos + 1;
  for (char letter : ops) {
    const std::size_t words = letter == 'D' ? 2 : 1;
    if (code.size() - p < words) {
      why = "operands run past the end of the block";
      return 0;
    }
    if (letter == '*' || letter == 'W') {
      const std::uint32_t count = code[p++];
      if (count > code.size() - p) {
        why = (letter == '*' ? "register count " : "data word count ") + std::to_string(count) +
              " runs past the end of the block";
        return 0;
      }
      p += count;
    } else {
      p += words;
    }
  }
  return p - pos;
}

std::string typeName(const TypeTable& types, TypeId t) {
  if (t >= types.size()) return "<unknown type " + std::to_string(t) + ">";
  // Deep nesting only comes from hostile files: show the outer levels, which is what a message needs.
  constexpr int kMaxDepth = 8;
  std::string prefix;
  for (int depth = 0;; ++depth) {
    const TypeKind k = types.kind(t);
    if (k != TypeKind::List && k != TypeKind::Array && k != TypeKind::Set) break;
    if (depth == kMaxDepth) return prefix + "...";
    prefix += k == TypeKind::List ? "list " : k == TypeKind::Array ? "array " : "set ";
    t = types.element(t);
  }
  if (types.kind(t) != TypeKind::Struct) return prefix + types.name(t);
  std::string s = prefix + ":(";
  bool first = true;
  for (TypeId f : types.fields(t)) {
    if (!first) s += ", ";
    first = false;
    // Fields are shown one level deep only, for the same reason.
    s += types.kind(f) == TypeKind::Struct ? ":(...)" : typeName(types, f);
  }
  return s + ")";
}

const char* sectionName(std::uint32_t tag) {
  static constexpr const char* kNames[] = {"?",       "types",      "predicates", "nodes",  "strings",
                                           "globals", "functions",  "externs",    "rules",  "processes",
                                           "axioms",  "scheduling", "indexes",    "sources"};
  return tag <= kSectionCount ? kNames[tag] : "?";
}

}  // namespace detail

}  // namespace meldvm
