#include "simcore/csg.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

namespace simcore {

struct CsgNode {
  enum class Kind {
    Cube,
    Sphere,
    Cylinder,
    Cone,
    Torus,
    Translate,
    Rotate,
    Scale,
    Color,
    Union,
    Difference,
    Intersection
  };
  Kind kind = Kind::Union;
  Vec3 v;                      // cube size; translate, scale: the vector
  double a = 0, b = 0, c = 0;  // sphere: a = radius; cylinder/cone: height, bottom, top; torus: radii
  bool center = false;
  double rot[9]{}, inv[9]{};  // rotate: the matrix (row-major) and its inverse
  std::uint32_t color = 0;
  std::vector<std::unique_ptr<CsgNode>> children;
};

namespace {

using Kind = CsgNode::Kind;
constexpr int kMaxDepth = 200;              // nesting of shapes, expressions and module calls
constexpr std::size_t kMaxShapes = 100000;  // modules calling modules twice would grow without bound

struct Token {
  enum Type { End, Number, Name, Punct } type = End;
  std::string text;
  double number = 0;
  std::size_t offset = 0;
};

std::vector<Token> tokenize(std::string_view s) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (true) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i + 1 < s.size() && s[i] == '/' && s[i + 1] == '/') {
      while (i < s.size() && s[i] != '\n') ++i;
      continue;
    }
    if (i + 1 < s.size() && s[i] == '/' && s[i + 1] == '*') {
      const std::size_t end = s.find("*/", i + 2);
      if (end == std::string_view::npos) throw CsgError(i, "unterminated comment");
      i = end + 2;
      continue;
    }
    Token t;
    t.offset = i;
    if (i >= s.size()) {
      out.push_back(t);
      return out;
    }
    const char c = s[i];
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
      std::string text(s.substr(i, std::min<std::size_t>(64, s.size() - i)));
      char* end = nullptr;
      t.number = std::strtod(text.c_str(), &end);
      const std::size_t length = std::size_t(end - text.c_str());
      t.type = Token::Number;
      t.text = text.substr(0, length);
      i += length;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '$') {
      std::size_t j = i + 1;
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_' || s[j] == '$'))
        ++j;
      t.type = Token::Name;
      t.text = std::string(s.substr(i, j - i));
      i = j;
    } else if (std::string_view("()[]{},;=+-*/^").find(c) != std::string_view::npos) {
      t.type = Token::Punct;
      t.text = std::string(1, c);
      ++i;
    } else {
      throw CsgError(i, std::string("unexpected character '") + c + "'");
    }
    out.push_back(std::move(t));
  }
}

double degrees(double a) { return a * M_PI / 180.0; }

// VisibleSim's rotate: Rx(x) * Ry(y) * Rz(z), points turned by the inverse.
void rotationMatrices(const Vec3& angles, double* rot, double* inv) {
  const double cx = std::cos(degrees(angles.x)), sx = std::sin(degrees(angles.x));
  const double cy = std::cos(degrees(angles.y)), sy = std::sin(degrees(angles.y));
  const double cz = std::cos(degrees(angles.z)), sz = std::sin(degrees(angles.z));
  const double rx[9] = {1, 0, 0, 0, cx, -sx, 0, sx, cx};
  const double ry[9] = {cy, 0, sy, 0, 1, 0, -sy, 0, cy};
  const double rz[9] = {cz, -sz, 0, sz, cz, 0, 0, 0, 1};
  auto mul = [](const double* p, const double* q, double* r) {
    for (int l = 0; l < 3; ++l)
      for (int c = 0; c < 3; ++c)
        r[l * 3 + c] = p[l * 3] * q[c] + p[l * 3 + 1] * q[3 + c] + p[l * 3 + 2] * q[6 + c];
  };
  double rxy[9];
  mul(rx, ry, rxy);
  mul(rxy, rz, rot);
  for (int l = 0; l < 3; ++l)
    for (int c = 0; c < 3; ++c) inv[l * 3 + c] = rot[c * 3 + l];  // a rotation's inverse: its transpose
}

Vec3 apply(const double* m, const Vec3& p) {
  return Vec3{m[0] * p.x + m[1] * p.y + m[2] * p.z, m[3] * p.x + m[4] * p.y + m[5] * p.z,
              m[6] * p.x + m[7] * p.y + m[8] * p.z};
}

class Parser {
 public:
  Parser(std::string_view content, std::vector<std::string>& warnings)
      : tokens_(tokenize(content)), warnings_(warnings) {}

  std::unique_ptr<CsgNode> program() {
    std::unique_ptr<CsgNode> root;
    while (peek().type != Token::End) {
      std::unique_ptr<CsgNode> shape = statement();
      if (!shape) continue;
      if (!root)
        root = std::move(shape);
      else
        warnings_.push_back(
            "a second top-level shape is ignored (only the first is the solid): combine them in union() { "
            "... }");
    }
    if (!root) throw CsgError(peek().offset, "no shape (cube, sphere, cylinder, torus, union, ...)");
    return root;
  }

 private:
  struct Module {
    std::vector<std::string> params;
    std::size_t begin = 0, end = 0;  // body tokens [begin, end)
  };

  const Token& peek(std::size_t ahead = 0) const {
    return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)];
  }
  bool isPunct(const char* p, std::size_t ahead = 0) const {
    return peek(ahead).type == Token::Punct && peek(ahead).text == p;
  }
  [[noreturn]] void fail(const std::string& message) const { throw CsgError(peek().offset, message); }
  void expect(const char* p) {
    if (!isPunct(p)) fail(std::string("expected '") + p + "'" + found());
    ++pos_;
  }
  std::string found() const {
    return peek().type == Token::End ? " at the end of the text" : ", found '" + peek().text + "'";
  }
  std::string name() {
    if (peek().type != Token::Name) fail("expected a name" + found());
    return tokens_[pos_++].text;
  }
  void enter() {
    if (++depth_ > kMaxDepth) fail("nested too deeply");
  }

  // A shape, or nothing for a definition (variable, module).
  std::unique_ptr<CsgNode> statement() {
    enter();
    std::unique_ptr<CsgNode> out;
    if (peek().type == Token::Name && isPunct("=", 1)) {
      const std::string var = name();
      expect("=");
      variables_[var] = expr();
      expect(";");
    } else if (peek().type == Token::Name && peek().text == "module") {
      ++pos_;
      defineModule();
    } else if (isPunct(";")) {
      ++pos_;  // an empty statement
    } else {
      out = shape();
    }
    --depth_;
    return out;
  }

  void defineModule() {
    const std::string id = name();
    Module m;
    expect("(");
    while (!isPunct(")")) {
      m.params.push_back(name());
      if (!isPunct(")")) expect(",");
    }
    expect(")");
    expect("{");
    m.begin = pos_;
    for (int open = 1; open > 0; ++pos_) {
      if (peek().type == Token::End) fail("module '" + id + "': '}' missing");
      if (isPunct("{")) ++open;
      if (isPunct("}")) --open;
    }
    m.end = pos_ - 1;
    modules_[id] = m;
  }

  std::unique_ptr<CsgNode> node(Kind k) {
    if (++shapes_ > kMaxShapes) fail("the solid has more than " + std::to_string(kMaxShapes) + " shapes");
    auto n = std::make_unique<CsgNode>();
    n->kind = k;
    return n;
  }

  std::unique_ptr<CsgNode> shape() {
    enter();
    const std::string word = name();
    std::unique_ptr<CsgNode> n;
    if (word == "union" || word == "difference" || word == "intersection") {
      n = node(word == "union" ? Kind::Union : word == "difference" ? Kind::Difference : Kind::Intersection);
      expect("(");
      expect(")");
      expect("{");
      while (!isPunct("}")) {
        if (peek().type == Token::End) fail("'}' missing after " + word + "() {");
        if (auto child = statement()) n->children.push_back(std::move(child));
      }
      ++pos_;
      if (isPunct(";")) ++pos_;
    } else if (word == "translate" || word == "rotate" || word == "scale" || word == "color") {
      n = node(word == "translate" ? Kind::Translate
               : word == "rotate"  ? Kind::Rotate
               : word == "scale"   ? Kind::Scale
                                   : Kind::Color);
      expect("(");
      n->v = vector();
      expect(")");
      if (n->kind == Kind::Rotate) rotationMatrices(n->v, n->rot, n->inv);
      if (n->kind == Kind::Color) {
        auto channel = [](double x) { return std::uint32_t(std::clamp(x, 0.0, 255.0)); };
        n->color = channel(n->v.x) << 16 | channel(n->v.y) << 8 | channel(n->v.z);
      }
      n->children.push_back(shape());
    } else if (word == "cube") {
      n = node(Kind::Cube);
      expect("(");
      n->v = vector();
      if (isPunct(",")) {
        ++pos_;
        n->center = boolean();
      }
      end();
    } else if (word == "sphere") {
      n = node(Kind::Sphere);
      expect("(");
      n->a = expr();
      end();
    } else if (word == "cylinder") {
      n = node(Kind::Cylinder);
      expect("(");
      n->a = expr();
      expect(",");
      n->b = n->c = expr();
      if (isPunct(",")) {
        ++pos_;
        n->c = expr();
        if (isPunct(",")) {
          ++pos_;
          n->center = boolean();
        }
      }
      if (n->b != n->c) n->kind = Kind::Cone;
      end();
    } else if (word == "torus") {
      n = node(Kind::Torus);
      expect("(");
      n->a = expr();
      expect(",");
      n->b = expr();
      end();
    } else if (auto m = modules_.find(word); m != modules_.end()) {
      n = callModule(word, m->second);
    } else {
      pos_--;
      fail("unknown shape '" + word + "'");
    }
    --depth_;
    return n;
  }

  void end() {
    expect(")");
    expect(";");
  }

  std::unique_ptr<CsgNode> callModule(const std::string& id, const Module& m) {
    expect("(");
    std::vector<double> args;
    while (!isPunct(")")) {
      args.push_back(expr());
      if (!isPunct(")")) expect(",");
    }
    expect(")");
    expect(";");
    if (args.size() != m.params.size())
      fail("module '" + id + "' takes " + std::to_string(m.params.size()) + " arguments, " +
           std::to_string(args.size()) + " given");
    const std::map<std::string, double> saved = variables_;
    for (std::size_t i = 0; i < args.size(); ++i) variables_[m.params[i]] = args[i];
    const std::size_t resume = pos_;
    pos_ = m.begin;
    auto body = node(Kind::Union);
    while (pos_ < m.end)
      if (auto child = statement()) body->children.push_back(std::move(child));
    pos_ = resume;
    variables_ = saved;
    // VisibleSim keeps the module's first shape.
    if (body->children.empty()) fail("module '" + id + "' makes no shape");
    return std::move(body->children.front());
  }

  Vec3 vector() {
    expect("[");
    Vec3 v;
    v.x = expr();
    expect(",");
    v.y = expr();
    expect(",");
    v.z = expr();
    expect("]");
    return v;
  }

  bool boolean() {
    const std::string w = name();
    if (w == "true") return true;
    if (w == "false") return false;
    pos_--;
    fail("expected true or false, found '" + w + "'");
  }

  double expr() {
    enter();
    double v = term();
    while (isPunct("+") || isPunct("-")) {
      const bool plus = isPunct("+");
      ++pos_;
      const double r = term();
      v = plus ? v + r : v - r;
    }
    --depth_;
    return v;
  }
  double term() {
    double v = unary();
    while (isPunct("*") || isPunct("/")) {
      const bool times = isPunct("*");
      ++pos_;
      const double r = unary();
      v = times ? v * r : v / r;
    }
    return v;
  }
  double unary() {
    if (isPunct("-")) {
      ++pos_;
      enter();
      const double v = -unary();
      --depth_;
      return v;
    }
    if (isPunct("+")) {
      ++pos_;
      return unary();
    }
    const double base = primary();
    if (!isPunct("^")) return base;
    ++pos_;
    enter();
    const double exponent = unary();  // right-associative
    --depth_;
    return std::pow(base, exponent);
  }
  double primary() {
    if (peek().type == Token::Number) return tokens_[pos_++].number;
    if (isPunct("(")) {
      ++pos_;
      const double v = expr();
      expect(")");
      return v;
    }
    const std::string id = name();
    if (isPunct("(")) return call(id);
    if (id == "_pi") return M_PI;
    if (id == "_e") return M_E;
    auto it = variables_.find(id);
    if (it == variables_.end()) {
      pos_--;
      fail("unknown variable '" + id + "'");
    }
    return it->second;
  }
  double call(const std::string& f) {
    expect("(");
    std::vector<double> a;
    while (!isPunct(")")) {
      a.push_back(expr());
      if (!isPunct(")")) expect(",");
    }
    expect(")");
    if (f == "min" || f == "max") {
      if (a.size() < 2) fail("'" + f + "' takes two or more arguments");
      return f == "min" ? *std::min_element(a.begin(), a.end()) : *std::max_element(a.begin(), a.end());
    }
    static const std::map<std::string, double (*)(double)> kOne = {
        {"sin", [](double x) { return std::sin(x); }},
        {"cos", [](double x) { return std::cos(x); }},
        {"tan", [](double x) { return std::tan(x); }},
        {"asin", [](double x) { return std::asin(x); }},
        {"acos", [](double x) { return std::acos(x); }},
        {"atan", [](double x) { return std::atan(x); }},
        {"sinh", [](double x) { return std::sinh(x); }},
        {"cosh", [](double x) { return std::cosh(x); }},
        {"tanh", [](double x) { return std::tanh(x); }},
        {"sqrt", [](double x) { return std::sqrt(x); }},
        {"abs", [](double x) { return std::fabs(x); }},
        {"exp", [](double x) { return std::exp(x); }},
        {"ln", [](double x) { return std::log(x); }},
        {"log", [](double x) { return std::log(x); }},
        {"log2", [](double x) { return std::log2(x); }},
        {"log10", [](double x) { return std::log10(x); }},
        {"sign", [](double x) { return double((x > 0) - (x < 0)); }},
        {"rint", [](double x) { return std::rint(x); }}};
    auto it = kOne.find(f);
    if (it == kOne.end()) fail("unknown function '" + f + "'");
    if (a.size() != 1) fail("'" + f + "' takes one argument");
    return it->second(a[0]);
  }

  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  std::size_t shapes_ = 0;
  std::map<std::string, double> variables_;
  std::map<std::string, Module> modules_;
  std::vector<std::string>& warnings_;
};

bool insideNode(const CsgNode& n, const Vec3& p, std::optional<std::uint32_t>& color) {
  auto anyChild = [&](const Vec3& q) {
    for (const auto& c : n.children)
      if (insideNode(*c, q, color)) return true;
    return false;
  };
  switch (n.kind) {
    case Kind::Cube:
      if (n.center)
        return p.x <= n.v.x / 2 && p.x >= -n.v.x / 2 && p.y <= n.v.y / 2 && p.y >= -n.v.y / 2 &&
               p.z <= n.v.z / 2 && p.z >= -n.v.z / 2;
      return p.x >= 0 && p.x <= n.v.x && p.y >= 0 && p.y <= n.v.y && p.z >= 0 && p.z <= n.v.z;
    case Kind::Sphere:
      return p.x * p.x + p.y * p.y + p.z * p.z <= n.a * n.a;
    case Kind::Cylinder: {
      const double low = n.center ? -n.a / 2 : 0, high = n.center ? n.a / 2 : n.a;
      return p.z >= low && p.z <= high && std::sqrt(p.x * p.x + p.y * p.y) <= n.b;
    }
    case Kind::Cone: {
      const double y = n.center ? p.z + n.a / 2 : p.z;
      return y >= 0 && y <= n.a && std::sqrt(p.x * p.x + p.y * p.y) <= n.b + y * (n.c - n.b) / n.a;
    }
    case Kind::Torus: {
      const double x = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);  // VisibleSim's (3D) distance
      return (x - n.a) * (x - n.a) + p.z * p.z < n.b * n.b || (x + n.a) * (x + n.a) + p.z * p.z < n.b * n.b;
    }
    case Kind::Translate:
      return anyChild(Vec3{p.x - n.v.x, p.y - n.v.y, p.z - n.v.z});
    case Kind::Rotate:
      return anyChild(apply(n.inv, p));
    case Kind::Scale:
      return anyChild(Vec3{p.x / n.v.x, p.y / n.v.y, p.z / n.v.z});
    case Kind::Color:
      if (!anyChild(p)) return false;
      color = n.color;  // after the child's: the outermost color wins
      return true;
    case Kind::Union:
      return anyChild(p);
    case Kind::Difference:
      if (n.children.empty() || !insideNode(*n.children[0], p, color)) return false;
      for (std::size_t i = 1; i < n.children.size(); ++i)
        if (insideNode(*n.children[i], p, color)) return false;
      return true;
    case Kind::Intersection:
      for (const auto& c : n.children)
        if (!insideNode(*c, p, color)) return false;
      return !n.children.empty();
  }
  return false;
}

CsgBox boxOf(const CsgNode& n) {
  CsgBox bb;  // zero, as VisibleSim's default box
  auto lastChild = [&] {
    for (const auto& c : n.children) bb = boxOf(*c);
  };
  switch (n.kind) {
    case Kind::Cube:
      if (n.center) return CsgBox{{-n.v.x / 2, -n.v.y / 2, -n.v.z / 2}, {n.v.x / 2, n.v.y / 2, n.v.z / 2}};
      return CsgBox{{0, 0, 0}, n.v};
    case Kind::Sphere:
      return CsgBox{{-n.a, -n.a, -n.a}, {n.a, n.a, n.a}};
    case Kind::Cylinder:
    case Kind::Cone: {
      const double r = std::max(n.b, n.c);
      return n.center ? CsgBox{{-r, -r, -n.a / 2}, {r, r, n.a / 2}} : CsgBox{{-r, -r, 0}, {r, r, n.a}};
    }
    case Kind::Torus:
      return CsgBox{{-n.a, -n.a, -n.b}, {n.a, n.a, n.b}};
    case Kind::Translate:
      lastChild();
      return CsgBox{{bb.min.x + n.v.x, bb.min.y + n.v.y, bb.min.z + n.v.z},
                    {bb.max.x + n.v.x, bb.max.y + n.v.y, bb.max.z + n.v.z}};
    case Kind::Rotate: {
      lastChild();
      const Vec3 a = apply(n.rot, bb.min), b = apply(n.rot, bb.max);
      return CsgBox{{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)},
                    {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}};
    }
    case Kind::Scale:
      lastChild();
      return CsgBox{{bb.min.x * n.v.x, bb.min.y * n.v.y, bb.min.z * n.v.z},
                    {bb.max.x * n.v.x, bb.max.y * n.v.y, bb.max.z * n.v.z}};
    case Kind::Color:
      lastChild();
      return bb;
    case Kind::Union:
      for (std::size_t i = 0; i < n.children.size(); ++i) {
        const CsgBox c = boxOf(*n.children[i]);
        bb = i == 0 ? c
                    : CsgBox{{std::min(bb.min.x, c.min.x), std::min(bb.min.y, c.min.y),
                              std::min(bb.min.z, c.min.z)},
                             {std::max(bb.max.x, c.max.x), std::max(bb.max.y, c.max.y),
                              std::max(bb.max.z, c.max.z)}};
      }
      return bb;
    case Kind::Difference:
    case Kind::Intersection:
      return n.children.empty() ? bb : boxOf(*n.children[0]);
  }
  return bb;
}

}  // namespace

CsgSolid CsgSolid::parse(std::string_view content) {
  CsgSolid s;
  Parser parser(content, s.warnings_);
  s.root_ = parser.program();
  return s;
}

CsgSolid::CsgSolid(CsgSolid&&) noexcept = default;
CsgSolid& CsgSolid::operator=(CsgSolid&&) noexcept = default;
CsgSolid::~CsgSolid() = default;

bool CsgSolid::inside(const Vec3& p, std::optional<std::uint32_t>& color) const {
  return insideNode(*root_, p, color);
}

CsgBox CsgSolid::boundingBox() const { return boxOf(*root_); }

}  // namespace simcore
