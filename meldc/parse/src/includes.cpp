#include "meldc/includes.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <system_error>

#include "meldc/case_folding.hpp"
#include "meldc/parser.hpp"
#include "support/program_dir.hpp"

namespace meldc {

namespace fs = std::filesystem;

namespace {

class IncludeLoader {
 public:
  IncludeLoader(const std::vector<std::string>& dirs, SourceManager& sources, Diagnostics& diag,
                bool groundFacts)
      : dirs_(dirs), sources_(sources), diag_(diag), groundFacts_(groundFacts) {}

  // Loads and merges one file; `from` is the include that names it (invalid for the main file).
  std::optional<ast::Program> load(const std::string& path, SourceLoc from) {
    uint32_t file = 0;
    readOk_ = false;
    std::error_code ec;
    const bool directory = fs::is_directory(path, ec);
    if (directory || !sources_.load(path, file)) {
      const std::string why = directory ? "': it is a directory, not a Meld file" : "'";
      if (from.valid())
        diag_.error(from, "cannot read included file '" + path + why);
      else
        diag_.errorNoLoc("cannot read '" + path + why);
      return std::nullopt;
    }
    std::string key = canonical(path);
    active_.insert(key);
    seen_.insert(key);
    readOk_ = true;
    std::optional<ast::Program> program = parseFile(file, sources_, diag_, groundFacts_);
    if (!program) {
      active_.erase(key);
      return std::nullopt;
    }
    program->mainFile = file;
    std::vector<ast::Program> included;
    for (ast::IncludeDecl& inc : program->includes) {
      std::string resolved;
      if (!resolve(path, inc.path, resolved)) {
        diag_.error(inc.loc, "cannot find included file '" + inc.path + "'" + searched(path));
        continue;
      }
      std::string incKey = canonical(resolved);
      if (active_.count(incKey)) {
        diag_.error(inc.loc, "include cycle: '" + resolved + "' is already being included");
        continue;
      }
      if (seen_.count(incKey)) continue;  // included once already
      if (auto sub = load(resolved, inc.loc)) {
        inc.file = sub->mainFile;
        included.push_back(std::move(*sub));
      } else if (readOk_)
        diag_.note(inc.loc, "in the file included here");
    }
    active_.erase(key);
    for (auto it = included.rbegin(); it != included.rend(); ++it) program->append(std::move(*it));
    return program;
  }

 private:
  static std::string canonical(const std::string& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::path(path), ec);
    return ec ? fs::path(path).lexically_normal().string() : p.string();
  }

  static bool isFile(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
  }

  bool resolve(const std::string& includer, const std::string& name, std::string& out) const {
    fs::path rel(name);
    if (rel.is_absolute()) {
      out = rel.lexically_normal().string();
      return isFile(rel);
    }
    fs::path first = (fs::path(includer).parent_path() / rel).lexically_normal();
    if (isFile(first)) {
      out = first.string();
      return true;
    }
    for (const std::string& dir : dirs_) {
      fs::path candidate = (fs::path(dir) / rel).lexically_normal();
      if (isFile(candidate)) {
        out = candidate.string();
        return true;
      }
    }
    return false;
  }

  std::string searched(const std::string& includer) const {
    std::string dir = fs::path(includer).parent_path().string();
    std::string out = " (searched " + (dir.empty() ? std::string(".") : dir);
    for (const std::string& d : dirs_) out += ", " + d;
    return out + ")";
  }

  const std::vector<std::string>& dirs_;
  SourceManager& sources_;
  Diagnostics& diag_;
  bool groundFacts_;
  std::set<std::string> active_;  // files on the current include chain
  std::set<std::string> seen_;    // every file loaded so far
  bool readOk_ = false;           // the last load() could read its file (errors were in its text)
};

bool sameType(const ast::TypeExpr& a, const ast::TypeExpr& b) {
  if (a.kind != b.kind || !sameName(a.name, b.name) || a.args.size() != b.args.size()) return false;
  for (std::size_t i = 0; i < a.args.size(); ++i)
    if (!sameType(a.args[i], b.args[i])) return false;
  return true;
}

// Same predicate, same modifiers, same field types and aggregates (argument names are comments).
bool sameDeclaration(const ast::PredicateDecl& a, const ast::PredicateDecl& b) {
  if (!sameName(a.name, b.name) || a.linear != b.linear || a.route != b.route || a.action != b.action ||
      a.imported || b.imported || a.fields.size() != b.fields.size())
    return false;
  for (std::size_t i = 0; i < a.fields.size(); ++i)
    if (a.fields[i].agg != b.fields[i].agg || !sameType(a.fields[i].type, b.fields[i].type)) return false;
  return true;
}

// A program that declares `neighbor` or `vacant` itself may still include the target's file,
// which declares them too: a declaration identical to an earlier one (in merged order) is dropped.
// Different declarations of one name stay, for the name pass to report.
void dropIdenticalRedeclarations(ast::Program& p) {
  std::vector<ast::PredicateDecl> kept;
  for (ast::PredicateDecl& d : p.predicates) {
    const bool again = std::any_of(kept.begin(), kept.end(),
                                   [&](const ast::PredicateDecl& k) { return sameDeclaration(k, d); });
    if (!again) kept.push_back(std::move(d));
  }
  p.predicates = std::move(kept);
}

}  // namespace

std::optional<ast::Program> loadProgram(const std::string& mainPath,
                                        const std::vector<std::string>& includeDirs, SourceManager& sources,
                                        Diagnostics& diag, bool groundFacts) {
  IncludeLoader loader(includeDirs, sources, diag, groundFacts);
  std::optional<ast::Program> program = loader.load(mainPath, SourceLoc{});
  if (program) dropIdenticalRedeclarations(*program);
  return program;
}

std::string defaultStdlibDir() {
  if (const char* env = std::getenv("MELD_STDLIB")) return env;
  // An installed program: <prefix>/bin/meldc (or meld, vsim ...) next to <prefix>/share/meld/stdlib.
  if (const std::filesystem::path bin = support::runningProgramDir(); !bin.empty()) {
    const std::filesystem::path installed = bin.parent_path() / "share" / "meld" / "stdlib";
    std::error_code ec;
    if (std::filesystem::is_regular_file(installed / "common.meld", ec)) return installed.string();
  }
#ifdef MELD_STDLIB_DIR
  return MELD_STDLIB_DIR;
#else
  return "";  // built without the definition (not through meldc/CMakeLists.txt)
#endif
}

}  // namespace meldc
